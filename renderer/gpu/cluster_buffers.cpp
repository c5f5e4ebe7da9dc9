// Clustered shading's buffers (see cluster_buffers.h).
#include "renderer/gpu/cluster_buffers.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "renderer/core/light_rect.h"

namespace gb {

static uint32_t divUp(uint32_t a, uint32_t b) { return (a + b - 1) / b; }

// `name` as the shaders call the buffer (RenderDoc's resource list).
static void replace(Renderer& r, Buffer& b, VkDeviceSize bytes, VkBufferUsageFlags usage, MemoryUse use,
                    const char* name) {
  if (b.buffer && b.size >= bytes) return;
  if (b.buffer) {
    vkDeviceWaitIdle(r.ctx->device);
    destroyBuffer(*r.ctx, b);
  }
  b = createBuffer(*r.ctx, std::max<VkDeviceSize>(bytes, 16), usage, use, name);
}

void clusterFrameData(const Camera& camera, uint32_t visibleMax, gpu::FrameData& f) {
  const uint32_t tilesX = divUp(camera.width, gpu::kClusterTile), tilesY = divUp(camera.height, gpu::kClusterTile);
  f.clusterGrid = glm::uvec4(tilesX, tilesY, divUp(camera.width, gpu::kBinTile), std::max(divUp(visibleMax, 32), 1u));
  const ClusterSlicing slicing = clusterSlicing(camera);  // renderer/core/light_rect.h
  f.clusterSlices = glm::vec4(float(slicing.scale), float(slicing.bias), 0.0f, 0.0f);
}

void gridFrameData(const GridShape& grid, gpu::FrameData& f) {
  f.gridShape = glm::uvec4(grid.tilesX, grid.tilesY, grid.slices, grid.tile);
  f.gridSlices = glm::vec4(float(grid.scale), float(grid.bias), 0.0f, 0.0f);
}

// How far the lighting passes' surface point may be from its pixel's ray: a stored position's rounding.
static PositionSlack positionSlack(const Renderer& r) {
  const RenderOptions& o = r.options;
  PositionSlack e;
  if (o.position == PositionSource::Depth) return e;
  e.relative = std::ldexp(1.0, o.position == PositionSource::Rgba16f ? -11 : -24);  // half an ULP, relative
  if (o.positionSpace == PositionSpace::World) e.storedOffset = glm::length(glm::dvec3(r.camera.worldFromEye[3]));
  return e;
}

bool writeClusterGrid(Renderer& r, std::string& why) {
  ClusterBuffers& c = r.clusters;
  FrameSlot& slot = frameSlot(r);  // the other slot's frame may still read its own grid
  assignLights(r.camera, r.lights.eye, r.lights.visible, positionSlack(r), c.grid);
  const VkDeviceSize cellBytes = c.grid.cells.size() * sizeof(glm::uvec2);
  const VkDeviceSize lightBytes = c.grid.lights.size() * sizeof(gpu::PointLight);
  // Many large lights over many cells can list more than one storage buffer may hold (the stress
  // suite's 16384 overlapping lights: 178 MB): that frame takes the occupied clusters instead.
  const VkDeviceSize limit = std::min<VkDeviceSize>(r.ctx->properties.limits.maxStorageBufferRange, kGridBudgetBytes);
  if (lightBytes + lightBytes / 2 > limit || cellBytes > limit) {
    why = "the cluster grid would list " + std::to_string(c.grid.lights.size()) + " lights (" +
          std::to_string(lightBytes >> 20) + " MiB, over " + std::to_string(limit >> 20) +
          " MiB): occupied clusters in compute this frame";
    return false;
  }
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  replace(r, slot.gridCells, cellBytes, usage, MemoryUse::Upload, "grid_cells");
  // Grown by half again, so a moving light count does not re-create them every frame.
  if (!slot.gridLights.buffer || slot.gridLights.size < lightBytes)
    replace(r, slot.gridLights, lightBytes + lightBytes / 2, usage, MemoryUse::Upload, "grid_lights");
  std::memcpy(slot.gridCells.mapped, c.grid.cells.data(), cellBytes);
  if (lightBytes) std::memcpy(slot.gridLights.mapped, c.grid.lights.data(), lightBytes);
  return true;
}

ClusterStats gridClusterStats(const Renderer& r) {
  ClusterStats s;
  s.valid = true;
  s.clusters = r.clusters.grid.occupiedCells();
  s.listEntries = uint32_t(r.clusters.grid.lights.size());
  return s;
}

void ensureClusterBuffers(Renderer& r, uint32_t visibleMax) {
  ClusterBuffers& c = r.clusters;
  const uint32_t w = r.options.width, h = r.options.height;
  const uint32_t tiles = divUp(w, gpu::kClusterTile) * divUp(h, gpu::kClusterTile);
  const uint32_t bins = divUp(w, gpu::kBinTile) * divUp(h, gpu::kBinTile);
  const uint32_t words = std::max(divUp(visibleMax, 32), 1u);
  // Typical frames hold a few clusters per tile and tens of lights per cluster; more is grown.
  c.clusterCapacity = std::max(c.clusterCapacity, tiles * 4);
  c.listCapacity = std::max(c.listCapacity, std::max(c.clusterCapacity * 16, 1u << 20));
  const VkBufferUsageFlags storage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  replace(r, c.header, sizeof(gpu::ClusterHeader), storage | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT |
                                                       VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Device, "cluster_header");
  // The current slot's copy for the CPU (its previous frame is retired: nothing reads it now).
  replace(r, frameSlot(r).clusterHeader, sizeof(gpu::ClusterHeader), VK_BUFFER_USAGE_TRANSFER_DST_BIT,
          MemoryUse::Readback, "cluster_header.readback");
  replace(r, c.clusters, VkDeviceSize(c.clusterCapacity) * sizeof(gpu::Cluster), storage, MemoryUse::Device, "clusters");
  replace(r, c.pixelClusters, VkDeviceSize(w) * h * 4, storage, MemoryUse::Device, "pixel_clusters");
  replace(r, c.lists, VkDeviceSize(c.listCapacity) * 4, storage, MemoryUse::Device, "light_lists");
  replace(r, c.binBits, VkDeviceSize(bins) * words * 4, storage, MemoryUse::Device, "bin_bits");
  replace(r, c.binBoxes, VkDeviceSize(bins) * 32, storage, MemoryUse::Device, "bin_boxes");
  c.binBitsBytes = VkDeviceSize(bins) * words * 4;
  c.binBoxBytes = VkDeviceSize(bins) * 32;
}

void destroyClusterBuffers(Renderer& r) {
  ClusterBuffers& c = r.clusters;
  for (Buffer* b : {&c.header, &c.clusters, &c.pixelClusters, &c.lists, &c.binBits, &c.binBoxes, &r.fairyBits})
    if (b->buffer) destroyBuffer(*r.ctx, *b);
  c = ClusterBuffers{};
}

bool fairiesInCompute(const GpuContext& ctx, const RenderOptions& o, std::string& reason) {
  if (singlePassFrame(o)) return reason = "drawn: the single-pass path draws them in its lighting subpass", false;
  if (o.fairySplat == FairySplat::Raster) return reason = "drawn (--fairy-splat raster)", false;
  if (o.fairySplat == FairySplat::Auto && ctx.isCpu)
    return reason = "drawn: a CPU device (cheaper there, docs/performance.md)", false;
  reason = o.fairySplat == FairySplat::Compute ? "--fairy-splat compute" : "auto: a GPU device";
  return true;
}

void ensureFairyBits(Renderer& r, uint32_t visibleMax) {
  const uint32_t bins = divUp(r.options.width, gpu::kBinTile) * divUp(r.options.height, gpu::kBinTile);
  r.fairyBitsBytes = VkDeviceSize(bins) * std::max(divUp(visibleMax, 32), 1u) * 4;
  replace(r, r.fairyBits, r.fairyBitsBytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
          MemoryUse::Device, "fairy_bits");
}

ClusterStats collectClusterStats(Renderer& r, const FrameSlot& slot) {
  ClusterBuffers& c = r.clusters;
  gpu::ClusterHeader h;
  std::memcpy(&h, slot.clusterHeader.mapped, sizeof(h));
  ClusterStats s;
  s.valid = true;
  s.clusters = h.counts.x;
  s.listEntries = h.counts.y;
  s.listOverflows = h.counts.z;
  s.tilesWithoutRoom = h.counts.w;
  // Out of room: exact but slower (those pixels test their bin's lights); the next frame has room.
  if (h.counts.w > 0) c.clusterCapacity = std::max(c.clusterCapacity, h.counts.x * 2);
  if (h.counts.z > 0) c.listCapacity = std::max(c.listCapacity, h.counts.y * 2);
  return s;
}

}  // namespace gb
