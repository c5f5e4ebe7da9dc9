// The measurements the drafting decides by (views/infer) beyond the geometry of core's
// surface_normals.h: channel values of raw target images, clear texels and the surface mask they
// give, the pixels evidence is measured at. Functions of raw target images; no layout is assumed.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/core/image.h"
#include "renderer/core/layout.h"
#include "renderer/core/surface_normals.h"

namespace gb {

// A target's channels decoded as their storage says (unorm / 255, half, ...).
glm::dvec4 channelValues(const CpuImage& img, uint32_t x, uint32_t y, const std::vector<uint32_t>& channels);
// The raw integers of those channels (for packed normal encodings).
std::array<uint32_t, 4> channelRaw(const CpuImage& img, uint32_t x, uint32_t y, const std::vector<uint32_t>& channels);

// The most common texel of a target (the clear value where nothing was drawn, when a frame has
// background) and the fraction of pixels holding it.
struct ClearTexel {
  std::vector<uint8_t> bytes;
  double fraction = 0.0;
};
ClearTexel commonTexel(const CpuImage& img);
// Surfaces where any of `images` differs from its common texel, counting only targets whose common
// texel looks like a clear value (all zero, or a single channel at infinity) and covers 2..98 %.
SurfaceMask maskFromClearTexels(const std::vector<const CpuImage*>& images);

// Pixels to measure at: a grid of about `wanted` surface pixels, away from the border.
std::vector<glm::uvec2> samplePixels(const SurfaceMask& s, uint32_t width, uint32_t height, size_t wanted);

}  // namespace gb
