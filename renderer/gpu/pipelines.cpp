// Pipelines and descriptors for the passes: cached pipelines keyed by what makes them differ,
// the specialization constants every pipeline gets, and set 1 pushed per pass.
#include "renderer/gpu/pipelines.h"

#include "renderer/vk/check.h"

namespace gb {

VkPipeline graphicsPipeline(Renderer& r, const PassContext& pc, const std::string& id,
                            const std::function<void(GraphicsPipelineDesc&)>& fill) {
  PipelineKey key{id, false, pc.compatClass, pc.subpass, specValues(commonSpec(r))};
  VkPipeline& p = r.pipelines[key];
  if (!p) {
    GraphicsPipelineDesc d;
    d.renderPass = pc.renderPass;
    d.subpass = pc.subpass;
    d.layout = r.pipelineLayout;
    d.name = id;
    d.spec = commonSpec(r);
    d.colorBlend.assign(pc.colorAttachments, BlendState{});
    fill(d);
    GB_ASSERT(d.colorBlend.size() == pc.colorAttachments);
    p = createGraphicsPipeline(*r.ctx, d);
  }
  return p;
}

VkPipeline computePipeline(Renderer& r, Shader shader) {
  PipelineKey key{shaderName(shader), true, 0, 0, specValues(commonSpec(r))};
  VkPipeline& p = r.pipelines[key];
  if (!p) p = createComputePipeline(*r.ctx, shader, commonSpec(r), r.pipelineLayout);
  return p;
}

std::vector<SpecConstant> commonSpec(const Renderer& r) {
  uint32_t normal = 0;
  switch (r.options.normalFormat) {
    case NormalFormat::Rgba16f: normal = gpu::kNormalRgba16f; break;
    case NormalFormat::Rgba8Snorm: normal = gpu::kNormalRgba8Snorm; break;
    case NormalFormat::OctRg16: normal = gpu::kNormalOctRg16; break;
    case NormalFormat::Rgb10a2: normal = gpu::kNormalRgb10a2; break;
  }
  uint32_t position = gpu::kPositionDepth;
  if (r.options.position != PositionSource::Depth)
    position = r.options.positionSpace == PositionSpace::World ? gpu::kPositionWorld : gpu::kPositionCamera;
  return {{gpu::kSpecEyeDepth, r.options.eyeDepth ? 1u : 0u},
          {gpu::kSpecPosition, position},
          {gpu::kSpecReversedZ, r.options.reversedZ ? 1u : 0u},
          {gpu::kSpecNormalEncoding, normal},
          {gpu::kSpecOctPrecise, r.options.octEncoding == OctEncoding::Precise ? 1u : 0u},
          {gpu::kSpecCoverage, r.options.coverage ? 1u : 0u}};
}

void bindDescriptors(Renderer& r, VkCommandBuffer cmd, VkPipelineLayout layout, std::initializer_list<PassImage> images,
                     VkPipelineBindPoint bindPoint) {
  vkCmdBindDescriptorSets(cmd, bindPoint, layout, gpu::kSetScene, 1, &frameSlot(r).sceneSet, 0, nullptr);
  if (images.size() == 0) return;
  std::vector<VkDescriptorImageInfo> infos;
  infos.reserve(images.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (const PassImage& img : images) {
    infos.push_back({img.sampler, img.view, img.layout});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = img.binding;
    w.descriptorCount = 1;
    w.descriptorType = img.type;
    w.pImageInfo = &infos.back();
    writes.push_back(w);
  }
  r.ctx->cmdPushDescriptorSet(cmd, bindPoint, layout, gpu::kSetPass, uint32_t(writes.size()), writes.data());
}

VkCompareOp closerOrEqual(const Renderer& r) {
  return r.options.reversedZ ? VK_COMPARE_OP_GREATER_OR_EQUAL : VK_COMPARE_OP_LESS_OR_EQUAL;
}
VkCompareOp fartherOrEqual(const Renderer& r) {
  return r.options.reversedZ ? VK_COMPARE_OP_LESS_OR_EQUAL : VK_COMPARE_OP_GREATER_OR_EQUAL;
}
float farDepth(const Renderer& r) { return r.options.reversedZ ? 0.0f : 1.0f; }

}  // namespace gb
