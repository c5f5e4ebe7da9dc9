// G-buffer resolve (--gbuffer visibility): a compute pass over the pixels that reads each one's
// visibility id, rebuilds its surface from the triangle's three vertices (the pixel centre's ray
// on the triangle's plane) and writes the targets the G-buffer pass writes (gbufferColourTargets:
// albedo_specular, normal_shadow, depth, and primitive_id, position, motion when asked), through
// their unsigned storage views, so every later pass reads the same targets (shaders/gbuffer_resolve.comp).
// One dispatch per texture group (gpu/visibility_scene.cpp), its two textures pushed as the
// G-buffer pass pushes a material's; the dispatches write disjoint pixels of the same images, a
// barrier between them (the graph sees one pass).
#include "renderer/passes/passes.h"
#include "renderer/vk/check.h"

namespace gb {

static uint32_t resolveBinding(Target t) {
  switch (t) {
    case Target::AlbedoSpecular: return gpu::kResolveBindingAlbedo;
    case Target::NormalShadow: return gpu::kResolveBindingNormal;
    case Target::Depth: return gpu::kResolveBindingDepth;
    case Target::PrimitiveId: return gpu::kResolveBindingPrimitiveId;
    case Target::Position: return gpu::kResolveBindingPosition;
    case Target::Motion: return gpu::kResolveBindingMotion;
    default: GB_ASSERT(!"a target gbuffer_resolve does not write"); return 0;
  }
}

static VkPipeline resolvePipeline(Renderer& r, bool primitiveId, bool position, bool motion) {
  // [primitive_id][stored position][motion], as the G-buffer pass's fragment variants
  static const Shader kShader[2][2][2] = {
      {{Shader::gbuffer_resolve_comp, Shader::gbuffer_resolve_motion_comp},
       {Shader::gbuffer_resolve_position_comp, Shader::gbuffer_resolve_position_motion_comp}},
      {{Shader::gbuffer_resolve_id_comp, Shader::gbuffer_resolve_id_motion_comp},
       {Shader::gbuffer_resolve_id_position_comp, Shader::gbuffer_resolve_id_position_motion_comp}}};
  const Shader shader = kShader[primitiveId][position][motion];
  std::vector<SpecConstant> spec = commonSpec(r);
  spec.push_back({gpu::kSpecVisibilityBits, r.visibilityPacking.triangleBits});
  spec.push_back({gpu::kSpecResolvePosition32, r.options.position == PositionSource::Rgba32f ? 1u : 0u});
  PipelineKey key{shaderName(shader), true, 0, 0, specValues(spec)};
  VkPipeline& p = r.pipelines[key];
  if (!p) p = createComputePipeline(*r.ctx, shader, spec, r.resolveLayout);
  return p;
}

void addGBufferResolvePass(FrameGraph& g, Renderer& r) {
  const std::vector<Target> outputs = gbufferColourTargets(r);
  std::vector<Use> uses = {{Target::Visibility, Access::SampledCompute}, {Target::ShadowMap, Access::SampledCompute}};
  for (Target t : outputs) uses.push_back({t, Access::StorageCompute});
  g.addPass("gbuffer_resolve", uses, [&r, outputs](PassContext& pc) {
    const bool primitiveId = std::find(outputs.begin(), outputs.end(), Target::PrimitiveId) != outputs.end();
    const bool position = std::find(outputs.begin(), outputs.end(), Target::Position) != outputs.end();
    const bool motion = std::find(outputs.begin(), outputs.end(), Target::Motion) != outputs.end();
    const VkPipeline pipeline = resolvePipeline(r, primitiveId, position, motion);
    const GraphTarget& shadow = r.targets[size_t(Target::ShadowMap)];
    const GraphTarget& id = r.targets[size_t(Target::Visibility)];
    std::vector<VkDescriptorImageInfo> infos;
    infos.reserve(4 + outputs.size());
    std::vector<VkWriteDescriptorSet> writes;
    auto add = [&](uint32_t binding, VkDescriptorType type, VkDescriptorImageInfo info) {
      infos.push_back(info);
      VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
      w.dstBinding = binding;
      w.descriptorCount = 1;
      w.descriptorType = type;
      w.pImageInfo = &infos.back();
      writes.push_back(w);
    };
    add(gpu::kResolveBindingShadowMap, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
        {r.samplerShadow, shadow.image.depthView, pc.layouts[size_t(Target::ShadowMap)]});
    add(gpu::kResolveBindingVisibility, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
        {r.samplerPoint, id.image.view, pc.layouts[size_t(Target::Visibility)]});
    for (Target t : outputs) {
      const Image& image = r.targets[size_t(t)].image;
      GB_ASSERT(image.clearView);
      add(resolveBinding(t), VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, {VK_NULL_HANDLE, image.clearView, VK_IMAGE_LAYOUT_GENERAL});
    }
    const VkDescriptorSet sets[] = {frameSlot(r).sceneSet};
    vkCmdBindDescriptorSets(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.resolveLayout, gpu::kSetScene, 1, sets, 0, nullptr);
    vkCmdBindDescriptorSets(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.resolveLayout, gpu::kSetResolveScene, 1,
                            &r.resolveSceneSet, 0, nullptr);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    // The textures of a group, with the sampler pushMaterialTextures gives them (stand-ins where none).
    const size_t white = r.textures.size() - 2, flat = r.textures.size() - 1;
    auto texture = [&](int t, size_t standIn) -> VkDescriptorImageInfo {
      const bool repeat = t < 0 || r.scene->textures[size_t(t)].repeat;
      return {repeat ? r.samplerRepeat : r.samplerClamp, r.textures[t >= 0 ? size_t(t) : standIn].view,
              VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    };
    const size_t fixed = writes.size();
    const uint32_t side = gpu::kResolveGroup;
    for (uint32_t group = 0; group < r.textureGroups.size(); ++group) {
      writes.resize(fixed);
      infos.resize(fixed);  // reserved above: the pointers stay valid
      add(gpu::kResolveBindingBaseTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, texture(r.textureGroups[group].first, white));
      add(gpu::kResolveBindingNormalTexture, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, texture(r.textureGroups[group].second, flat));
      r.ctx->cmdPushDescriptorSet(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.resolveLayout, gpu::kSetPass,
                                  uint32_t(writes.size()), writes.data());
      const glm::uvec4 push(group, 0u, 0u, 0u);
      vkCmdPushConstants(pc.cmd, r.resolveLayout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(push), &push);
      if (group > 0) {  // disjoint pixels of the same images: ordered for the validation's hazard tracking
        VkMemoryBarrier2 b{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
        b.srcStageMask = b.dstStageMask = VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
        b.srcAccessMask = b.dstAccessMask = VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT;
        VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
        dep.memoryBarrierCount = 1;
        dep.pMemoryBarriers = &b;
        vkCmdPipelineBarrier2(pc.cmd, &dep);
      }
      vkCmdDispatch(pc.cmd, (r.options.width + side - 1) / side, (r.options.height + side - 1) / side, 1);
    }
  });
}

}  // namespace gb
