// shadePointsOnDevice: a compute shader calls the lighting passes' point-light formula over a buffer
// of cases, so its float rounding can be measured against the double reference.
#include "renderer/readback/shading_probe.h"

#include "renderer/vk/check.h"

namespace gb {

std::vector<glm::vec3> shadePointsOnDevice(Renderer& r, const std::vector<ShadingCase>& cases) {
  if (cases.empty()) return {};
  GpuContext& ctx = *r.ctx;
  const size_t groups = (cases.size() + 63) / 64, count = groups * 64;
  Buffer values = createBuffer(ctx, count * 4 * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Readback);
  auto* v = static_cast<glm::vec4*>(values.mapped);
  for (size_t i = 0; i < count; ++i) {
    const ShadingCase c = i < cases.size() ? cases[i] : ShadingCase{{0, 0, 1}, {0, 0, -1}, {0, 0, -0.5f}, 1.0f};
    v[4 * i] = glm::vec4(c.normal, 0.0f);
    v[4 * i + 1] = glm::vec4(c.position, 1.0f);
    v[4 * i + 2] = glm::vec4(c.light, c.radius);
    v[4 * i + 3] = glm::vec4(0.0f);
  }
  VkPipeline pipeline = createComputePipeline(ctx, Shader::shading_probe_comp, {}, r.pipelineLayout);
  submitOnce(ctx, [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    VkDescriptorBufferInfo buffer{values.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = gpu::kBindingTileLights;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &buffer;
    ctx.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipelineLayout, gpu::kSetPass, 1, &w);
    vkCmdDispatch(cmd, uint32_t(groups), 1, 1);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  });
  std::vector<glm::vec3> out(cases.size());
  for (size_t i = 0; i < cases.size(); ++i) out[i] = glm::vec3(v[4 * i + 3]);
  vkDestroyPipeline(ctx.device, pipeline, nullptr);
  destroyBuffer(ctx, values);
  return out;
}

}  // namespace gb
