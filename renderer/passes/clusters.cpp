// Clustered shading's light assignment (method clustered; Olsson, Billeter, Assarsson, HPG 2012),
// four small passes before clustered_lighting: cluster_clear (counters, bin boxes and masks),
// cluster_bounds (occupied clusters and their boxes, per 16x16 tile), cluster_bins (each light
// into the 64x64-pixel bins it reaches) and cluster_lists (each cluster's lights, in order).
#include "renderer/passes/passes.h"

#include "renderer/gpu/cluster_buffers.h"

namespace gb {

static std::vector<BufferUse> withLightReads(const Renderer& r, std::vector<BufferUse> uses) {
  for (const BufferUse& u : lightReads(r, BufferAccess::ComputeRead)) uses.push_back(u);
  return uses;
}

void pushClusterDescriptors(Renderer& r, const PassContext& pc, std::initializer_list<PassImage> images) {
  const ClusterBuffers& c = r.clusters;
  bindGBuffer(r, pc, images, VK_PIPELINE_BIND_POINT_COMPUTE,
              {{gpu::kBindingClusterHeader, c.header.buffer},
               {gpu::kBindingClusters, c.clusters.buffer},
               {gpu::kBindingPixelClusters, c.pixelClusters.buffer},
               {gpu::kBindingLightLists, c.lists.buffer},
               {gpu::kBindingBinBits, c.binBits.buffer},
               {gpu::kBindingBinBoxes, c.binBoxes.buffer}});
}

void addClusterClearPass(FrameGraph& g, Renderer& r) {
  const ClusterBuffers& c = r.clusters;
  g.addPass("cluster_clear", {}, [&r](PassContext& pc) {
    const ClusterBuffers& c = r.clusters;
    gpu::ClusterHeader h{};
    h.capacity = glm::uvec4(c.clusterCapacity, c.listCapacity, 0u, 0u);
    if (c.listsFull) h.counts.y = c.listCapacity + 1;
    h.dispatch = glm::uvec4(0u, 1u, 1u, 0u);
    vkCmdUpdateBuffer(pc.cmd, c.header.buffer, 0, sizeof(h), &h);
    vkCmdFillBuffer(pc.cmd, c.binBoxes.buffer, 0, c.binBoxBytes, 0xFFFFFFFFu);  // empty boxes (cluster_common.glsl)
    vkCmdFillBuffer(pc.cmd, c.binBits.buffer, 0, c.binBitsBytes, 0u);
  }, {{c.header.buffer, BufferAccess::TransferWrite}, {c.binBoxes.buffer, BufferAccess::TransferWrite},
      {c.binBits.buffer, BufferAccess::TransferWrite}});
}

void addClusterBoundsPass(FrameGraph& g, Renderer& r) {
  std::vector<Use> uses;
  for (Use u : gbufferReads(r)) {  // reads only the position source; the others are bound (one layout)
    u.access = Access::SampledCompute;
    uses.push_back(u);
  }
  const ClusterBuffers& c = r.clusters;
  g.addPass("cluster_bounds", uses, [&r](PassContext& pc) {
    pushClusterDescriptors(r, pc, {});
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::cluster_bounds_comp));
    const uint32_t t = gpu::kClusterTile;
    vkCmdDispatch(pc.cmd, (r.options.width + t - 1) / t, (r.options.height + t - 1) / t, 1);
  }, {{c.header.buffer, BufferAccess::ComputeReadWrite}, {c.clusters.buffer, BufferAccess::ComputeReadWrite},
      {c.pixelClusters.buffer, BufferAccess::ComputeReadWrite}, {c.binBoxes.buffer, BufferAccess::ComputeReadWrite}});
}

void addClusterBinsPass(FrameGraph& g, Renderer& r, uint32_t visibleMax) {
  const ClusterBuffers& c = r.clusters;
  g.addPass("cluster_bins", {}, [&r, visibleMax](PassContext& pc) {
    pushClusterDescriptors(r, pc, {});
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::cluster_bins_comp));
    vkCmdDispatch(pc.cmd, (visibleMax + 63) / 64, 1, 1);  // invocations past the visible count return
  }, withLightReads(r, {{c.binBoxes.buffer, BufferAccess::ComputeRead}, {c.binBits.buffer, BufferAccess::ComputeReadWrite}}));
}

void addClusterListsPass(FrameGraph& g, Renderer& r) {
  const ClusterBuffers& c = r.clusters;
  g.addPass("cluster_lists", {}, [&r](PassContext& pc) {
    pushClusterDescriptors(r, pc, {});
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::cluster_lists_comp));
    vkCmdDispatchIndirect(pc.cmd, r.clusters.header.buffer, offsetof(gpu::ClusterHeader, dispatch));
  }, withLightReads(r, {{c.header.buffer, BufferAccess::IndirectRead}, {c.header.buffer, BufferAccess::ComputeReadWrite},
                        {c.clusters.buffer, BufferAccess::ComputeReadWrite}, {c.binBits.buffer, BufferAccess::ComputeRead},
                        {c.lists.buffer, BufferAccess::ComputeReadWrite}}));
}

}  // namespace gb
