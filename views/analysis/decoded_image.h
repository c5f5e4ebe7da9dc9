// A view's values over its whole target (visualize.h viewValue: each quantity decoded as its kind says,
// in the layout's own units and space, as the probe shows it), as arrays: what the Python module hands
// out (frame["Normal"]) and what the compare report's hover readout shows. NaN where the view has no
// value (no surface, a depth's background).
#pragma once
#include <cmath>
#include <cstdint>
#include <vector>

#include "views/analysis/visualize.h"

namespace gb {

// Components of a view's value as the probe lists them: colour its channels (up to 4), else the view's.
uint32_t decodedComponents(const FrameSnapshot& f, const ViewDef& view);

// The view over its whole target, rows top to bottom, components interleaved (the target's width x
// height x decodedComponents). The frame must hold the whole target.
template <class T>
std::vector<T> decodedImage(const FrameSnapshot& f, const ViewDef& view) {
  const TargetImage& ti = f.images[view.target];
  const uint32_t n = decodedComponents(f, view);
  std::vector<T> out(size_t(ti.image.width) * ti.image.height * n, T(NAN));
  for (uint32_t y = 0; y < ti.image.height; ++y)
    for (uint32_t x = 0; x < ti.image.width; ++x)
      if (const std::optional<std::array<double, 4>> v = viewValue(f, view, x + ti.x0, y + ti.y0)) {
        T* o = &out[(size_t(y) * ti.image.width + x) * n];
        for (uint32_t k = 0; k < n; ++k) o[k] = T((*v)[k]);
      }
  return out;
}

}  // namespace gb
