// The Vulkan format of each TexelFormat (renderer/core/targets.h), and of each target under the options.
#pragma once
#include <vulkan/vulkan.h>

#include "renderer/core/targets.h"

namespace gb {

VkFormat vkFormat(TexelFormat f);
inline VkFormat targetFormat(Target t, const RenderOptions& o) { return vkFormat(texelFormat(t, o)); }

}  // namespace gb
