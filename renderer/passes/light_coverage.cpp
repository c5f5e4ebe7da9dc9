// Light coverage (view 9): every visible light volume counted per pixel in screen space, with
// no depth or stencil test. Computed only when coverage is requested.
#include "renderer/passes/passes.h"

namespace gb {

void addLightCoveragePass(FrameGraph& g, Renderer& r) {
  // No G-buffer reads: the same pass serves deferred, tiled and forward frames.
  std::vector<Use> uses = {hdrUse(Access::ColorBlend)};
  uses.push_back(depthStencilUse(Access::DepthStencilRead));
  uses.push_back({Target::CoverageFull, Access::StorageFragment});
  g.addPass("light_coverage", uses, [&r](PassContext& pc) {
    VkPipeline p = graphicsPipeline(r, pc, "light_coverage", [&r](GraphicsPipelineDesc& d) {
      d.vertexShader = Shader::light_volume_vert;
      d.fragmentShader = Shader::light_coverage_frag;
      d.vertexInput = VertexInput::Position;
      d.layout = lightingLayout(r);
      d.depthClamp = true;
      for (BlendState& b : d.colorBlend) b.writeMask = 0;
    });
    const GraphTarget& coverage = r.targets[size_t(Target::CoverageFull)];
    bindDescriptors(r, pc.cmd, lightingLayout(r),
                    {{gpu::kBindingCoverage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, coverage.image.view, VK_IMAGE_LAYOUT_GENERAL}});
    bindPipeline(pc, p);
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, gpu::kStencilGeometry);
    // Front faces cover the volume's screen footprint; near-class volumes are clipped at the
    // near plane, so their back faces are counted instead.
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_BACK_BIT);
    drawLightVolumes(r, pc.cmd, 0, r.lights.stencilCount);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_FRONT_BIT);
    drawLightVolumes(r, pc.cmd, r.lights.stencilCount, uint32_t(r.lights.visible.size()) - r.lights.stencilCount);
  });
}

}  // namespace gb
