// The screen rectangle of a light's sphere: the pixels whose centres its projection can cover.
// One function for light culling (sub-pixel lights, the stencil layers' icosahedra), the ideal
// pair count and the CPU reference's light bins.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "renderer/core/camera.h"

namespace gb {

// Pixels [x0, x1] x [y0, y1] of a frame, inclusive; empty when x0 > x1 or y0 > y1.
struct PixelRect {
  int64_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};

// The pixels whose centres can lie inside the projection of a sphere (centre `c` in eye space,
// radius `r`), widened by `margin` pixels and clipped to the frame. Exact for a sphere in front
// of the eye: along each screen axis the lines through the eye tangent to the sphere bound it.
// The whole frame when the sphere reaches the eye's plane (its projection is unbounded), empty
// when it lies behind it. The near plane is not applied (clipping only removes pixels).
PixelRect sphereScreenRect(const Camera& camera, const glm::dvec3& c, double r, double margin);

}  // namespace gb
