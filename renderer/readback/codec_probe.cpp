// encodeNormalsOnDevice: a compute shader calls the G-buffer pass's encoder over a buffer of
// vectors, so the CPU mirror (renderer/core/codec.cpp) can be compared with what the device runs.
#include "renderer/readback/codec_probe.h"

#include <cstring>

#include "renderer/vk/check.h"

namespace gb {

std::vector<glm::vec4> encodeNormalsOnDevice(Renderer& r, const std::vector<glm::vec3>& normals, NormalFormat format,
                                             OctEncoding encoding) {
  GpuContext& ctx = *r.ctx;
  const size_t groups = (normals.size() + 63) / 64, count = groups * 64;
  if (normals.empty()) return {};
  uint32_t code = gpu::kNormalRgba16f;
  switch (format) {
    case NormalFormat::Rgba16f: code = gpu::kNormalRgba16f; break;
    case NormalFormat::Rgba8Snorm: code = gpu::kNormalRgba8Snorm; break;
    case NormalFormat::OctRg16: code = gpu::kNormalOctRg16; break;
    case NormalFormat::Rgb10a2: code = gpu::kNormalRgb10a2; break;
  }
  Buffer values = createBuffer(ctx, count * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Readback);
  auto* v = static_cast<glm::vec4*>(values.mapped);
  for (size_t i = 0; i < count; ++i) v[i] = glm::vec4(i < normals.size() ? normals[i] : glm::vec3(0, 0, 1), 0.0f);
  std::vector<SpecConstant> spec = {{gpu::kSpecNormalEncoding, code},
                                    {gpu::kSpecOctPrecise, encoding == OctEncoding::Precise ? 1u : 0u}};
  VkPipeline pipeline = createComputePipeline(ctx, Shader::codec_probe_comp, spec, r.pipelineLayout);
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
  std::vector<glm::vec4> out(v, v + normals.size());
  vkDestroyPipeline(ctx.device, pipeline, nullptr);
  destroyBuffer(ctx, values);
  return out;
}

}  // namespace gb
