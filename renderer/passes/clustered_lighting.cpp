// Clustered deferred lighting (method clustered): a compute pass over the pixels that reads the
// G-buffer once and writes hdr = sun + ambient + the lights of the pixel's cluster
// (shaders/clustered_lighting.comp); the cluster passes (clusters.cpp) built the lists. It also
// copies the cluster counters for the CPU (FrameStats::clusters, the next frame's buffer sizes).
// Renderer::lightingPixels picks the shader of one or two pixels an invocation (the same image).
#include "renderer/passes/passes.h"

namespace gb {

void addClusteredLightingPass(FrameGraph& g, Renderer& r) {
  std::vector<Use> uses = gbufferReads(r);  // SampledCompute: clustered is never single-pass
  for (Use& u : uses) u.access = Access::SampledCompute;
  uses.push_back({Target::Hdr, Access::StorageCompute});
  uses.push_back({Target::CoverageMasked, Access::StorageCompute});  // bound even when off (1x1)
  const ClusterBuffers& c = r.clusters;
  g.addPass("clustered_lighting", uses, [&r](PassContext& pc) {
    // Two pixels an invocation (r.lightingPixels, GBLENS_LIGHTING_PIXELS=2): the same image, the same
    // dispatch (a workgroup is still one tile), half the invocations.
    const bool two = r.lightingPixels == 2;
    const Shader shader =
        r.options.accumFormat == AccumFormat::Rgba32f
            ? (two ? Shader::clustered_lighting2_rgba32f_comp : Shader::clustered_lighting_rgba32f_comp)
        : r.options.accumFormat == AccumFormat::Rgba8
            ? (two ? Shader::clustered_lighting2_rgba8_comp : Shader::clustered_lighting_rgba8_comp)
            : (two ? Shader::clustered_lighting2_rgba16f_comp : Shader::clustered_lighting_rgba16f_comp);
    const ClusterBuffers& c = r.clusters;
    VkBufferCopy copy{0, 0, sizeof(gpu::ClusterHeader)};
    vkCmdCopyBuffer(pc.cmd, c.header.buffer, frameSlot(r).clusterHeader.buffer, 1, &copy);
    const GraphTarget& hdr = r.targets[size_t(Target::Hdr)];
    const GraphTarget& coverage = r.targets[size_t(Target::CoverageMasked)];
    pushClusterDescriptors(
        r, pc,
        {{gpu::kBindingHdrStorage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr.image.view, VK_IMAGE_LAYOUT_GENERAL},
         {gpu::kBindingCoverage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, coverage.image.view, VK_IMAGE_LAYOUT_GENERAL}});
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, shader));
    const uint32_t tile = gpu::kTileSize;
    vkCmdDispatch(pc.cmd, (r.options.width + tile - 1) / tile, (r.options.height + tile - 1) / tile, 1);
  }, [&] {
    std::vector<BufferUse> b = lightReads(r, BufferAccess::ComputeRead);
    b.insert(b.end(), {{c.header.buffer, BufferAccess::TransferRead},
                       {frameSlot(r).clusterHeader.buffer, BufferAccess::TransferWrite},
                       {c.clusters.buffer, BufferAccess::ComputeRead}, {c.pixelClusters.buffer, BufferAccess::ComputeRead},
                       {c.lists.buffer, BufferAccess::ComputeRead}, {c.binBits.buffer, BufferAccess::ComputeRead}});
    return b;
  }());
}

}  // namespace gb
