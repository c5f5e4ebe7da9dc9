// probeSrgbDecode: reads back what the device's sampler makes of every 8-bit sRGB value. On
// llvmpipe the decode is an approximation (up to a few 0.1% off the exact curve); the error
// measure uses the device's own table so the lighting passes are measured, not the sampler.
#include <cstring>

#include "renderer/gpu/renderer_state.h"
#include "renderer/vk/check.h"

namespace gb {

const std::vector<float>& probeSrgbDecode(Renderer& r) {
  if (!r.srgbDecode.empty()) return r.srgbDecode;
  GpuContext& ctx = *r.ctx;
  std::vector<uint8_t> bytes(256 * 4);
  for (int i = 0; i < 256; ++i) std::memset(&bytes[i * 4], i, 4);
  ImageDesc d;
  d.format = VK_FORMAT_R8G8B8A8_SRGB;
  d.width = 256;
  d.height = 1;
  d.mipLevels = 1;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  d.name = "srgb_probe";
  Image img = createImage(ctx, d);
  uploadTexture(ctx, img, bytes);
  Buffer out = createBuffer(ctx, 256 * 16, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Readback, "srgb_probe");
  VkPipeline pipeline = createComputePipeline(ctx, Shader::srgb_probe_comp, {}, r.pipelineLayout);
  submitOnce(ctx, [&](VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipeline);
    VkDescriptorImageInfo image{r.samplerPoint, img.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
    VkDescriptorBufferInfo buffer{out.buffer, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet w[2] = {{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}, {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET}};
    w[0].dstBinding = gpu::kBindingAlbedo;
    w[0].descriptorCount = 1;
    w[0].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w[0].pImageInfo = &image;
    w[1].dstBinding = gpu::kBindingTileLights;
    w[1].descriptorCount = 1;
    w[1].descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w[1].pBufferInfo = &buffer;
    ctx.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, r.pipelineLayout, gpu::kSetPass, 2, w);
    vkCmdDispatch(cmd, 256 / 64, 1, 1);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  });
  const float* v = static_cast<const float*>(out.mapped);
  r.srgbDecode.resize(256);
  for (int i = 0; i < 256; ++i) r.srgbDecode[i] = v[i * 4];  // red: an sRGB-decoded channel
  vkDestroyPipeline(ctx.device, pipeline, nullptr);
  destroyBuffer(ctx, out);
  destroyImage(ctx, img);
  return r.srgbDecode;
}

}  // namespace gb
