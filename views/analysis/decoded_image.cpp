// Whole-target decoding (decoded_image.h): each kind through the one decoder, renderer/core/decode.h.
#include "views/analysis/decoded_image.h"

#include "renderer/core/assert.h"
#include "renderer/core/decode.h"

namespace gb {

namespace {

bool isColour(QuantityKind k) {
  return k == QuantityKind::Albedo || k == QuantityKind::BaseColor || k == QuantityKind::Emission ||
         k == QuantityKind::Radiance || k == QuantityKind::Display;
}

uint32_t channelsOf(const Quantity& q) { return uint32_t(std::min<size_t>(q.channels.size(), 4)); }

}  // namespace

uint32_t decodedComponents(const Quantity& q) {
  switch (q.kind) {
    case QuantityKind::Normal:
    case QuantityKind::Position: return 3;
    case QuantityKind::Depth:
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count: return 1;
    case QuantityKind::Motion: return 2;
    default: return channelsOf(q);
  }
}

std::vector<std::string> decodedComponentNames(const Quantity& q) {
  switch (q.kind) {
    case QuantityKind::Normal:
    case QuantityKind::Position: return {"x", "y", "z"};
    case QuantityKind::Depth: return {q.ofSun ? "stored" : "eye_depth"};
    case QuantityKind::Motion: return {"dx_pixels", "dy_pixels"};
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count: return {"value"};
    default: break;
  }
  static const char* rgba[] = {"r", "g", "b", "a"};
  static const char* plain[] = {"c0", "c1", "c2", "c3"};
  std::vector<std::string> names;
  for (uint32_t k = 0; k < channelsOf(q); ++k) names.push_back(isColour(q.kind) ? rgba[k] : plain[k]);
  return names;
}

void decodeAt(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y, VectorSpace space, double* out) {
  GB_ASSERT(holds(f, q, x, y));
  // Vectors in the layout's own space: points for positions (camera-relative ones stay directions).
  auto toSpace = [&](const glm::dvec3& eye, bool point) {
    const glm::dvec3 v = space == VectorSpace::Eye ? eye : spaceFromEye(f, q.space, eye, point);
    out[0] = v.x, out[1] = v.y, out[2] = v.z;
  };
  switch (q.kind) {
    case QuantityKind::Normal: return toSpace(decodeNormal(f, q, x, y).unit, false);
    case QuantityKind::Depth: {
      const std::optional<double> z = decodeEyeDepth(f, q, x, y);
      out[0] = z ? *z : NAN;
      return;
    }
    case QuantityKind::Position: {
      const std::optional<glm::dvec3> e = decodePosition(f, q, x, y);
      if (!e) {
        out[0] = out[1] = out[2] = NAN;
        return;
      }
      return toSpace(*e, q.space != Space::CameraRelative);
    }
    case QuantityKind::Motion: {
      const glm::dvec2 m = decodeMotion(f, q, x, y);
      out[0] = m.x, out[1] = m.y;
      return;
    }
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count: out[0] = double(decodeInteger(f, q, x, y)); return;
    default: break;
  }
  if (isColour(q.kind)) {
    const glm::dvec4 c = decodeColor(f, q, x, y);
    for (uint32_t k = 0; k < channelsOf(q); ++k) out[k] = c[int(k)];
    return;
  }
  const std::array<double, 4> v = storedValues(f, q, x, y);
  for (uint32_t k = 0; k < channelsOf(q); ++k) out[k] = v[k] * q.scale + q.bias;
}

}  // namespace gb
