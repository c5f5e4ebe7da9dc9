// The measurements the drafting decides by (views/infer): where the surfaces are, the normals of a
// surface rebuilt from points (stored positions, or depth through a camera), angles between vector
// fields on the pixels away from silhouettes, and robust statistics of them. Functions of raw
// target images; no layout is assumed.
#pragma once
#include <array>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/core/image.h"
#include "renderer/core/layout.h"

namespace gb {

// The pixels that hold a surface, or none known (empty: every pixel).
struct SurfaceMask {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> at;  // width * height, 1: a surface
  std::string from;         // what said so, for people ("hardware depth ≠ 1", "texels ≠ the clear value")
  bool surface(uint32_t x, uint32_t y) const { return at.empty() || at[size_t(y) * width + x]; }
  bool known() const { return !at.empty(); }
  size_t count() const;
};

// A target's channels decoded as their storage says (unorm / 255, half, ...), `n` of them from `first`.
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
// Surfaces where any of `images` differs from its common texel (each counted only when its common
// texel covers 2..98 % of the frame: a target cleared where nothing drew).
SurfaceMask maskFromClearTexels(const std::vector<const CpuImage*>& images);

// Pixels to measure at: a grid of about `wanted` surface pixels, away from the border.
std::vector<glm::uvec2> samplePixels(const SurfaceMask& s, uint32_t width, uint32_t height, size_t wanted);

// A point per pixel (stored or rebuilt), nullopt where none.
using PointField = std::function<std::optional<glm::dvec3>(uint32_t x, uint32_t y)>;

// The unit normal of the surface the points describe at each sample pixel (a plane fitted to the
// points of a 5x5 window that lie on the same surface; none at silhouettes and creases), in the
// points' own space; oriented toward `eye` when given.
struct ReferenceNormals {
  std::vector<glm::uvec2> pixels;
  std::vector<glm::dvec3> normals;
  std::string from;  // for people: "stored positions P (world space)"
};
ReferenceNormals surfaceNormals(const PointField& points, const SurfaceMask& s, const std::vector<glm::uvec2>& pixels,
                                const std::optional<glm::dvec3>& eye);

// Angles (degrees) between a candidate's unit vectors and the reference, orientation-free
// (|cos|), with how often the candidate points the reference's way.
struct AngleStats {
  size_t count = 0;
  double median = 180.0, p90 = 180.0, p99 = 180.0;
  double sameSide = 0.0;  // fraction with cos > 0
  std::string text() const;  // "median 0.31°, p90 1.2°, p99 3.4° over 812 pixels"
};
using VectorField = std::function<std::optional<glm::dvec3>(uint32_t x, uint32_t y)>;
AngleStats anglesTo(const ReferenceNormals& ref, const VectorField& candidate);

// Nearest-rank quantile of a copy.
double quantileOf(std::vector<double> v, double q);
// A number for people at `digits` significant digits.
std::string numText(double v, int digits = 3);

}  // namespace gb
