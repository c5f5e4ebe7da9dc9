// The cluster grid: clustered shading with the lights assigned on the CPU (--cluster-assign cpu).
// A fixed view-space grid of screen tiles x exponential depth slices from the near to the far plane
// (Olsson, Billeter, Assarsson, HPG 2012, the explicit grid; Persson, "Practical Clustered Shading",
// SIGGRAPH 2015, lights assigned on the CPU); each cell lists every light whose sphere reaches the
// cell's box, so a surface point a light reaches always finds it in its cell (exact).
#pragma once
#include <cstdint>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/core/camera.h"
#include "shaders/shared.h"

namespace gb {

// The grid of a frame: tiles of `tile` pixels, `slices` depth slices; slice =
// floor(log2(eye depth) * scale + bias), clamped to [0, slices): exponential between two eye
// depths, the first slice reaching down to the camera, the last one to the far plane.
struct GridShape {
  uint32_t tile = gpu::kGridTile, tilesX = 1, tilesY = 1, slices = gpu::kGridSlices;
  double scale = 1.0, bias = 0.0;
  uint32_t cells() const { return tilesX * tilesY * slices; }
  uint32_t cell(uint32_t tx, uint32_t ty, uint32_t slice) const { return (slice * tilesY + ty) * tilesX + tx; }
};
GridShape gridShape(const Camera& camera, double depthNear, double depthFar);
// The slice of an eye depth, rounded as the shader rounds it (float), so the probe names the
// shader's cell.
uint32_t gridSlice(const GridShape& g, double eyeDepth);
// The grid assignLights uses for these lights: slices spanning the visible lights' depths (within
// the near and far planes), the first reaching down to the camera, the last to the far plane.
GridShape gridShapeForLights(const Camera& camera, const std::vector<gpu::PointLight>& eyeLights,
                             const std::vector<uint32_t>& visible);

// How far a reconstructed surface point may lie from its pixel centre's ray, beyond float rounding:
// 0 for positions from depth; for a stored position target, its rounding (`relative` of the
// largest coordinate stored: 2^-11 for rgba16f, 2^-24 for rgba32f) over coordinates up to
// `storedOffset` + the point's distance from the camera.
struct PositionSlack {
  double relative = 0.0;
  double storedOffset = 0.0;  // the stored coordinates' origin from the camera (world space: the camera's position)
};

// Each cell's lights: cells[c] = (offset, count) into `lights`, each cell's in visible-list order.
struct ClusterGrid {
  GridShape shape;
  std::vector<glm::uvec2> cells;
  std::vector<gpu::PointLight> lights;
  std::vector<uint32_t> listed;  // per entry of `lights`: its light's position in the visible list
  std::vector<uint32_t> pairCell, pairLight, count;  // scratch, kept between frames
  uint32_t occupiedCells() const;
};

// Assigns the visible lights (`eyeLights[visible[k]]`, eye space) to the cells whose box they reach,
// on the grid of gridShapeForLights.
void assignLights(const Camera& camera, const std::vector<gpu::PointLight>& eyeLights,
                  const std::vector<uint32_t>& visible, const PositionSlack& error, ClusterGrid& grid);

}  // namespace gb
