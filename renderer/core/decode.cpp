// The layout-driven decoder (see decode.h).
#include "renderer/core/decode.h"

#include <cmath>

#include "renderer/core/assert.h"
#include "renderer/core/camera.h"
#include "renderer/core/codec.h"

namespace gb {

const TargetImage* layoutImage(const FrameSnapshot& f, uint32_t target) {
  GB_ASSERT(target < f.images.size());
  const TargetImage& ti = f.images[target];
  return ti.present() ? &ti : nullptr;
}

bool holds(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  const TargetImage* ti = layoutImage(f, q.target);
  return ti && ti->contains(x, y);
}

std::array<double, 4> storedValues(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  const TargetImage* ti = layoutImage(f, q.target);
  GB_ASSERT(ti && ti->contains(x, y));
  std::array<double, 4> v{};
  for (size_t k = 0; k < q.channels.size() && k < 4; ++k) v[k] = ti->value(x, y, q.channels[k]);
  return v;
}

glm::dvec4 decodeColor(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  std::array<double, 4> v = storedValues(f, q, x, y);
  glm::dvec4 c(v[0], v[1], v[2], q.channels.size() > 3 ? v[3] : 1.0);
  if (q.color == ColorEncoding::Srgb)
    for (int i = 0; i < 3; ++i) c[i] = srgbToLinear(c[i]);
  return c;
}

double decodeScalar(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  return storedValues(f, q, x, y)[0] * q.scale + q.bias;
}

uint32_t decodeInteger(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  double v = storedValues(f, q, x, y)[0];
  return std::isfinite(v) && v > 0.0 ? uint32_t(std::llround(v)) : 0u;
}

glm::dvec3 decodeNormalValues(NormalEncoding e, const std::array<double, 4>& c, const std::array<uint32_t, 4>& raw) {
  switch (e) {
    case NormalEncoding::Xyz: return {c[0], c[1], c[2]};
    case NormalEncoding::XyzUnorm: return glm::dvec3(c[0], c[1], c[2]) * 2.0 - 1.0;
    case NormalEncoding::Octahedral: return octDecode({c[0], c[1]});
    case NormalEncoding::OctahedralUnorm: return octDecode(glm::dvec2(c[0], c[1]) * 2.0 - 1.0);
    case NormalEncoding::Octahedral12: {
      // 12 + 12 bits in three bytes: x = b0 << 4 | b1 >> 4, y = (b1 & 15) << 8 | b2.
      const uint32_t px = (raw[0] << 4) | (raw[1] >> 4), py = ((raw[1] & 15u) << 8) | raw[2];
      return octDecode(glm::dvec2(px, py) / 4095.0 * 2.0 - 1.0);
    }
    case NormalEncoding::Spheremap: {
      // Spheremap transform (Pranckevicius, "Compact Normal Storage for Small G-Buffers", method 4).
      glm::dvec2 fenc = glm::dvec2(c[0], c[1]) * 4.0 - 2.0;
      double f = glm::dot(fenc, fenc), g = std::sqrt(std::max(1.0 - f / 4.0, 0.0));
      return {fenc.x * g, fenc.y * g, 1.0 - f / 2.0};
    }
    case NormalEncoding::Lambert: {
      // Lambert azimuthal equal-area onto the unit disc: |p|^2 = (1 - z) / 2.
      glm::dvec2 p(c[0], c[1]);
      double r2 = glm::dot(p, p), z = 1.0 - 2.0 * r2, s = std::sqrt(std::max(1.0 - z * z, 0.0));
      glm::dvec2 xy = r2 > 0.0 ? p / std::sqrt(r2) * s : glm::dvec2(0.0);
      return {xy.x, xy.y, z};
    }
  }
  GB_ASSERT(!"normal encoding");
  return {};
}

glm::dvec3 eyeFromSpace(const FrameSnapshot& f, Space space, const glm::dvec3& v, bool point) {
  const LayoutCamera& c = f.layout.camera;
  switch (space) {
    case Space::View: return c.leftHanded ? glm::dvec3(v.x, v.y, -v.z) : v;
    case Space::World: {
      glm::dvec3 w = worldFromLayoutWorld(c) * v;
      return point ? glm::dvec3(f.camera.eyeFromWorld * glm::dvec4(w, 1.0)) : glm::dmat3(f.camera.eyeFromWorld) * w;
    }
    case Space::CameraRelative: return glm::dmat3(f.camera.eyeFromWorld) * (worldFromLayoutWorld(c) * v);
  }
  return v;
}

glm::dvec3 spaceFromEye(const FrameSnapshot& f, Space space, const glm::dvec3& e, bool point) {
  const LayoutCamera& c = f.layout.camera;
  switch (space) {
    case Space::View: return c.leftHanded ? glm::dvec3(e.x, e.y, -e.z) : e;
    case Space::World: {
      glm::dvec3 w = point ? glm::dvec3(f.camera.worldFromEye * glm::dvec4(e, 1.0)) : glm::dmat3(f.camera.worldFromEye) * e;
      return layoutWorldFromWorld(c) * w;
    }
    case Space::CameraRelative: return layoutWorldFromWorld(c) * (glm::dmat3(f.camera.worldFromEye) * e);
  }
  return e;
}

NormalSample decodeNormal(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  const TargetImage* ti = layoutImage(f, q.target);
  GB_ASSERT(ti && ti->contains(x, y));
  std::array<double, 4> v = storedValues(f, q, x, y);
  std::array<uint32_t, 4> raw{};
  for (size_t k = 0; k < q.channels.size() && k < 4; ++k) raw[k] = ti->raw(x, y, q.channels[k]);
  NormalSample n;
  n.stored = decodeNormalValues(q.normal, v, raw);
  glm::dvec3 eye = eyeFromSpace(f, q.space, n.stored, false);
  double length = glm::length(eye);
  n.unit = length > 0.0 && std::isfinite(length) ? eye / length : glm::dvec3(0.0);
  return n;
}

namespace {
// A camera depth's eye or radial distance: the stored value with the quantity's scale and bias (a
// depth stored as a fraction of the far plane, say); null where it is the background or no distance.
std::optional<double> storedDistance(const Quantity& q, double v) {
  if (q.background && v == *q.background) return std::nullopt;
  const double d = v * q.scale + q.bias;
  if (!(d > 0.0) || !std::isfinite(d)) return std::nullopt;
  return d;
}
}  // namespace

std::optional<double> decodeEyeDepth(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  GB_ASSERT(q.kind == QuantityKind::Depth);
  const double v = storedValues(f, q, x, y)[0];
  if (q.ofSun) return v;
  if (q.depth == DepthEncoding::Hardware) {
    if (q.background && v == *q.background) return std::nullopt;
    const double far = f.camera.reversedZ ? 0.0 : 1.0;
    if (!q.background && v == far) return std::nullopt;
    return -eyeFromHardwareDepth(f.camera, x, y, v).z;
  }
  const std::optional<double> d = storedDistance(q, v);
  if (!d || q.depth == DepthEncoding::Eye) return d;
  return -pixelRay(f.camera, x, y).direction.z * *d;  // radial: along the pixel's ray (from z = 0)
}

std::optional<glm::dvec3> decodePosition(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  if (q.kind == QuantityKind::Position) {
    std::array<double, 4> v = storedValues(f, q, x, y);
    return eyeFromSpace(f, q.space, {v[0], v[1], v[2]}, q.space != Space::CameraRelative);
  }
  GB_ASSERT(q.kind == QuantityKind::Depth && !q.ofSun);
  const double v = storedValues(f, q, x, y)[0];
  if (q.depth == DepthEncoding::Hardware) {
    if (!decodeEyeDepth(f, q, x, y)) return std::nullopt;
    return eyeFromHardwareDepth(f.camera, x, y, v);
  }
  const std::optional<double> d = storedDistance(q, v);
  if (!d) return std::nullopt;
  if (q.depth == DepthEncoding::Eye) return eyeFromEyeDepth(f.camera, x, y, *d);
  const PixelRay ray = pixelRay(f.camera, x, y);
  return ray.origin + ray.direction * *d;
}

glm::dvec2 decodeMotion(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y) {
  std::array<double, 4> v = storedValues(f, q, x, y);
  glm::dvec2 m(v[0], v[1]);
  if (q.units == MotionUnits::Ndc) m *= glm::dvec2(f.camera.width, f.camera.height) * 0.5;
  if (q.units == MotionUnits::Uv) m *= glm::dvec2(f.camera.width, f.camera.height);
  if (q.motionYUp) m.y = -m.y;
  return q.toPrevious ? m : -m;
}

const Quantity* surfaceDepth(const Layout& l) {
  for (const Quantity& q : l.quantities)
    if (q.kind == QuantityKind::Depth && !q.ofSun) return &q;
  return nullptr;
}

bool hasSurface(const FrameSnapshot& f, uint32_t x, uint32_t y) {
  bool anyDepth = false;
  for (const Quantity& q : f.layout.quantities) {
    if (q.kind != QuantityKind::Depth || q.ofSun) continue;
    anyDepth = true;
    // The first camera depth the frame holds (a forward frame has no eye depth, only the hardware one).
    if (layoutImage(f, q.target)) return holds(f, q, x, y) && decodeEyeDepth(f, q, x, y).has_value();
  }
  return !anyDepth;
}

}  // namespace gb
