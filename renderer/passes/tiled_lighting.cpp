// Tiled deferred lighting (method tiled): a compute pass over 16x16 tiles that reads the
// G-buffer once per pixel, bins the visible lights against each tile's box of surface points
// (its depth bounds and screen extent), and writes hdr = sun + ambient + the tile's lights.
// It replaces the directional, light-mask and point-light passes (shaders/tiled_lighting.comp).
#include "renderer/passes/passes.h"

namespace gb {

void addTiledLightingPass(FrameGraph& g, Renderer& r) {
  std::vector<Use> uses = gbufferReads(r);  // SampledCompute: tiled is never single-pass
  for (Use& u : uses) u.access = Access::SampledCompute;
  uses.push_back({Target::Hdr, Access::StorageCompute});
  uses.push_back({Target::CoverageMasked, Access::StorageCompute});  // the shader binds it even when off (1x1)
  g.addPass("tiled_lighting", uses, [&r](PassContext& pc) {
    // The storage image's format is part of the shader (GLSL layout qualifier).
    const Shader shader = r.options.accumFormat == AccumFormat::Rgba32f ? Shader::tiled_lighting_rgba32f_comp
                          : r.options.accumFormat == AccumFormat::Rgba8 ? Shader::tiled_lighting_rgba8_comp
                                                                         : Shader::tiled_lighting_rgba16f_comp;
    VkPipeline p = computePipeline(r, shader);
    const GraphTarget& hdr = r.targets[size_t(Target::Hdr)];
    const GraphTarget& coverage = r.targets[size_t(Target::CoverageMasked)];
    bindGBuffer(r, pc,
                {{gpu::kBindingHdrStorage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, hdr.image.view, VK_IMAGE_LAYOUT_GENERAL},
                 {gpu::kBindingCoverage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, coverage.image.view, VK_IMAGE_LAYOUT_GENERAL}},
                VK_PIPELINE_BIND_POINT_COMPUTE);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p);
    const uint32_t tile = gpu::kTileSize;
    vkCmdDispatch(pc.cmd, (r.options.width + tile - 1) / tile, (r.options.height + tile - 1) / tile, 1);
  }, lightReads(r, BufferAccess::ComputeRead));
}

}  // namespace gb
