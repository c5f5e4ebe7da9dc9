// Turns a target into an image a person can read: normals as colour, depth with an automatic
// range over visible geometry, shadow as grey, coverage as a heat map. Used by `gblens render
// --target`, the viewer's views and captures' previews.
#pragma once
#include <string>

#include "renderer/image.h"
#include "renderer/options.h"
#include "views/image_io.h"

namespace gb {

// The view names of `render --target` and the viewer (keys 2..9, 0; the last three from its menu).
enum class ViewKind {
  Final, Albedo, Normal, Depth, Specular, Shadow, ShadowMap, CoverageMasked, CoverageFull,
  Hdr, HardwareDepth, Stencil
};
constexpr int kViewKindCount = 12;
bool parseView(const std::string& name, ViewKind& out);
const char* viewName(ViewKind v);

struct FrameImages {
  const CpuImage* albedoSpecular = nullptr;
  const CpuImage* normalShadow = nullptr;
  const CpuImage* depth = nullptr;
  const CpuImage* shadowMap = nullptr;
  const CpuImage* final = nullptr;
  const CpuImage* coverageMasked = nullptr;
  const CpuImage* coverageFull = nullptr;
  const CpuImage* hdr = nullptr;
  const CpuImage* depthStencil = nullptr;
  bool reversedZ = false;
  NormalFormat normalFormat = NormalFormat::Rgba16f;
};

// The targets a view reads.
std::vector<std::string> viewTargets(ViewKind v);

Rgba8Image visualize(ViewKind view, const FrameImages& frame);

// Heat-map colour for a count (0 = black, then blue -> green -> yellow -> red at `max`).
void heatColor(double count, double max, uint8_t out[3]);

}  // namespace gb
