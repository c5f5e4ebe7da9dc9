// Motion-vector conventions (what a stored vector means, as a layout declares it and as `gblens motion`
// detects it) and the reprojection of a frame's surface into another frame's camera.
#include "views/analysis/motion.h"

#include <cmath>

#include "renderer/core/decode.h"

namespace gb {

// The world-space point a frame's pixel shows, its centre moved back by the frame's jitter (the
// jittered projection shows at pixel centre c the point whose unjittered position is c - jitter).
std::optional<glm::dvec3> surfacePoint(const FrameSnapshot& f, uint32_t x, uint32_t y, glm::dvec2 jitter) {
  const Quantity* depth = surfaceDepth(f.layout);
  std::optional<glm::dvec3> eye;
  if (depth) {
    if (!holds(f, *depth, x, y)) return std::nullopt;
    const std::optional<double> d = decodeEyeDepth(f, *depth, x, y);
    if (!d) return std::nullopt;
    if (depth->depth == DepthEncoding::Radial) {
      eye = decodePosition(f, *depth, x, y);  // the ray's own direction: the jitter's effect is second order
    } else {
      eye = eyeFromEyeDepth(f.camera, x - jitter.x, y - jitter.y, *d);
    }
  } else if (const Quantity* p = f.layout.find(QuantityKind::Position); p && holds(f, *p, x, y)) {
    eye = decodePosition(f, *p, x, y);
  }
  if (!eye) return std::nullopt;
  return glm::dvec3(f.camera.worldFromEye * glm::dvec4(*eye, 1.0));
}

// A world point in a frame's unjittered pixel coordinates (continuous; null behind the camera).
std::optional<glm::dvec2> projectToPixel(const Camera& c, const glm::dvec3& world) {
  const glm::dvec4 clip = c.clipFromWorld * glm::dvec4(world, 1.0);
  if (!(clip.w > 1e-12)) return std::nullopt;
  const glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
  return glm::dvec2((ndc.x + 1.0) * 0.5 * c.width, (ndc.y + 1.0) * 0.5 * c.height);
}

std::optional<glm::dvec2> reprojectPixel(const FrameSnapshot& from, uint32_t x, uint32_t y, const FrameSnapshot& to) {
  const std::optional<glm::dvec3> p = surfacePoint(from, x, y, glm::dvec2(0.0));
  if (!p) return std::nullopt;
  return projectToPixel(to.camera, *p);
}

MotionConvention declaredConvention(const Quantity& q) {
  MotionConvention c;
  c.units = q.units;
  c.toPrevious = q.toPrevious;
  c.yUp = q.motionYUp;
  c.jitterIncluded = q.jitterIncluded;
  return c;
}

static const char* unitsName(MotionUnits u) { return u == MotionUnits::Pixels ? "pixels" : u == MotionUnits::Ndc ? "ndc" : "uv"; }

nlohmann::json conventionJson(const MotionConvention& c, const MotionDecided* d) {
  auto field = [&](bool decided, nlohmann::json v) { return !d || decided ? v : nlohmann::json(); };
  return {{"units", field(!d || d->units, unitsName(c.units))},
          {"direction", field(!d || d->direction, c.toPrevious ? "to_previous" : "to_next")},
          {"y", field(!d || d->y, c.yUp ? "up" : "down")},
          {"scale", field(!d || d->scale, c.scale)},
          {"jitter", field(!d || d->jitter, c.jitterIncluded ? "included" : "excluded")},
          {"lag", field(!d || d->lag, c.lag)}};
}

std::vector<std::string> conventionDifferences(const MotionConvention& a, const MotionConvention& b, const MotionDecided& d) {
  std::vector<std::string> out;
  if (d.units && a.units != b.units)
    out.push_back(std::string("units are ") + unitsName(b.units) + ", not " + unitsName(a.units) + " as the layout says");
  if (d.direction && a.toPrevious != b.toPrevious)
    out.push_back(b.toPrevious ? "direction is flipped: the vectors point to the previous frame"
                               : "direction is flipped: the vectors point from the previous frame (to_next)");
  if (d.y && a.yUp != b.yUp) out.push_back(b.yUp ? "y is flipped (+y points up)" : "y is flipped (+y points down)");
  if (d.scale && b.scale != a.scale) {
    if (b.scale == 0.5) out.push_back("vectors are half length (made for a half-resolution target?)");
    else if (b.scale == 2.0) out.push_back("vectors are double length (made for a double-resolution target?)");
    else out.push_back("vectors are scaled by " + std::to_string(b.scale));
  }
  if (d.jitter && a.jitterIncluded != b.jitterIncluded)
    out.push_back(b.jitterIncluded ? "jitter is included (the vectors join jittered positions)"
                                   : "jitter is excluded (the layout says included)");
  if (d.lag && a.lag != b.lag) out.push_back(b.lag == 1 ? "one frame late (each frame holds the previous frame's vectors)"
                                                        : "not late (the layout expects the previous frame's vectors)");
  return out;
}

static glm::dvec2 unitsPerPixel(MotionUnits u, uint32_t w, uint32_t h) {
  if (u == MotionUnits::Ndc) return glm::dvec2(2.0 / w, 2.0 / h);
  if (u == MotionUnits::Uv) return glm::dvec2(1.0 / w, 1.0 / h);
  return glm::dvec2(1.0);
}

glm::dvec2 storedFromMotion(const MotionConvention& c, glm::dvec2 m, glm::dvec2 dj, uint32_t w, uint32_t h) {
  glm::dvec2 v = m + (c.jitterIncluded ? dj : glm::dvec2(0.0));
  if (!c.toPrevious) v = -v;
  if (c.yUp) v.y = -v.y;
  return v * unitsPerPixel(c.units, w, h) * c.scale;
}

glm::dvec2 motionFromStored(const MotionConvention& c, glm::dvec2 s, glm::dvec2 dj, uint32_t w, uint32_t h) {
  glm::dvec2 v = s / (unitsPerPixel(c.units, w, h) * c.scale);
  if (c.yUp) v.y = -v.y;
  if (!c.toPrevious) v = -v;
  return v - (c.jitterIncluded ? dj : glm::dvec2(0.0));
}

}  // namespace gb
