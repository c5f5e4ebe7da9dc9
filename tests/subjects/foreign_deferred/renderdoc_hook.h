// RenderDoc's in-application API, used only when RenderDoc already runs this process (renderdoccmd
// capture injects librenderdoc.so): RenderDoc captures on present and this app never presents, so it
// brackets the frame to capture with StartFrameCapture/EndFrameCapture itself.
#pragma once
#include <vulkan/vulkan.h>

namespace fd {

// True when librenderdoc.so is loaded in this process and answered RENDERDOC_GetAPI.
bool renderdoc_present();
// Bracket one frame on `instance`'s device; nothing happens without RenderDoc. end returns false
// when RenderDoc reports that it wrote no capture.
void renderdoc_begin(VkInstance instance);
bool renderdoc_end(VkInstance instance);

}  // namespace fd
