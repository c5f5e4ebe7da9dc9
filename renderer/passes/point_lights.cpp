// Point lights: each light volume shades the pixels it may light, adding into hdr.
//  - stencil class, culling on: front faces in front of the geometry, where the mask marked
//    the pixel (stencil > 128);
//  - stencil class, culling off: front faces in front of the geometry (the sample's full coverage);
//  - near class (the volume touches the near plane or contains the camera): back faces behind
//    or at the geometry, depth test reversed, no mask; depth clamp keeps the far plane.
#include "renderer/passes/passes.h"

namespace gb {

void addPointLightPass(FrameGraph& g, Renderer& r) {
  std::vector<Use> uses = gbufferReads(r);
  uses.push_back(hdrUse(Access::ColorBlend));
  uses.push_back(depthStencilUse(Access::DepthStencilRead));
  // Declared even when coverage is off (then a 1x1 image nobody writes): the shader binds it.
  uses.push_back({Target::CoverageMasked, Access::StorageFragment});
  g.addPass("point_lights", uses, [&r](PassContext& pc) {
    auto describe = [&r](bool culled, bool nearClass) {
      return [&r, culled, nearClass](GraphicsPipelineDesc& d) {
        d.vertexShader = "light_volume.vert";
        d.fragmentShader = lightingShader(r, "point_light");
        d.vertexInput = VertexInput::Position;
        d.layout = lightingLayout(r);
        d.depthTest = true;
        d.depthCompare = nearClass ? fartherOrEqual(r) : closerOrEqual(r);
        d.depthClamp = true;
        d.stencilTest = true;
        d.stencil = culled ? stencil(VK_COMPARE_OP_LESS, 0xFF)   // 128 < stencil: marked by the mask
                           : stencil(VK_COMPARE_OP_EQUAL, 0x80);  // any geometry pixel
        d.colorBlend[0] = BlendState{true};  // additive: ONE, ONE
        d.rasterOrderColor = singlePass(r);
      };
    };
    const bool culled = r.options.stencilCulling;
    VkPipeline front = graphicsPipeline(r, pc, culled ? "point_light.culled" : "point_light.unculled",
                                        describe(culled, false));
    VkPipeline nearClass = graphicsPipeline(r, pc, "point_light.near", describe(false, true));
    const GraphTarget& coverage = r.targets[size_t(Target::CoverageMasked)];
    bindGBuffer(r, pc, {{gpu::kBindingCoverage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, coverage.image.view,
                         VK_IMAGE_LAYOUT_GENERAL}});
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, gpu::kStencilGeometry);
    bool stats = r.statisticsPool != VK_NULL_HANDLE;
    if (stats) vkCmdBeginQuery(pc.cmd, r.statisticsPool, 0, 0);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, front);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_BACK_BIT);
    drawLightVolumes(r, pc.cmd, 0, r.lights.stencilCount);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, nearClass);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_FRONT_BIT);
    drawLightVolumes(r, pc.cmd, r.lights.stencilCount, uint32_t(r.lights.visible.size()) - r.lights.stencilCount);
    if (stats) vkCmdEndQuery(pc.cmd, r.statisticsPool, 0);
  });
}

}  // namespace gb
