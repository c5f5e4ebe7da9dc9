// runBufferProbe: one compute dispatch over a buffer of cases, for the device probes.
#include "renderer/readback/buffer_probe.h"

#include "renderer/vk/check.h"

namespace gb {

void runBufferProbe(Renderer& r, Shader shader, const std::vector<SpecConstant>& spec, const Buffer& values, uint32_t groups) {
  GpuContext& ctx = *r.ctx;
  VkPipeline pipeline = createComputePipeline(ctx, shader, spec, r.pipelineLayout);
  submitOnce(ctx, [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    VkDescriptorBufferInfo buffer{values.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = gpu::kBindingTileLights;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &buffer;
    ctx.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipelineLayout, gpu::kSetPass, 1, &w);
    vkCmdDispatch(cmd, groups, 1, 1);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  });
  vkDestroyPipeline(ctx.device, pipeline, nullptr);
}

}  // namespace gb
