// Read-back of whole targets: the copy recorded at the end of a frame, and the texels unpacked
// into CpuImage (renderer/core/texels.h).
#include "renderer/readback/target_readback.h"

#include <string>

#include "renderer/core/texels.h"
#include "renderer/vk/check.h"

namespace gb {

static VkDeviceSize readbackBytes(const GraphTarget& t) {
  VkDeviceSize texels = VkDeviceSize(t.image.desc.width) * t.image.desc.height;
  VkDeviceSize bytes = texels * bytesPerPixel(t.image.desc.format);
  if (hasStencil(t.image.desc.format)) bytes += texels;  // stencil aspect after depth
  return bytes;
}

void recordReadback(Renderer& r, VkCommandBuffer cmd, Target t) {
  GraphTarget& gt = r.targets[size_t(t)];
  Buffer& buf = r.readbackBuffers[size_t(t)];
  VkDeviceSize bytes = readbackBytes(gt);
  if (buf.size < bytes) {
    destroyBuffer(*r.ctx, buf);
    buf = createBuffer(*r.ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback,
                       (std::string("readback.") + targetName(t)).c_str());
  }
  VkBufferImageCopy copies[2];
  const uint32_t n = wholeImageCopies(gt.image.desc, copies);
  vkCmdCopyImageToBuffer(cmd, gt.image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf.buffer, n, copies);
  hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

CpuImage unpackTarget(Target t, const RenderOptions& options, const uint8_t* src, uint32_t width, uint32_t height) {
  CpuImage img = unpackTexels(texelFormat(t, options), src, width, height);
  describeReadback(t, options, img);
  return img;
}

CpuImage unpackReadback(Renderer& r, Target t) {
  const ImageDesc& d = r.targets[size_t(t)].image.desc;
  return unpackTarget(t, r.options, static_cast<const uint8_t*>(r.readbackBuffers[size_t(t)].mapped), d.width,
                      d.height);
}

}  // namespace gb
