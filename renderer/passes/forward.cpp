// Forward shading (method forward): the scene's instances drawn once with a fragment shader
// that evaluates the material, the sun and every visible point light, writing hdr directly.
// No G-buffer: albedo_specular, normal_shadow, depth (and position, primitive_id) are not
// produced, and captures and views list them as unavailable (targetUnavailable).
#include "renderer/gpu/gpu_scene.h"
#include "renderer/passes/passes.h"

namespace gb {

void addForwardPass(FrameGraph& g, Renderer& r) {
  Use depth{Target::DepthStencil, Access::DepthStencilWrite, true};
  depth.clearValue.depthStencil = {farDepth(r), 0};
  // Declared even when coverage is off (then a 1x1 image nobody writes): the shader binds it.
  std::vector<Use> uses = {hdrUse(Access::ColorWrite, true), depth, {Target::ShadowMap, Access::SampledFragment},
                           {Target::CoverageMasked, Access::StorageFragment}};
  g.addPass("forward", uses, [&r](PassContext& pc) {
    auto describe = [&](DrawVariantBits v) {
      return [&r, v](GraphicsPipelineDesc& d) {
        d.vertexShader = Shader::gbuffer_vert;
        d.fragmentShader = v.alpha ? Shader::forward_alpha_frag : Shader::forward_frag;  // early depth tests when opaque
        d.vertexInput = VertexInput::SceneVertex;
        sceneGeometryDepthStencil(r, d);  // stencil 128 where geometry is, as the G-buffer pass writes it
        d.spec.push_back({gpu::kSpecAlphaTest, v.alpha ? 1u : 0u});
        d.spec.push_back({gpu::kSpecNormalMap, v.normalMap ? 1u : 0u});
        d.spec.push_back({gpu::kSpecBaseColorTexture, v.baseTexture ? 1u : 0u});
      };
    };
    const GraphTarget& shadow = r.targets[size_t(Target::ShadowMap)];
    const GraphTarget& coverage = r.targets[size_t(Target::CoverageMasked)];
    bindDescriptors(r, pc.cmd, r.pipelineLayout,
                    {{gpu::kBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, shadow.image.depthView,
                      pc.layouts[size_t(Target::ShadowMap)], r.samplerShadow},
                     {gpu::kBindingCoverage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, coverage.image.view, VK_IMAGE_LAYOUT_GENERAL}});
    // The G-buffer's draw order: opaque before alpha-tested, by material within a variant.
    for (uint32_t v = 0; v < kDrawVariants; ++v) {  // drawVariant() (renderer/gpu/gpu_scene.h)
      if (r.drawVariants[v] == r.drawVariants[v + 1]) continue;
      const std::string id = std::string("forward") + drawVariantName(v);
      bindPipeline(pc, graphicsPipeline(r, pc, id, describe(drawVariantBits(v))));
      vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, gpu::kStencilGeometry);
      drawInstances(r, pc.cmd, r.drawVariants[v], r.drawVariants[v + 1], false);
    }
  });
}

}  // namespace gb
