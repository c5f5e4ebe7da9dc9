// gblens as a RenderDoc client: when gblens runs under RenderDoc (renderdoccmd capture, qrenderdoc's
// Launch Application), the in-application API (renderdoc_app.h) turns the frames rendered between
// start and end into one .rdc, headless frames included (they never present, so RenderDoc's own
// trigger never fires). Without RenderDoc every call does nothing. No Vulkan types here: the viewer
// and the commands call it with their GpuContext.
#pragma once
#include <string>

namespace gb {

struct GpuContext;

// True when RenderDoc's library is loaded in this process and its API answered.
bool underRenderDoc();

// Where the next captures go: RenderDoc strips any extension and appends "_frameN.rdc" (RenderDoc's
// temporary folder, or renderdoccmd's -c, until this is called). Directories are created.
void setRenderDocCaptureTemplate(const std::string& pathTemplate);

// The frames rendered while this lives on ctx's device are one RenderDoc capture, kept when end() is
// called (an early return discards it). Does nothing when not under RenderDoc or `enabled` is false.
class RenderDocCapture {
 public:
  explicit RenderDocCapture(const GpuContext& ctx, bool enabled = true);
  ~RenderDocCapture();
  RenderDocCapture(const RenderDocCapture&) = delete;
  RenderDocCapture& operator=(const RenderDocCapture&) = delete;

  bool active() const { return device_ != nullptr; }
  // Ends the capture and returns the .rdc written: "" when none was started, or when RenderDoc
  // failed to write it (then `error`, when given, says so).
  std::string end(std::string* error = nullptr);

 private:
  void* device_ = nullptr;  // RENDERDOC_DEVICEPOINTER_FROM_VKINSTANCE
};

}  // namespace gb
