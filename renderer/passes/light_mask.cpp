// Light mask: back faces of every stencil-class light volume, no fragment shader. Where a back
// face lies behind the geometry (depth test fails) the stencil is incremented above 128, so the
// point-light pass shades only pixels with geometry inside some light volume. Depth clamp keeps
// back faces beyond the far plane (they clamp to it and still fail behind geometry).
#include "renderer/passes/passes.h"

namespace gb {

void addLightMaskPass(FrameGraph& g, Renderer& r) {
  std::vector<Use> uses = gbufferReads(r);  // same subpass inputs as its neighbours
  uses.push_back(hdrUse(Access::ColorBlend));
  uses.push_back(depthStencilUse(Access::DepthTestStencilWrite));
  g.addPass("light_mask", uses, [&r](PassContext& pc) {
    VkPipeline p = graphicsPipeline(r, pc, "light_mask", [&r](GraphicsPipelineDesc& d) {
      d.vertexShader = Shader::light_volume_vert;
      d.vertexInput = VertexInput::Position;
      d.layout = lightingLayout(r);
      d.depthTest = true;
      d.depthCompare = closerOrEqual(r);
      d.depthClamp = true;
      d.stencilTest = true;
      // Only geometry pixels (bit 7 set) count; increment where the back face is behind them.
      d.stencil = stencil(VK_COMPARE_OP_EQUAL, 0x80, VK_STENCIL_OP_INCREMENT_AND_CLAMP);
      for (BlendState& b : d.colorBlend) b.writeMask = 0;
    });
    bindGBuffer(r, pc);
    bindPipeline(pc, p);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_FRONT_BIT);
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, gpu::kStencilGeometry);
    drawLightVolumes(r, pc.cmd, 0, r.lights.stencilCount);
  });
}

}  // namespace gb
