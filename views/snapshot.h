// A frame snapshot: everything the probe, captures and compare need to know about one frame,
// on the CPU, with no Vulkan in sight. Filled from a live Renderer (snapshotFromRenderer) or
// from a capture directory (loadCapture in views/capture.h); probePixel() reads only this.
#pragma once
#include <array>
#include <string>
#include <vector>

#include "renderer/camera.h"
#include "renderer/image.h"
#include "renderer/options.h"
#include "renderer/scene.h"
#include "renderer/targets.h"
#include "shaders/shared.h"

namespace gb {

struct Renderer;

// A target on the CPU, whole or a region of it. Region read-back: the viewer reads back only
// the texels a probe needs; `image` then holds a w x h window whose texel (0, 0) is target
// texel (x0, y0). Every accessor takes TARGET coordinates, so a probe works the same on a
// 1x1 region around the clicked pixel as on the whole frame.
struct TargetImage {
  CpuImage image;                         // empty: not read back (see FrameSnapshot::absent)
  uint32_t x0 = 0, y0 = 0;                // target coordinates of image texel (0, 0)
  uint32_t targetWidth = 0, targetHeight = 0;  // size of the whole target

  bool present() const { return !image.empty(); }
  bool whole() const { return x0 == 0 && y0 == 0 && image.width == targetWidth && image.height == targetHeight; }
  bool contains(uint32_t x, uint32_t y) const {
    return present() && x >= x0 && y >= y0 && x - x0 < image.width && y - y0 < image.height;
  }
  // Stored bits / decoded value at target texel (x, y); the texel must be contained.
  uint32_t raw(uint32_t x, uint32_t y, uint32_t c) const;
  double value(uint32_t x, uint32_t y, uint32_t c) const;
};

struct FrameSnapshot {
  RenderOptions options;                  // what the frame was rendered with
  View view;                              // camera matrices (double), size, near/far, reversed Z
  glm::dmat4 lightClipFromWorld{1.0};     // the sun's shadow-map clip space
  Sun sun;                                // world space
  Sky sky;                                // ambient term of the directional pass
  // Point lights as uploaded for this frame (eye space, float; index = scene light index),
  // the lights drawn (`visible`), of which [0, stencilCount) use the stencil mask and the
  // rest (volume touches the near plane) are drawn as back faces without it.
  std::vector<gpu::PointLight> eyeLights;
  std::vector<uint32_t> visibleLights;
  uint32_t stencilCount = 0;
  std::array<TargetImage, kTargetCount> targets;
  std::array<std::string, kTargetCount> absent;  // why a target is not here ("" when present)

  const TargetImage& target(Target t) const { return targets[size_t(t)]; }
  TargetImage& target(Target t) { return targets[size_t(t)]; }
  // Eye-space direction toward the sun, as the renderer uploads it (float).
  glm::dvec3 sunEyeDirection() const;
};

// Copies this frame's state out of a Renderer (no Vulkan calls: plain fields only). `fresh`
// names the targets read back by the last renderFrame(); Renderer::readback may hold stale
// images of other targets from earlier frames, which are left out. Images are copied whole
// (origin 0, 0); a viewer that read back a region sets x0/y0 and targetWidth/Height itself.
FrameSnapshot snapshotFromRenderer(const Renderer& r, const std::vector<Target>& fresh);

// A target is screen-space when it has the output's size (every target but the shadow map).
bool screenSpaceTarget(Target t);

}  // namespace gb
