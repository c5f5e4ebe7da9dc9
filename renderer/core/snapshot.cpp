// Frame snapshots: region-aware texel access.
#include "renderer/core/snapshot.h"

#include "renderer/core/assert.h"
#include "renderer/core/layout_json.h"

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

bool screenSpaceTarget(Target t) { return targetInfo(t).size == SizeRule::Output; }

void FrameSnapshot::setLayout(Layout l) {
  layout = std::move(l);
  images.assign(layout.targets.size(), TargetImage{});
  absences.assign(layout.targets.size(), Absent::NotCaptured);
  // Another renderer's target that happens to be named like one of gblens's is not gblens's target.
  const bool gblens = gblensLayout(layout);
  for (const TargetInfo& t : targetTable()) native_[size_t(t.target)] = gblens ? layout.findTarget(t.name) : -1;
}

const TargetImage& FrameSnapshot::target(Target t) const {
  static const TargetImage none;
  const int i = native_[size_t(t)];
  return i < 0 ? none : images[size_t(i)];
}

TargetImage& FrameSnapshot::target(Target t) {
  const int i = native_[size_t(t)];
  GB_ASSERT(i >= 0);
  return images[size_t(i)];
}

Absent FrameSnapshot::absence(Target t) const {
  const int i = native_[size_t(t)];
  return i < 0 ? Absent::NotCaptured : absences[size_t(i)];
}

void FrameSnapshot::setAbsence(Target t, Absent why) {
  const int i = native_[size_t(t)];
  GB_ASSERT(i >= 0);
  absences[size_t(i)] = why;
}

}  // namespace gb
