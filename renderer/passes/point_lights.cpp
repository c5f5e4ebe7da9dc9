// Point lights: each light volume shades the pixels it may light, adding into hdr.
//  - per-light mask (default): Z-fail marks a stencil bit per light, then the light shades where
//    its bit says the surface is inside the volume and clears it. Lights in front of the near
//    plane come in layers whose volumes cover disjoint pixels (renderer/frame/light_culling.cpp), so a layer
//    shares one bit and is drawn instanced: back faces mark where they lie behind the geometry,
//    front faces in front of the geometry shade where marked (two rasterizations, two draws per
//    layer). A light touching the near plane (front faces may be clipped, the camera may be
//    inside) has a bit of its own: both faces mark (INVERT: odd = inside; a clipped front face
//    only makes the mark conservative) and its back faces shade. Up to 7 layers or lights share
//    a batch (bits 0..6); exact per light; depth clamp keeps back faces beyond the far plane.
//    Without layers (--stencil-layers off; the default on a GPU) each light is its own group.
//  - shared mask (the sample): front faces in front of the geometry where the shared light_mask
//    marked the pixel (stencil > 128). Lights touching the near plane are drawn as back faces
//    behind or at the geometry, depth test reversed, no mask; depth clamp keeps the far plane.
//  - culling off: front faces in front of the geometry (the sample's full coverage), same near class.
#include "renderer/passes/passes.h"

namespace gb {

static constexpr size_t kBatch = 7;  // stencil bits 0..6; bit 7 marks geometry


static void describeShading(Renderer& r, GraphicsPipelineDesc& d) {
  d.vertexShader = Shader::light_volume_vert;
  d.fragmentShader = lightingShader(r, Shader::point_light_frag, Shader::point_light_input_frag);
  d.vertexInput = VertexInput::Position;
  d.layout = lightingLayout(r);
  d.depthClamp = true;
  d.stencilTest = true;
  d.colorBlend[0] = BlendState{true};  // additive: ONE, ONE
  d.rasterOrderColor = singlePass(r);
}

// Per-light stencil bits: mask 7 groups, then shade them, batch after batch.
static void drawPerLight(Renderer& r, PassContext& pc) {
  VkPipeline mask = graphicsPipeline(r, pc, "point_light.mask_bits", [&r](GraphicsPipelineDesc& d) {
    d.vertexShader = Shader::light_volume_vert;
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
  // A group shares a stencil bit: a layer of the stencil class (one light each without layers,
  // --stencil-layers off), or one near-plane light.
  struct Group {
    uint32_t first, count;
    bool inFront;
  };
  std::vector<Group> groups;
  const std::vector<uint32_t>& starts = r.lights.layerStarts;
  for (size_t k = 0; k + 1 < starts.size(); ++k) groups.push_back({starts[k], starts[k + 1] - starts[k], true});
  if (starts.empty())
    for (uint32_t i = 0; i < r.lights.stencilCount; ++i) groups.push_back({i, 1, true});
  for (uint32_t i = r.lights.stencilCount; i < r.lights.visible.size(); ++i) groups.push_back({i, 1, false});
  for (size_t first = 0; first < groups.size(); first += kBatch) {
    const size_t count = std::min<size_t>(kBatch, groups.size() - first);
    bindPipeline(pc, mask);
    vkCmdSetStencilCompareMask(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);  // ALWAYS: unused, but dynamic
    for (size_t k = 0; k < count; ++k) {
      const Group& g = groups[first + k];
      vkCmdSetCullMode(pc.cmd, g.inFront ? VK_CULL_MODE_FRONT_BIT : VK_CULL_MODE_NONE);
      vkCmdSetStencilWriteMask(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1u << k);
      drawLightVolumes(r, pc.cmd, g.first, g.count);
    }
    VkPipeline bound = VK_NULL_HANDLE;
    for (size_t k = 0; k < count; ++k) {
      const Group& g = groups[first + k];
      if (VkPipeline p = g.inFront ? shadeFront : shadeBack; p != bound) {
        bindPipeline(pc, p);
        bound = p;
      }
      // Front faces, or back faces: those are never clipped by the near plane.
      vkCmdSetCullMode(pc.cmd, g.inFront ? VK_CULL_MODE_BACK_BIT : VK_CULL_MODE_FRONT_BIT);
      vkCmdSetStencilCompareMask(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1u << k);
      vkCmdSetStencilWriteMask(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1u << k);
      vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 1u << k);
      drawLightVolumes(r, pc.cmd, g.first, g.count);
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
  const bool perLight = perLightMask(r.options, r.method);
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
