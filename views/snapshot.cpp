// Frame snapshots from a live renderer; region-aware texel access.
#include "views/snapshot.h"

#include <algorithm>

#include "renderer/renderer.h"
#include "renderer/vk/check.h"

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
  return glm::dvec3(glm::vec3(glm::normalize(glm::dmat3(view.eyeFromWorld) * sun.toSun)));
}

bool screenSpaceTarget(Target t) { return t != Target::ShadowMap; }

FrameSnapshot snapshotFromRenderer(const Renderer& r, const std::vector<Target>& fresh) {
  FrameSnapshot s;
  s.options = r.options;
  s.view = r.view;
  s.lightClipFromWorld = r.lightClipFromWorld;
  GB_ASSERT(r.scene);
  s.sun = r.scene->sun;
  s.sky = r.scene->sky;
  s.eyeLights = r.lights.eye;
  s.visibleLights = r.lights.visible;
  s.stencilCount = r.lights.stencilCount;
  for (size_t i = 0; i < kTargetCount; ++i) {
    Target t = Target(i);
    std::string why = targetUnavailable(t, r.options, r.scene);
    if (!why.empty()) {
      s.absent[i] = why;
    } else if (std::find(fresh.begin(), fresh.end(), t) == fresh.end() || r.readback[i].empty()) {
      s.absent[i] = "not read back";
    } else {
      TargetImage& ti = s.targets[i];
      ti.image = r.readback[i];
      ti.targetWidth = ti.image.width;
      ti.targetHeight = ti.image.height;
    }
  }
  return s;
}

}  // namespace gb
