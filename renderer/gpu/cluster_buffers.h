// Clustered shading's GPU buffers (sized per frame size and light count, grown when a frame ran
// out of room), the grid and depth-slice parameters of a frame, and what the last frame counted.
#pragma once
#include "renderer/gpu/renderer_state.h"

namespace gb {

// The cluster grid of this frame (FrameData::clusterGrid / clusterSlices) for `visibleMax` lights
// at most in the visible list.
void clusterFrameData(const Camera& camera, uint32_t visibleMax, gpu::FrameData& f);

// The cluster grid's shape as its shader reads it (FrameData::gridShape, gridSlices).
void gridFrameData(const GridShape& grid, gpu::FrameData& f);
// The cluster grid (--cluster-assign cpu): assigns this frame's visible lights (r.lights, set up on
// the CPU) to its cells and writes the host-visible buffers the grid lighting pass reads; false
// (and why) when its lists would not fit one storage buffer of at most kGridBudgetBytes.
constexpr VkDeviceSize kGridBudgetBytes = VkDeviceSize(64) << 20;
bool writeClusterGrid(Renderer& r, std::string& why);
// What the grid holds: occupied cells and light entries (FrameStats::clusters).
ClusterStats gridClusterStats(const Renderer& r);

// Creates or grows the buffers for this frame's size and visible-list bound.
void ensureClusterBuffers(Renderer& r, uint32_t visibleMax);
void destroyClusterBuffers(Renderer& r);

// Fairy sprites in compute (--fairy-splat): whether this frame splats them, and why; their bin masks.
bool fairiesInCompute(const GpuContext& ctx, const RenderOptions& o, std::string& reason);
void ensureFairyBits(Renderer& r, uint32_t visibleMax);

// After the frame's fence: the clusters, list entries and overflows it counted (its slot's copy
// of the header); a frame that ran out of room (shaded exactly, more slowly) makes the next one
// get buffers twice the size needed.
ClusterStats collectClusterStats(Renderer& r, const FrameSlot& slot);

}  // namespace gb
