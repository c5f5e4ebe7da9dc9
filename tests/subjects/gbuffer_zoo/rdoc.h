// RenderDoc's in-application API, only when `renderdoccmd capture` injected librenderdoc.so into this
// process: the app never presents, so it brackets the frame to capture itself.
#pragma once
#include <vulkan/vulkan.h>

namespace zoo {

bool rdoc_attached();
void rdoc_start(VkInstance instance);
bool rdoc_end(VkInstance instance);  // false when RenderDoc says no capture was written

}  // namespace zoo
