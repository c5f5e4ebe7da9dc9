// Normals of a surface rebuilt from points (stored positions, or depth through a camera) and the
// angles between vector fields and them: what decides that a stored vector is a normal (views/infer)
// and what `gblens check` holds stored normals to (views/analysis). A plane fitted to the points of a
// window that lie on one surface; none at silhouettes and creases.
#pragma once
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

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
