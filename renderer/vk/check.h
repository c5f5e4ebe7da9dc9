// VK_CHECK and GB_ASSERT: a failed Vulkan call or a broken invariant stops the program with file:line.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdio>
#include <cstdlib>

namespace gb {
const char* vkResultName(VkResult r);
[[noreturn]] void vkFail(VkResult r, const char* call, const char* file, int line);
}  // namespace gb

#define VK_CHECK(call)                                             \
  do {                                                             \
    VkResult gb_r_ = (call);                                       \
    if (gb_r_ != VK_SUCCESS) ::gb::vkFail(gb_r_, #call, __FILE__, __LINE__); \
  } while (0)

// Always on (release builds too): a bug must stop the program, not produce wrong pixels.
#define GB_ASSERT(cond)                                                                  \
  do {                                                                                   \
    if (!(cond)) {                                                                       \
      std::fprintf(stderr, "gblens: assertion failed: %s (%s:%d)\n", #cond, __FILE__, __LINE__); \
      std::abort();                                                                      \
    }                                                                                    \
  } while (0)
