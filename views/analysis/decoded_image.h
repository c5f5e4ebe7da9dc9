// A quantity decoded at every texel of its target (renderer/core/decode.h), as whole arrays: what the
// Python module hands out (frame["normal"]) and what the compare report's hover readout shows. Values
// are the probe's: colours linear, normals unit, depths as eye depth, positions, motion in pixels,
// integers, scalars with scale and bias; vectors in eye space (as the probe shows them) or in the
// layout's own space (its world axes: a Z-up layout's world positions come back Z up).
#pragma once
#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/core/snapshot.h"

namespace gb {

enum class VectorSpace : uint8_t { Eye, Layout };

// Components a quantity decodes to (normal 3, depth 1, position 3, motion 2, colour its channels, ...).
uint32_t decodedComponents(const Quantity& q);
// Their names, for people ("x", "y", "z"; "r", "g", "b", "a"; "eye_depth"; ...).
std::vector<std::string> decodedComponentNames(const Quantity& q);

// The quantity at target texel (x, y) into out[0 .. decodedComponents(q)): NaN where it decodes to
// nothing (a depth or position where no surface was drawn). The frame must hold the texel.
void decodeAt(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y, VectorSpace space, double* out);

// The quantity over its whole target, rows top to bottom, components interleaved (the target's
// width x height x decodedComponents(q)). The frame must hold the whole target.
template <class T>
std::vector<T> decodeImage(const FrameSnapshot& f, const Quantity& q, VectorSpace space) {
  const TargetImage& ti = f.images[q.target];
  const uint32_t n = decodedComponents(q);
  std::vector<T> out(size_t(ti.image.width) * ti.image.height * n);
  double v[4];
  for (uint32_t y = 0; y < ti.image.height; ++y)
    for (uint32_t x = 0; x < ti.image.width; ++x) {
      decodeAt(f, q, x + ti.x0, y + ti.y0, space, v);
      T* o = &out[(size_t(y) * ti.image.width + x) * n];
      for (uint32_t k = 0; k < n; ++k) o[k] = T(v[k]);
    }
  return out;
}

}  // namespace gb
