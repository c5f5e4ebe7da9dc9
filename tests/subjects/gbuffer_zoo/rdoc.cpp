// See rdoc.h. RTLD_NOLOAD: look for an injected RenderDoc, never load one.
#include "rdoc.h"

#include <dlfcn.h>
#include <renderdoc_app.h>

namespace zoo {

namespace {

RENDERDOC_API_1_4_1* api() {
  static RENDERDOC_API_1_4_1* table = []() -> RENDERDOC_API_1_4_1* {
    void* lib = dlopen("librenderdoc.so", RTLD_NOW | RTLD_NOLOAD);
    if (lib == nullptr) return nullptr;
    auto get = reinterpret_cast<pRENDERDOC_GetAPI>(dlsym(lib, "RENDERDOC_GetAPI"));
    void* out = nullptr;
    if (get == nullptr || get(eRENDERDOC_API_Version_1_4_1, &out) != 1) return nullptr;
    return static_cast<RENDERDOC_API_1_4_1*>(out);
  }();
  return table;
}

}  // namespace

bool rdoc_attached() { return api() != nullptr; }

void rdoc_start(VkInstance instance) {
  if (api()) api()->StartFrameCapture(RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(instance), nullptr);
}

bool rdoc_end(VkInstance instance) {
  return !api() || api()->EndFrameCapture(RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(instance), nullptr) == 1;
}

}  // namespace zoo
