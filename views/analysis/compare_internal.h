// Compare's parts that live in their own files (compare.h is the interface).
#pragma once
#include <chrono>

#include "views/analysis/compare.h"

namespace gb {

inline double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

// One quantity on one side.
struct CompareSide {
  const FrameSnapshot& f;
  const Quantity& q;
};

// Compares one group at every pixel (compare.cpp); with a mask of the group's size, sums the unmasked
// and the masked pixels apart (the unmasked ones decide) as well as all of them.
void compareGroup(const CompareSide& a, const CompareSide& b, const CompareMask* mask, GroupResult& r);

}  // namespace gb
