// Fairy lights: a camera-facing sprite at each visible light, alpha-blended (premultiplied),
// depth-tested against the scene.
#include "renderer/passes/passes.h"

namespace gb {

void addFairyPass(FrameGraph& g, Renderer& r) {
  // No G-buffer reads: the same pass serves deferred, tiled and forward frames.
  std::vector<Use> uses = {hdrUse(Access::ColorBlend)};
  uses.push_back(depthStencilUse(Access::DepthStencilRead));
  g.addPass("fairy_lights", uses, [&r](PassContext& pc) {
    VkPipeline p = graphicsPipeline(r, pc, "fairy", [&r](GraphicsPipelineDesc& d) {
      d.vertexShader = Shader::fairy_vert;
      d.fragmentShader = Shader::fairy_frag;
      d.layout = lightingLayout(r);
      d.depthTest = true;
      d.depthCompare = closerOrEqual(r);
      d.colorBlend[0] = BlendState{true, VK_BLEND_FACTOR_ONE, VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA, VK_BLEND_FACTOR_ONE,
                                   VK_BLEND_FACTOR_ONE_MINUS_SRC_ALPHA};
    });
    bindDescriptors(r, pc.cmd, lightingLayout(r), {});
    bindPipeline(pc, p);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);
    // The visible count as the GPU has it (light setup on the GPU leaves it there).
    vkCmdDrawIndirect(pc.cmd, frameSlot(r).lightCountBuffer.buffer, offsetof(gpu::LightCounts, fairyDraw), 1, 0);
  }, [&r] {
    std::vector<BufferUse> b = lightReads(r, BufferAccess::VertexRead);
    b.push_back({frameSlot(r).lightCountBuffer.buffer, BufferAccess::IndirectRead});
    return b;
  }());
}

}  // namespace gb
