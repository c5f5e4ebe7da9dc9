// See renderdoc.h. RTLD_NOLOAD: RenderDoc's library is used only if the process already has it.
#include "renderdoc.h"

#include <dlfcn.h>
#include <renderdoc_app.h>

namespace td {

namespace {

RENDERDOC_API_1_1_2* table() {
  static RENDERDOC_API_1_1_2* const api = []() -> RENDERDOC_API_1_1_2* {
    void* handle = dlopen("librenderdoc.so", RTLD_NOW | RTLD_NOLOAD);
    if (!handle) return nullptr;
    auto get_api = reinterpret_cast<pRENDERDOC_GetAPI>(dlsym(handle, "RENDERDOC_GetAPI"));
    void* found = nullptr;
    return get_api && get_api(eRENDERDOC_API_Version_1_1_2, &found) == 1 ? static_cast<RENDERDOC_API_1_1_2*>(found) : nullptr;
  }();
  return api;
}

}  // namespace

bool renderdoc_present() { return table() != nullptr; }

void renderdoc_frame_begin(VkInstance instance) {
  if (RENDERDOC_API_1_1_2* api = table()) api->StartFrameCapture(RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(instance), nullptr);
}

bool renderdoc_frame_end(VkInstance instance) {
  RENDERDOC_API_1_1_2* api = table();
  return !api || api->EndFrameCapture(RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(instance), nullptr) == 1;
}

}  // namespace td
