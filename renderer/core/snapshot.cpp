// Frame snapshots: region-aware texel access.
#include "renderer/core/snapshot.h"

#include "renderer/core/assert.h"

namespace gb {

uint32_t TargetImage::raw(uint32_t x, uint32_t y, uint32_t c) const {
  GB_ASSERT(contains(x, y));
  return image.raw(x - x0, y - y0, c);
}

double TargetImage::value(uint32_t x, uint32_t y, uint32_t c) const {
  GB_ASSERT(contains(x, y));
  return image.value(x - x0, y - y0, c);
}

glm::dvec3 FrameSnapshot::sunEyeDirection() const {
  // The same expression as the renderer's frame data (double, then rounded to float).
  return glm::dvec3(glm::vec3(glm::normalize(glm::dmat3(camera.eyeFromWorld) * sun.toSun)));
}

bool screenSpaceTarget(Target t) { return t != Target::ShadowMap; }

}  // namespace gb
