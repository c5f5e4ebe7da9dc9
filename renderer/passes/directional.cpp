// Directional light: the sun + ambient over every geometry pixel (stencil == 128), full screen.
// First writer of hdr: clears it, so sky-less frames have defined pixels.
#include "renderer/passes/passes.h"

namespace gb {

void addDirectionalLightPass(FrameGraph& g, Renderer& r) {
  std::vector<Use> uses = gbufferReads(r);
  uses.push_back(hdrUse(Access::ColorWrite, true));
  uses.push_back(depthStencilUse(Access::DepthStencilRead));
  g.addPass("directional_light", uses, [&r](PassContext& pc) {
    VkPipeline p = graphicsPipeline(r, pc, "directional", [&r](GraphicsPipelineDesc& d) {
      d.vertexShader = Shader::fullscreen_vert;
      d.fragmentShader = lightingShader(r, Shader::directional_frag, Shader::directional_input_frag);
      d.layout = lightingLayout(r);
      d.stencilTest = true;  // only where geometry wrote 128: the sky is left alone
      d.stencil = stencil(VK_COMPARE_OP_EQUAL, 0xFF);
      d.rasterOrderColor = singlePass(r);
    });
    bindGBuffer(r, pc);
    bindPipeline(pc, p);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, gpu::kStencilGeometry);
    vkCmdDraw(pc.cmd, 3, 1, 0, 0);
  });
}

}  // namespace gb
