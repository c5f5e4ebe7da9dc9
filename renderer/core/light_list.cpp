// LightList's generations: one counter for the process, so no two lists (copies, other scenes,
// a list destroyed and another made at its address) ever hold the same generation.
#include "renderer/core/light_list.h"

#include <atomic>

namespace gb {

uint64_t LightList::nextGeneration() {
  static std::atomic<uint64_t> counter{0};
  return counter.fetch_add(1, std::memory_order_relaxed) + 1;
}

}  // namespace gb
