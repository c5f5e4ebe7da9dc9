// The cluster grid's shape and the CPU's light assignment (see cluster_grid.h): per light, the cells
// in its screen rectangle and depth range whose box its sphere reaches; then a counting sort by cell,
// which keeps each cell's lights in visible-list order (the shader adds them in that order).
#include "renderer/core/cluster_grid.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/light_rect.h"

namespace gb {

namespace {

// Rounding between the CPU's double and the shader's float: the slice computed from a float
// log2 (a few ULP) moves a depth by ~3e-6 of itself at most, a point reconstructed from depth lies
// within ~1e-6 of its pixel centre's ray (relative to its depth); the boxes are widened by far more.
constexpr double kDepthPad = 1e-4;
constexpr double kRayPad = 1e-4;
constexpr double kRadiusPad = 1e-4;

// What the cell boxes of a frame are made of. A cell's box is separable: its x extent depends on
// the tile column and the slice, its y extent on the row and the slice, its z extent on the slice.
struct GridGeometry {
  std::vector<double> x0, x1;      // per tile column: eye x per unit depth at its first and last pixel centre
  std::vector<double> y0, y1;      // per tile row
  std::vector<double> near, far;   // per slice: its eye depths, widened for rounding
  std::vector<double> margin;      // per slice: absolute widening (ray rounding, stored position error)
};

// Eye-space x (or y) per unit depth of pixel centre `p` along one axis (row 0 or 1 of the projection).
double slope(const Camera& c, uint32_t p, int axis) {
  const glm::dmat4& m = c.clipFromEye;
  const glm::dvec2 n = pixelNdc(c, p, p);
  return axis == 0 ? (n.x + m[2][0]) / m[0][0] : (n.y + m[2][1]) / m[1][1];
}

GridGeometry gridGeometry(const Camera& c, const GridShape& g, const PositionSlack& slack) {
  GridGeometry geo;
  double steepest = 0.0;
  auto axis = [&](uint32_t tiles, uint32_t pixels, int a, std::vector<double>& lo, std::vector<double>& hi) {
    for (uint32_t t = 0; t < tiles; ++t) {
      const double s0 = slope(c, t * g.tile, a), s1 = slope(c, std::min((t + 1) * g.tile, pixels) - 1, a);
      lo.push_back(std::min(s0, s1));
      hi.push_back(std::max(s0, s1));
      steepest = std::max({steepest, std::abs(s0), std::abs(s1)});
    }
  };
  axis(g.tilesX, c.width, 0, geo.x0, geo.x1);
  axis(g.tilesY, c.height, 1, geo.y0, geo.y1);
  for (uint32_t k = 0; k < g.slices; ++k) {
    const double n = k == 0 ? 0.0 : std::exp2((double(k) - g.bias) / g.scale);
    // Geometry is clipped at the far plane: the last slice ends there (rounding aside).
    const double f = k + 1 >= g.slices ? c.zfar * (1.0 + 1e-3) : std::exp2((double(k) + 1.0 - g.bias) / g.scale);
    geo.near.push_back(n * (1.0 - kDepthPad));
    geo.far.push_back(f * (1.0 + kDepthPad));
    const double reach = geo.far.back() * (1.0 + 2.0 * steepest);  // bounds a cell point's distance from the camera
    // A stored vector's error: `relative` of its largest coordinate per coordinate, at most twice that in length.
    geo.margin.push_back(kRayPad * reach + 2.0 * slack.relative * (slack.storedOffset + reach));
  }
  return geo;
}

// Distance from v to the interval of slopes [s0, s1] times depths [n, f], widened by m.
double gap(double v, double s0, double s1, double n, double f, double m) {
  const double lo = std::min(s0 * n, s0 * f) - m, hi = std::max(s1 * n, s1 * f) + m;
  return std::max({lo - v, v - hi, 0.0});
}

}  // namespace

GridShape gridShape(const Camera& camera, double depthNear, double depthFar) {
  GridShape g;
  g.tilesX = (camera.width + g.tile - 1) / g.tile;
  g.tilesY = (camera.height + g.tile - 1) / g.tile;
  depthNear = std::clamp(depthNear, camera.znear, camera.zfar);
  depthFar = std::clamp(depthFar, depthNear * 1.01, std::max(camera.zfar, depthNear * 1.01));
  g.scale = double(g.slices) / std::log2(depthFar / depthNear);
  g.bias = -std::log2(depthNear) * g.scale;
  return g;
}

uint32_t gridSlice(const GridShape& g, double eyeDepth) {
  const float k = std::floor(std::log2(std::max(float(eyeDepth), 1e-30f)) * float(g.scale) + float(g.bias));
  return uint32_t(std::clamp(k, 0.0f, float(g.slices - 1)));
}

GridShape gridShapeForLights(const Camera& camera, const std::vector<gpu::PointLight>& eyeLights,
                             const std::vector<uint32_t>& visible) {
  // No light reaches a surface point outside the lights' depths: the slices need not cover it.
  if (visible.empty()) return gridShape(camera, camera.znear, camera.zfar);
  double lightNear = camera.zfar, lightFar = camera.znear;
  for (uint32_t i : visible) {
    const glm::vec4 l = eyeLights[i].eyePositionRadius;
    lightNear = std::min(lightNear, double(-l.z) - double(l.w));
    lightFar = std::max(lightFar, double(-l.z) + double(l.w));
  }
  return gridShape(camera, lightNear, lightFar);
}

uint32_t ClusterGrid::occupiedCells() const {
  return uint32_t(std::count_if(cells.begin(), cells.end(), [](const glm::uvec2& c) { return c.y != 0; }));
}

void assignLights(const Camera& camera, const std::vector<gpu::PointLight>& eyeLights,
                  const std::vector<uint32_t>& visible, const PositionSlack& slack, ClusterGrid& grid) {
  const GridShape g = gridShapeForLights(camera, eyeLights, visible);
  grid.shape = g;
  const GridGeometry geo = gridGeometry(camera, g, slack);

  // Pairs (cell, position in the visible list), light by light; the box test is separable, so
  // each slice's x and y distances are computed once per column and row.
  std::vector<uint32_t>&pairCell = grid.pairCell, &pairLight = grid.pairLight, &count = grid.count;
  pairCell.clear();
  pairLight.clear();
  count.assign(g.cells(), 0u);
  std::vector<double> dx2(g.tilesX), dy2(g.tilesY);
  for (uint32_t k = 0; k < visible.size(); ++k) {
    const glm::vec4 l = eyeLights[visible[k]].eyePositionRadius;
    const glm::dvec3 c(l);
    const double depth = -c.z;
    // The sphere grown by the stored position's error (a point off its pixel's ray by that much).
    const double r = double(l.w) * (1.0 + kRadiusPad) + 2.0 * slack.relative * (slack.storedOffset + glm::length(c) + double(l.w));
    if (depth + r <= 0.0) continue;  // behind the camera: no surface point reaches it
    const PixelRect rect = sphereScreenRect(camera, c, r, 1.0);
    if (rect.empty()) continue;
    const uint32_t tx0 = uint32_t(rect.x0) / g.tile, tx1 = uint32_t(rect.x1) / g.tile;
    const uint32_t ty0 = uint32_t(rect.y0) / g.tile, ty1 = uint32_t(rect.y1) / g.tile;
    const uint32_t k0 = depth - r > 0.0 ? gridSlice(g, (depth - r) * (1.0 - kDepthPad)) : 0u;
    const uint32_t k1 = gridSlice(g, (depth + r) * (1.0 + kDepthPad));
    const double r2 = r * r;
    for (uint32_t s = k0; s <= k1; ++s) {
      const double n = geo.near[s], f = geo.far[s], m = geo.margin[s];
      const double dz = std::max({-f - m - c.z, c.z - (-n + m), 0.0});
      if (dz * dz >= r2) continue;
      for (uint32_t tx = tx0; tx <= tx1; ++tx) {
        const double dx = gap(c.x, geo.x0[tx], geo.x1[tx], n, f, m);
        dx2[tx] = dx * dx;
      }
      for (uint32_t ty = ty0; ty <= ty1; ++ty) {
        const double dy = gap(c.y, geo.y0[ty], geo.y1[ty], n, f, m);
        const double dyz = dy * dy + dz * dz;
        if (dyz >= r2) continue;
        for (uint32_t tx = tx0; tx <= tx1; ++tx) {
          if (dyz + dx2[tx] >= r2) continue;
          const uint32_t cell = g.cell(tx, ty, s);
          pairCell.push_back(cell);
          pairLight.push_back(k);
          ++count[cell];
        }
      }
    }
  }

  // Counting sort by cell (stable: each cell's lights stay in visible-list order).
  grid.cells.assign(g.cells(), glm::uvec2(0u));
  uint32_t offset = 0;
  for (uint32_t cell = 0; cell < g.cells(); ++cell) {
    grid.cells[cell] = {offset, 0u};
    offset += count[cell];
  }
  grid.lights.resize(offset);
  grid.listed.resize(offset);
  for (size_t i = 0; i < pairCell.size(); ++i) {
    glm::uvec2& cell = grid.cells[pairCell[i]];
    const uint32_t at = cell.x + cell.y++;
    grid.lights[at] = eyeLights[visible[pairLight[i]]];
    grid.listed[at] = pairLight[i];
  }
}

}  // namespace gb
