// Whole-target view values (decoded_image.h).
#include "views/analysis/decoded_image.h"

#include <algorithm>

namespace gb {

uint32_t decodedComponents(const FrameSnapshot& f, const ViewDef& view) {
  const Quantity& q = f.layout.quantities[size_t(view.quantity)];
  return view.visual == Visual::Color ? uint32_t(std::min<size_t>(q.channels.size(), 4)) : view.components;
}

}  // namespace gb
