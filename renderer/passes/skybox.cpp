// Skybox: a procedural gradient drawn at the far plane, depth-tested against the G-buffer depth
// so it lands exactly where no geometry was drawn.
#include "renderer/passes/passes.h"

namespace gb {

void addSkyboxPass(FrameGraph& g, Renderer& r) {
  // No G-buffer reads: the same pass serves deferred, tiled and forward frames.
  std::vector<Use> uses = {hdrUse(Access::ColorBlend)};
  uses.push_back(depthStencilUse(Access::DepthStencilRead));
  r.skyQueryActive = true;
  g.addPass("skybox", uses, [&r](PassContext& pc) {
    VkPipeline p = graphicsPipeline(r, pc, "skybox", [&r](GraphicsPipelineDesc& d) {
      d.vertexShader = Shader::fullscreen_vert;
      d.fragmentShader = Shader::sky_frag;
      d.layout = lightingLayout(r);
      d.depthTest = true;
      d.depthCompare = closerOrEqual(r);  // passes only at the cleared far depth
    });
    bindDescriptors(r, pc.cmd, lightingLayout(r), {});
    bindPipeline(pc, p);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);
    // Count the sky pixels (depth test passed): zero lets later frames with the same camera skip.
    if (r.skyQueryActive) vkCmdBeginQuery(pc.cmd, frameSlot(r).occlusionPool, 0, 0);
    vkCmdDraw(pc.cmd, 3, 1, 0, 0);
    if (r.skyQueryActive) vkCmdEndQuery(pc.cmd, frameSlot(r).occlusionPool, 0);
  });
}

}  // namespace gb
