// A frame snapshot: everything the probe, captures, compare and error analysis need to know about
// one frame, on the CPU, with no Vulkan in sight. Filled from a live Renderer (HeadlessSession,
// renderer/frame/session.h) or from a capture directory (views/capture/capture.h); analysis reads only this.
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "renderer/core/camera.h"
#include "renderer/core/image.h"
#include "renderer/core/layout.h"
#include "renderer/core/lights.h"
#include "renderer/core/options.h"
#include "renderer/core/targets.h"
#include "shaders/shared.h"

namespace gb {

// A target on the CPU, whole or a region of it. Region read-back: the viewer reads back only
// the texels a probe needs; `image` then holds a w x h window whose texel (0, 0) is target
// texel (x0, y0). Every accessor takes TARGET coordinates, so a probe works the same on a
// 1x1 region around the clicked pixel as on the whole frame.
struct TargetImage {
  CpuImage image;                         // empty: not read back (see FrameSnapshot::absent)
  // A multisampled target: every sample's plane, `image` being sample 0 (empty: one sample).
  std::vector<CpuImage> samples;
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

// What a frame is besides its layout and pixels: a copy of it is cheap (decodeSamples in
// views/analysis/probe.cpp builds 1x1 frames from it without copying the targets' planes).
struct FrameContext {
  RenderOptions options;                  // what the frame was rendered with (imports: the defaults, size)
  Method method = Method::Auto;           // the lighting method that ran (Auto: not known, e.g. a capture)
  bool clusterGrid = false;               // method clustered ran with the CPU's cluster grid (--cluster-assign)
  Camera camera;                          // camera matrices (double), size, near/far, reversed Z
  glm::dmat4 lightClipFromWorld{1.0};     // the sun's shadow-map clip space
  Sun sun;                                // world space
  Sky sky;                                // ambient term of the directional pass
  // Point lights as uploaded for this frame (eye space, float; index = scene light index),
  // the lights drawn (`visible`), of which [0, stencilCount) use the stencil mask and the
  // rest (volume touches the near plane) are drawn as back faces without it.
  std::vector<gpu::PointLight> eyeLights;
  std::vector<uint32_t> visibleLights;
  uint32_t stencilCount = 0;
  // The per-light mask's layers: [layerStarts[k], layerStarts[k + 1]) of the visible list share a
  // stencil bit (renderer/frame/light_culling.cpp). Empty: each stencil-class light has its own bit.
  std::vector<uint32_t> layerStarts;
  uint32_t sampleShown = 0;  // multisampled targets: the sample their images are (views/analysis/sample_views.h)
  // The point lights' descriptions (world space, animation) when the frame came from a scene.
  std::vector<PointLightDesc> lightDescs;
  // The lighting passes' uniform data as uploaded (live frames; captures rebuild what they need).
  gpu::FrameData frameData{};
  // What the device's sampler returns for each 8-bit sRGB value (empty: not probed; exact curve).
  std::vector<float> srgbDecode;
  // What the frame's source does not say (an imported or streamed frame): manifest field -> why
  // ("sun": "the layout gives no lights"). A capture leaves those fields out and records why, never
  // a default in their place; compare reports them apart. Empty for gblens's own frames.
  std::map<std::string, std::string> unknown;
  // With unknown["options"]: the options (table names) the source or the user stated.
  std::vector<std::string> statedOptions;
};

struct FrameSnapshot : FrameContext {
  Layout layout;                          // what its targets hold (nativeLayout(options) for gblens's frames)
  // One image and one reason per layout target, in layout order.
  std::vector<TargetImage> images;
  std::vector<Absent> absences;  // why a target is not here (Absent::No when present)

  // Sets the layout: one empty image per target, each absent as "not captured".
  void setLayout(Layout l);
  // The layout target holding gblens's Target t (the one of its name), or -1.
  int indexOf(Target t) const { return native_[size_t(t)]; }
  int indexOf(const std::string& targetName) const { return layout.findTarget(targetName); }
  // gblens's own targets by Target: an empty image when the layout has no target of that name.
  const TargetImage& target(Target t) const;
  TargetImage& target(Target t);  // the layout must have it
  Absent absence(Target t) const;
  void setAbsence(Target t, Absent why);
  // Eye-space direction toward the sun, as the renderer uploads it (float).
  glm::dvec3 sunEyeDirection() const;

 private:
  std::array<int, kTargetCount> native_ = filled(-1);
  static std::array<int, kTargetCount> filled(int v) {
    std::array<int, kTargetCount> a;
    a.fill(v);
    return a;
  }
};

// A target is screen-space when it has the output's size (every target but the shadow map).
bool screenSpaceTarget(Target t);

}  // namespace gb
