// GB_ASSERT: a broken invariant stops the program with file:line (release builds too: a bug must
// stop the program, not produce wrong pixels). Vulkan failures use VK_CHECK (renderer/vk/check.h).
#pragma once
#include <cstdio>
#include <cstdlib>

#define GB_ASSERT(cond)                                                                  \
  do {                                                                                   \
    if (!(cond)) {                                                                       \
      std::fprintf(stderr, "gblens: assertion failed: %s (%s:%d)\n", #cond, __FILE__, __LINE__); \
      std::abort();                                                                      \
    }                                                                                    \
  } while (0)
