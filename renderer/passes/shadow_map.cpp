// Shadow map: depth only from the sun's orthographic view, with depth bias. Opaque casters have
// no fragment stage; alpha-tested ones cut out the same texels as in the G-buffer.
#include "renderer/gpu/gpu_scene.h"
#include "renderer/passes/passes.h"

namespace gb {

void addShadowMapPass(FrameGraph& g, Renderer& r) {
  Use depth{Target::ShadowMap, Access::DepthStencilWrite, true};
  depth.clearValue.depthStencil = {1.0f, 0};
  g.beginRenderPass("shadow_map");
  g.addPass("shadow_map", {depth}, [&r](PassContext& pc) {
    auto describe = [&](bool alpha) {
      return [&r, alpha](GraphicsPipelineDesc& d) {
        d.vertexShader = Shader::shadow_vert;
        if (alpha) d.fragmentShader = Shader::shadow_frag;
        d.vertexInput = VertexInput::SceneVertex;
        d.vertexAttributes = 0b01101;  // position, uv0, uv1
        d.depthTest = d.depthWrite = true;
        d.depthCompare = VK_COMPARE_OP_LESS_OR_EQUAL;
        d.depthBias = true;
        d.depthClamp = true;  // casters between the sun and the fitted near plane still cast
        d.spec.push_back({gpu::kSpecAlphaTest, alpha ? 1u : 0u});
      };
    };
    VkPipeline opaque = graphicsPipeline(r, pc, "shadow.opaque", describe(false));
    VkPipeline alpha = graphicsPipeline(r, pc, "shadow.alpha", describe(true));
    bindDescriptors(r, pc.cmd, r.pipelineLayout, {});
    vkCmdSetDepthBias(pc.cmd, r.options.shadowBiasConstant, r.options.shadowBiasClamp, r.options.shadowBiasSlope);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);
    // Opaque variants [0, 4) need no fragment stage; alpha-tested ones [4, 8) cut out texels.
    bindPipeline(pc, opaque);
    drawInstances(r, pc.cmd, r.drawVariants[0], r.drawVariants[4], true);
    bindPipeline(pc, alpha);
    drawInstances(r, pc.cmd, r.drawVariants[4], r.drawVariants[kDrawVariants], true);
  });
  g.endRenderPass();
}

}  // namespace gb
