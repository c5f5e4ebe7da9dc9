// Fairy sprites in compute (--fairy-splat): fairy_bins puts each visible light's sprite into the
// 64x64-pixel bins its rectangle touches, fairy_splat blends each tile's sprites over hdr in draw
// order (shaders/fairy_bins.comp, fairy_splat.comp). The same image as the fairy_lights raster
// pass (tests/gpu/test_fairies.cpp), without its blended fill.
#include "renderer/passes/passes.h"

namespace gb {

void addFairySplatPasses(FrameGraph& g, Renderer& r, uint32_t visibleMax) {
  const Buffer& bits = r.fairyBits;
  g.addPass("fairy_clear", {}, [&r](PassContext& pc) {
    vkCmdFillBuffer(pc.cmd, r.fairyBits.buffer, 0, r.fairyBitsBytes, 0u);
  }, {{bits.buffer, BufferAccess::TransferWrite}});
  g.addPass("fairy_bins", {}, [&r, visibleMax](PassContext& pc) {
    pushComputeBuffers(r, pc.cmd, {{gpu::kBindingFairyBits, r.fairyBits.buffer}});
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::fairy_bins_comp));
    vkCmdDispatch(pc.cmd, (visibleMax + 63) / 64, 1, 1);
  }, [&] {
    std::vector<BufferUse> b = lightReads(r, BufferAccess::ComputeRead);
    b.push_back({bits.buffer, BufferAccess::ComputeReadWrite});
    return b;
  }());
  std::vector<Use> uses = {{Target::Hdr, Access::StorageCompute}, {Target::DepthStencil, Access::SampledCompute}};
  g.addPass("fairy_splat", uses, [&r](PassContext& pc) {
    const Shader shader = r.options.accumFormat == AccumFormat::Rgba32f ? Shader::fairy_splat_rgba32f_comp
                          : r.options.accumFormat == AccumFormat::Rgba8 ? Shader::fairy_splat_rgba8_comp
                                                                         : Shader::fairy_splat_rgba16f_comp;
    const GraphTarget& hdr = r.targets[size_t(Target::Hdr)];
    const GraphTarget& ds = r.targets[size_t(Target::DepthStencil)];
    VkDescriptorImageInfo images[2] = {{VK_NULL_HANDLE, hdr.image.view, VK_IMAGE_LAYOUT_GENERAL},
                                       {r.samplerPoint, ds.image.depthView, pc.layouts[size_t(Target::DepthStencil)]}};
    VkDescriptorBufferInfo buffer{r.fairyBits.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w[3] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET},
                                 {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    w[0].dstBinding = gpu::kBindingHdrStorage;
    w[0].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    w[0].pImageInfo = &images[0];
    w[1].dstBinding = gpu::kBindingDepth;
    w[1].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w[1].pImageInfo = &images[1];
    w[2].dstBinding = gpu::kBindingFairyBits;
    w[2].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[2].pBufferInfo = &buffer;
    for (VkWriteDescriptorSet& x : w) x.descriptorCount = 1;
    vkCmdBindDescriptorSets(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipelineLayout, gpu::kSetScene, 1, &frameSlot(r).sceneSet, 0,
                            nullptr);
    r.ctx->cmdPushDescriptorSet(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipelineLayout, gpu::kSetPass, 3, w);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, shader));
    const uint32_t tile = gpu::kTileSize;
    vkCmdDispatch(pc.cmd, (r.options.width + tile - 1) / tile, (r.options.height + tile - 1) / tile, 1);
  }, [&] {
    std::vector<BufferUse> b = lightReads(r, BufferAccess::ComputeRead);
    b.push_back({bits.buffer, BufferAccess::ComputeRead});
    return b;
  }());
}

}  // namespace gb
