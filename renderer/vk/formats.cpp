// TexelFormat -> VkFormat.
#include "renderer/vk/formats.h"

namespace gb {

VkFormat vkFormat(TexelFormat f) {
  static const VkFormat table[] = {
      VK_FORMAT_R8G8B8A8_SRGB,       VK_FORMAT_R8G8B8A8_UNORM,      VK_FORMAT_R8G8B8A8_SNORM,
      VK_FORMAT_R16G16B16A16_SNORM,  VK_FORMAT_A2B10G10R10_UNORM_PACK32, VK_FORMAT_R16G16B16A16_SFLOAT,
      VK_FORMAT_R32G32B32A32_SFLOAT, VK_FORMAT_R32_SFLOAT,          VK_FORMAT_R32_UINT,
      VK_FORMAT_R16G16_SFLOAT,       VK_FORMAT_D32_SFLOAT_S8_UINT,  VK_FORMAT_D24_UNORM_S8_UINT,   VK_FORMAT_D32_SFLOAT,
      VK_FORMAT_D16_UNORM,
  };
  static_assert(sizeof(table) / sizeof(table[0]) == size_t(TexelFormat::D16) + 1);
  return table[size_t(f)];
}

}  // namespace gb
