// Uploading captured targets: pack, copy, transition to the layouts the graph expects after a
// frame's hand-off (shader read / depth-stencil read).
#include "renderer/gpu/upload_targets.h"

#include <cmath>
#include <cstring>

#include "renderer/core/texels.h"
#include "renderer/vk/check.h"

namespace gb {

void uploadTargets(Renderer& r, const RenderOptions& options, const std::array<const CpuImage*, kTargetCount>& images) {
  GpuContext& ctx = *r.ctx;
  vkDeviceWaitIdle(ctx.device);
  for (GraphTarget& t : r.targets) {
    destroyImage(ctx, t.image);
    t = GraphTarget{};
  }
  clearFramebuffers(ctx, r.graphCache);
  r.options = options;
  r.targetsKey.reset();  // uploaded: the next rendered frame creates its own targets
  r.targetsValid = true;
  for (size_t i = 0; i < kTargetCount; ++i) {
    const CpuImage* img = images[i];
    if (!img || img->empty()) continue;
    Target t = Target(i);
    ImageDesc d;
    d.format = targetFormat(t, options);
    d.width = img->width;
    d.height = img->height;
    d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    // The read-only depth/stencil layout (as after a live frame) requires the attachment usage.
    if (isDepthFormat(d.format)) d.usage |= VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT;
    d.name = targetName(t);
    GraphTarget& gt = r.targets[i];
    gt.image = createImage(ctx, d);
    std::vector<uint8_t> bytes = packTexels(*img, texelFormat(t, options));
    Buffer staging = createBuffer(ctx, bytes.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload, "staging");
    std::memcpy(staging.mapped, bytes.data(), bytes.size());
    const VkImageLayout readLayout =
        isDepthFormat(d.format) && hasStencil(d.format) ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    submitOnce(ctx, [&](VkCommandBuffer cmd) {
      const VkImageSubresourceRange all = {aspectsOf(d.format), 0, 1, 0, 1};
      imageBarrier(cmd, gt.image.image, all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      VkBufferImageCopy copies[2];
      const uint32_t n = wholeImageCopies(d, copies);
      vkCmdCopyBufferToImage(cmd, staging.buffer, gt.image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, n, copies);
      imageBarrier(cmd, gt.image.image, all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, readLayout,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
                   VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    });
    destroyBuffer(ctx, staging);
    gt.layout = readLayout;
    gt.stage = VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    gt.access = VK_ACCESS_2_SHADER_SAMPLED_READ_BIT;
    gt.keep = true;
  }
}

}  // namespace gb
