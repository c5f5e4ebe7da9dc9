// The frame RenderDoc captures when `renderdoccmd capture` runs tiler_deferred: the subject never
// presents, so it brackets the frame itself through RenderDoc's in-application API (only when
// librenderdoc.so was injected into the process; nothing is ever loaded).
#pragma once
#include <vulkan/vulkan.h>

namespace td {

bool renderdoc_present();
void renderdoc_frame_begin(VkInstance instance);
bool renderdoc_frame_end(VkInstance instance);  // false: RenderDoc wrote no capture

}  // namespace td
