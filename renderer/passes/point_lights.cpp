// Point lights: each light volume shades the pixels it may light, adding into hdr.
//  - per-light mask (default): for batches of 7 lights, Z-fail marks each light's own stencil
//    bit, then the light shades where its bit says the surface is inside the volume and clears
//    it. A light in front of the near plane marks with its back faces (set where the back face
//    lies behind the geometry) and shades with its front faces in front of the geometry: two
//    rasterizations of the volume. A light touching the near plane (its front faces may be
//    clipped, the camera may be inside) marks with both faces (INVERT: odd = inside; a clipped
//    front face only makes the mark conservative) and shades with its back faces. Exact per
//    light; depth clamp keeps back faces beyond the far plane.
//  - shared mask (the sample): front faces in front of the geometry where the shared light_mask
//    marked the pixel (stencil > 128). Lights touching the near plane are drawn as back faces
//    behind or at the geometry, depth test reversed, no mask; depth clamp keeps the far plane.
//  - culling off: front faces in front of the geometry (the sample's full coverage), same near class.
#include "renderer/passes/passes.h"

namespace gb {

static constexpr uint32_t kBatch = 7;  // stencil bits 0..6; bit 7 marks geometry


static void describeShading(Renderer& r, GraphicsPipelineDesc& d) {
  d.vertexShader = "light_volume.vert";
  d.fragmentShader = lightingShader(r, "point_light");
  d.vertexInput = VertexInput::Position;
  d.layout = lightingLayout(r);
  d.depthClamp = true;
  d.stencilTest = true;
  d.colorBlend[0] = BlendState{true};  // additive: ONE, ONE
  d.rasterOrderColor = singlePass(r);
}

// Per-light stencil bits: mask 7 lights, then shade them, batch after batch. Lights
// [0, stencilCount) are in front of the near plane, the rest touch it (light_culling.cpp).
static void drawPerLight(Renderer& r, PassContext& pc) {
  VkPipeline mask = graphicsPipeline(r, pc, "point_light.mask_bits", [&r](GraphicsPipelineDesc& d) {
    d.vertexShader = "light_volume.vert";
    d.vertexInput = VertexInput::Position;
    d.layout = lightingLayout(r);
    d.depthTest = true;
    d.depthCompare = closerOrEqual(r);  // fails where the face lies behind the geometry
    d.depthClamp = true;
    d.stencilTest = true;
    d.stencil = stencil(VK_COMPARE_OP_ALWAYS, 0, VK_STENCIL_OP_INVERT);
    d.dynamicStencilMasks = true;
    for (BlendState& b : d.colorBlend) b.writeMask = 0;
  });
  // Front faces in front of the geometry, where the back faces marked: the surface is inside.
  // The bit is cleared whether or not the front face passes the depth test.
  VkPipeline shadeFront = graphicsPipeline(r, pc, "point_light.per_light_front", [&r](GraphicsPipelineDesc& d) {
    describeShading(r, d);
    d.depthTest = true;
    d.depthCompare = closerOrEqual(r);
    d.stencil = stencil(VK_COMPARE_OP_EQUAL, 0, VK_STENCIL_OP_ZERO, VK_STENCIL_OP_ZERO);
    d.dynamicStencilMasks = true;
  });
  VkPipeline shadeBack = graphicsPipeline(r, pc, "point_light.per_light", [&r](GraphicsPipelineDesc& d) {
    describeShading(r, d);
    d.stencil = stencil(VK_COMPARE_OP_EQUAL, 0, VK_STENCIL_OP_KEEP, VK_STENCIL_OP_ZERO);  // shade, clear the bit
    d.dynamicStencilMasks = true;
  });
  const uint32_t n = uint32_t(r.lights.visible.size());
  for (uint32_t first = 0; first < n; first += kBatch) {
    uint32_t count = std::min(kBatch, n - first);
    bindPipeline(pc, mask);
    vkCmdSetStencilCompareMask(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);  // ALWAYS: unused, but dynamic
    for (uint32_t k = 0; k < count; ++k) {
      bool inFront = first + k < r.lights.stencilCount;
      vkCmdSetCullMode(pc.cmd, inFront ? VK_CULL_MODE_FRONT_BIT : VK_CULL_MODE_NONE);
      vkCmdSetStencilWriteMask(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1u << k);
      drawLightVolumes(r, pc.cmd, first + k, 1);
    }
    VkPipeline bound = VK_NULL_HANDLE;
    for (uint32_t k = 0; k < count; ++k) {
      bool inFront = first + k < r.lights.stencilCount;
      if (VkPipeline p = inFront ? shadeFront : shadeBack; p != bound) {
        bindPipeline(pc, p);
        bound = p;
      }
      // Front faces, or back faces: those are never clipped by the near plane.
      vkCmdSetCullMode(pc.cmd, inFront ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_FRONT_BIT);
      vkCmdSetStencilCompareMask(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1u << k);
      vkCmdSetStencilWriteMask(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1u << k);
      vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1u << k);
      drawLightVolumes(r, pc.cmd, first + k, 1);
    }
  }
}

// Shared mask or no culling: instanced front faces, then the near-plane class.
static void drawInstanced(Renderer& r, PassContext& pc) {
  const bool culled = r.options.stencilCulling;
  VkPipeline front = graphicsPipeline(r, pc, culled ? "point_light.shared" : "point_light.unculled",
                                      [&r, culled](GraphicsPipelineDesc& d) {
                                        describeShading(r, d);
                                        d.depthTest = true;
                                        d.depthCompare = closerOrEqual(r);
                                        d.stencil = culled ? stencil(VK_COMPARE_OP_LESS, 0xFF)    // 128 < stencil
                                                           : stencil(VK_COMPARE_OP_EQUAL, 0x80);  // any geometry
                                      });
  VkPipeline nearClass = graphicsPipeline(r, pc, "point_light.near", [&r](GraphicsPipelineDesc& d) {
    describeShading(r, d);
    d.depthTest = true;
    d.depthCompare = fartherOrEqual(r);
    d.stencil = stencil(VK_COMPARE_OP_EQUAL, 0x80);
  });
  vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, gpu::kStencilGeometry);
  bindPipeline(pc, front);
  vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_BACK_BIT);
  drawLightVolumes(r, pc.cmd, 0, r.lights.stencilCount);
  bindPipeline(pc, nearClass);
  vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_FRONT_BIT);
  drawLightVolumes(r, pc.cmd, r.lights.stencilCount, uint32_t(r.lights.visible.size()) - r.lights.stencilCount);
}

void addPointLightPass(FrameGraph& g, Renderer& r) {
  const bool perLight = r.options.stencilCulling && r.options.stencilMask == StencilMask::PerLight;
  std::vector<Use> uses = gbufferReads(r);
  uses.push_back(hdrUse(Access::ColorBlend));
  uses.push_back(depthStencilUse(perLight ? Access::DepthTestStencilWrite : Access::DepthStencilRead));
  // Declared even when coverage is off (then a 1x1 image nobody writes): the shader binds it.
  uses.push_back({Target::CoverageMasked, Access::StorageFragment});
  g.addPass("point_lights", uses, [&r, perLight](PassContext& pc) {
    const GraphTarget& coverage = r.targets[size_t(Target::CoverageMasked)];
    bindGBuffer(r, pc, {{gpu::kBindingCoverage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, coverage.image.view,
                         VK_IMAGE_LAYOUT_GENERAL}});
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    if (r.statisticsActive) vkCmdBeginQuery(pc.cmd, r.statisticsPool, 0, 0);
    if (perLight)
      drawPerLight(r, pc);
    else
      drawInstanced(r, pc);
    if (r.statisticsActive) vkCmdEndQuery(pc.cmd, r.statisticsPool, 0);
  });
}

}  // namespace gb
