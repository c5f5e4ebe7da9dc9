// See renderdoc_hook.h. The library is looked up with RTLD_NOLOAD: the app never loads RenderDoc
// itself, it only talks to one that was injected.
#include "renderdoc_hook.h"

#include <dlfcn.h>
#include <renderdoc_app.h>

namespace fd {

namespace {

// API 1.1.2 has StartFrameCapture/EndFrameCapture with a device pointer, all that is used here.
RENDERDOC_API_1_1_2* renderdoc() {
  static RENDERDOC_API_1_1_2* api = []() -> RENDERDOC_API_1_1_2* {
    void* library = dlopen("librenderdoc.so", RTLD_NOW | RTLD_NOLOAD);
    if (!library) return nullptr;
    auto get_api = reinterpret_cast<pRENDERDOC_GetAPI>(dlsym(library, "RENDERDOC_GetAPI"));
    void* table = nullptr;
    if (!get_api || get_api(eRENDERDOC_API_Version_1_1_2, &table) != 1) return nullptr;
    return static_cast<RENDERDOC_API_1_1_2*>(table);
  }();
  return api;
}

}  // namespace

bool renderdoc_present() { return renderdoc() != nullptr; }

void renderdoc_begin(VkInstance instance) {
  if (renderdoc()) renderdoc()->StartFrameCapture(RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(instance), nullptr);
}

bool renderdoc_end(VkInstance instance) {
  if (!renderdoc()) return true;
  return renderdoc()->EndFrameCapture(RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(instance), nullptr) == 1;
}

}  // namespace fd
