// Compare's parts that live in their own files (compare.h is the interface).
#pragma once
#include "views/analysis/compare.h"

namespace gb {

// One quantity on one side.
struct CompareSide {
  const FrameSnapshot& f;
  const Quantity& q;
};

// Compares one group at every pixel (compare.cpp); with a mask of the group's size, sums the unmasked
// and the masked pixels apart (the unmasked ones decide) as well as all of them.
void compareGroup(const CompareSide& a, const CompareSide& b, const CompareMask* mask, GroupResult& r);

}  // namespace gb
