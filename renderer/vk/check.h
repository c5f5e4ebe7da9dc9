// VK_CHECK: a failed Vulkan call stops the program with file:line (GB_ASSERT: renderer/core/assert.h).
#pragma once
#include <vulkan/vulkan.h>

#include <cstdio>
#include <cstdlib>

#include "renderer/core/assert.h"

namespace gb {
const char* vkResultName(VkResult r);
[[noreturn]] void vkFail(VkResult r, const char* call, const char* file, int line);
}  // namespace gb

#define VK_CHECK(call)                                             \
  do {                                                             \
    VkResult gb_r_ = (call);                                       \
    if (gb_r_ != VK_SUCCESS) ::gb::vkFail(gb_r_, #call, __FILE__, __LINE__); \
  } while (0)

