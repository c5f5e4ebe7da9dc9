// Read-back of whole targets: the copy recorded at the end of a frame, and the texels unpacked
// into CpuImage (D24 widened, stencil after depth, rgb10a2 split into channels).
#include <cstring>

#include "renderer/frame.h"
#include "renderer/renderer.h"
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
    buf = createBuffer(*r.ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
  }
  VkBufferImageCopy copies[2];
  const uint32_t n = wholeImageCopies(gt.image.desc, copies);
  vkCmdCopyImageToBuffer(cmd, gt.image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buf.buffer, n, copies);
  hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
}

CpuImage unpackTexels(Target t, const RenderOptions& options, VkFormat format, const uint8_t* src, uint32_t width,
                      uint32_t height) {
  CpuImage img;
  describeReadback(t, options, img);
  img.width = width;
  img.height = height;
  size_t texels = size_t(width) * height;
  img.data.resize(texels * img.texelBytes());
  if (t == Target::DepthStencil) {  // F32 Depth, F32 Stencil
    float* out = reinterpret_cast<float*>(img.data.data());
    const uint8_t* stencil = src + texels * 4;
    for (size_t i = 0; i < texels; ++i) {
      uint32_t bits;
      std::memcpy(&bits, src + i * 4, 4);
      float depth;
      if (format == VK_FORMAT_D24_UNORM_S8_UINT)
        depth = float(double(bits & 0xFFFFFF) / 16777215.0);
      else
        std::memcpy(&depth, &bits, 4);
      out[2 * i] = depth;
      out[2 * i + 1] = float(stencil[i]);
    }
  } else if (format == VK_FORMAT_A2B10G10R10_UNORM_PACK32) {
    uint16_t* out = reinterpret_cast<uint16_t*>(img.data.data());
    for (size_t i = 0; i < texels; ++i) {
      uint32_t v;
      std::memcpy(&v, src + i * 4, 4);
      out[4 * i + 0] = uint16_t(v & 0x3FF);
      out[4 * i + 1] = uint16_t((v >> 10) & 0x3FF);
      out[4 * i + 2] = uint16_t((v >> 20) & 0x3FF);
      out[4 * i + 3] = uint16_t(v >> 30);
    }
  } else {
    GB_ASSERT(img.data.size() == texels * bytesPerPixel(format));
    std::memcpy(img.data.data(), src, img.data.size());
  }
  return img;
}

CpuImage unpackReadback(Renderer& r, Target t) {
  const ImageDesc& d = r.targets[size_t(t)].image.desc;
  return unpackTexels(t, r.options, d.format, static_cast<const uint8_t*>(r.readbackBuffers[size_t(t)].mapped),
                      d.width, d.height);
}

}  // namespace gb
