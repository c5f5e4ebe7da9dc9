// The RenderDoc in-application API, found in the process (never loaded by gblens itself).
#include "renderer/vk/renderdoc_capture.h"

#include <dlfcn.h>
#include <renderdoc_app.h>

#include <vector>

#include "renderer/vk/context.h"

namespace gb {

// 1.4.0 has everything used here (Start/End/DiscardFrameCapture, GetCapture, the path template);
// asking for the oldest version that does keeps older RenderDoc builds working.
static RENDERDOC_API_1_4_0* api() {
  static RENDERDOC_API_1_4_0* const loaded = []() -> RENDERDOC_API_1_4_0* {
    // RTLD_NOLOAD: only a library RenderDoc injected (LD_PRELOAD or its Vulkan layer) is used.
    void* lib = dlopen("librenderdoc.so", RTLD_NOW | RTLD_NOLOAD);
    if (!lib) return nullptr;
    auto getApi = reinterpret_cast<pRENDERDOC_GetAPI>(dlsym(lib, "RENDERDOC_GetAPI"));
    void* out = nullptr;
    if (!getApi || getApi(eRENDERDOC_API_Version_1_4_0, &out) != 1) return nullptr;
    return static_cast<RENDERDOC_API_1_4_0*>(out);
  }();
  return loaded;
}

bool underRenderDoc() { return api() != nullptr; }

void setRenderDocCaptureTemplate(const std::string& pathTemplate) {
  if (api()) api()->SetCaptureFilePathTemplate(pathTemplate.c_str());
}

RenderDocCapture::RenderDocCapture(const GpuContext& ctx, bool enabled) {
  if (!enabled || !api() || !ctx.instance) return;
  device_ = RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE(ctx.instance);
  // No window: a headless frame has none, and the viewer's frame is named by its device alone.
  api()->StartFrameCapture(device_, nullptr);
}

RenderDocCapture::~RenderDocCapture() {
  if (device_) api()->DiscardFrameCapture(device_, nullptr);
}

std::string RenderDocCapture::end(std::string* error) {
  if (!device_) return "";
  void* device = device_;
  device_ = nullptr;
  if (api()->EndFrameCapture(device, nullptr) != 1) {
    if (error) *error = "RenderDoc did not write a capture (EndFrameCapture failed; see RenderDoc's log)";
    return "";
  }
  // The newest capture is the last in RenderDoc's list.
  uint32_t n = api()->GetNumCaptures();
  uint32_t length = 0;
  if (n == 0 || api()->GetCapture(n - 1, nullptr, &length, nullptr) != 1 || length == 0) {
    if (error) *error = "RenderDoc ended the capture but lists no capture file";
    return "";
  }
  std::vector<char> path(length + 1, '\0');
  api()->GetCapture(n - 1, path.data(), &length, nullptr);
  return std::string(path.data());
}

}  // namespace gb
