// G-buffer: albedo_specular, normal_shadow (with the shadow-map compare), eye depth, and the
// depth/stencil target where geometry writes stencil 128; on request primitive_id, the stored
// position and the motion target (pixels toward the previous frame's camera, FrameData).
#include "renderer/gpu/gpu_scene.h"
#include "renderer/passes/passes.h"

namespace gb {

std::vector<Target> gbufferColourTargets(const Renderer& r) {
  std::vector<Target> out = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth};
  if (primitiveIdOn(*r.ctx, r.options)) out.push_back(Target::PrimitiveId);
  if (r.options.position != PositionSource::Depth) out.push_back(Target::Position);
  if (r.options.motion) out.push_back(Target::Motion);
  return out;
}

void addGBufferPass(FrameGraph& g, Renderer& r) {
  Use depth{Target::DepthStencil, Access::DepthStencilWrite, true};
  depth.clearValue.depthStencil = {farDepth(r), 0};
  // Colour attachments in this order = the shader's output locations (gbuffer.frag), cleared to 0
  // (depth 0: no geometry) here or before, by clear_gbuffer (then loaded).
  std::vector<Use> uses;
  for (Target t : gbufferColourTargets(r)) {
    Use u{t, Access::ColorWrite, !r.computeClear};
    u.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
    uses.push_back(u);
  }
  const bool primitiveId = primitiveIdOn(*r.ctx, r.options);
  const bool position = r.options.position != PositionSource::Depth;
  const bool motion = r.options.motion;
  uses.push_back(depth);
  uses.push_back({Target::ShadowMap, Access::SampledFragment});
  // [primitive_id][stored position][motion]
  static const Shader kFragment[2][2][2] = {
      {{Shader::gbuffer_frag, Shader::gbuffer_motion_frag},
       {Shader::gbuffer_position_frag, Shader::gbuffer_position_motion_frag}},
      {{Shader::gbuffer_id_frag, Shader::gbuffer_id_motion_frag},
       {Shader::gbuffer_id_position_frag, Shader::gbuffer_id_position_motion_frag}}};
  const Shader fragment = kFragment[primitiveId][position][motion];
  g.addPass("gbuffer", uses, [&r, fragment](PassContext& pc) {
    auto describe = [&](DrawVariantBits v) {
      return [&r, v, fragment](GraphicsPipelineDesc& d) {
        d.vertexShader = Shader::gbuffer_vert;
        d.fragmentShader = fragment;
        d.vertexInput = VertexInput::SceneVertex;
        sceneGeometryDepthStencil(r, d);
        d.spec.push_back({gpu::kSpecAlphaTest, v.alpha ? 1u : 0u});
        d.spec.push_back({gpu::kSpecNormalMap, v.normalMap ? 1u : 0u});
        d.spec.push_back({gpu::kSpecBaseColorTexture, v.baseTexture ? 1u : 0u});
      };
    };
    const GraphTarget& shadow = r.targets[size_t(Target::ShadowMap)];
    bindDescriptors(r, pc.cmd, r.pipelineLayout,
                    {{gpu::kBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, shadow.image.depthView,
                      pc.layouts[size_t(Target::ShadowMap)], r.samplerShadow}});
    for (uint32_t v = 0; v < kDrawVariants; ++v) {  // drawVariant() (renderer/gpu/gpu_scene.h)
      if (r.drawVariants[v] == r.drawVariants[v + 1]) continue;
      const std::string id = std::string(shaderName(fragment)) + drawVariantName(v);
      bindPipeline(pc, graphicsPipeline(r, pc, id, describe(drawVariantBits(v))));
      vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, gpu::kStencilGeometry);
      drawInstances(r, pc.cmd, r.drawVariants[v], r.drawVariants[v + 1], false);
    }
  });
}

}  // namespace gb
