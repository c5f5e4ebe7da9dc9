// Region read-back: one transfer pass copying the clamped windows into one host buffer.
#include "renderer/frame/region_readback.h"

#include <algorithm>

#include "renderer/readback/target_readback.h"
#include "renderer/vk/check.h"

namespace gb {

std::vector<RegionImage> readbackRegions(Renderer& r, const std::vector<RegionRequest>& requests,
                                         const std::vector<Target>& handOff) {
  struct Copy {
    size_t request;
    VkDeviceSize offset;
    uint32_t x, y, w, h;
  };
  std::vector<RegionImage> out(requests.size());
  std::vector<Copy> copies;
  VkDeviceSize bytes = 0;
  std::vector<Use> uses;
  for (size_t i = 0; i < requests.size(); ++i) {
    const RegionRequest& q = requests[i];
    const Image& img = r.targets[size_t(q.target)].image;
    GB_ASSERT(img.image && !img.desc.transient);
    RegionImage& o = out[i];
    o.target = q.target;
    o.targetWidth = img.desc.width;
    o.targetHeight = img.desc.height;
    int64_t x0 = std::max<int64_t>(q.x, 0), y0 = std::max<int64_t>(q.y, 0);
    int64_t x1 = std::min<int64_t>(int64_t(q.x) + q.width, img.desc.width);
    int64_t y1 = std::min<int64_t>(int64_t(q.y) + q.height, img.desc.height);
    if (x1 <= x0 || y1 <= y0) continue;
    Copy c{i, bytes, uint32_t(x0), uint32_t(y0), uint32_t(x1 - x0), uint32_t(y1 - y0)};
    VkDeviceSize texels = VkDeviceSize(c.w) * c.h;
    bytes += texels * bytesPerPixel(img.desc.format) + (hasStencil(img.desc.format) ? texels : 0);
    bytes = (bytes + 15) & ~VkDeviceSize(15);  // depth/stencil copies need 4-byte aligned offsets
    copies.push_back(c);
    if (std::none_of(uses.begin(), uses.end(), [&](const Use& u) { return u.target == q.target; }))
      uses.push_back({q.target, Access::TransferSrc});
  }
  if (copies.empty()) return out;

  Buffer buffer = createBuffer(*r.ctx, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback, "probe_readback");
  runAfterFrame(
      r,
      [&](FrameGraph& g) {
        g.addPass("probe_readback", uses, [&](PassContext& pc) {
          for (const Copy& c : copies) {
            const Image& img = r.targets[size_t(requests[c.request].target)].image;
            VkBufferImageCopy regions[2]{};
            uint32_t n = 0;
            VkImageAspectFlags aspect = isDepthFormat(img.desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
            regions[n].bufferOffset = c.offset;
            regions[n].imageSubresource = {aspect, 0, 0, 1};
            regions[n].imageOffset = {int32_t(c.x), int32_t(c.y), 0};
            regions[n++].imageExtent = {c.w, c.h, 1};
            if (hasStencil(img.desc.format)) {
              regions[n].bufferOffset = c.offset + VkDeviceSize(c.w) * c.h * bytesPerPixel(img.desc.format);
              regions[n].imageSubresource = {VK_IMAGE_ASPECT_STENCIL_BIT, 0, 0, 1};
              regions[n].imageOffset = {int32_t(c.x), int32_t(c.y), 0};
              regions[n++].imageExtent = {c.w, c.h, 1};
            }
            vkCmdCopyImageToBuffer(pc.cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer, n, regions);
          }
          // The host reads the buffer after the wait: make the copies visible to it.
          hostReadBarrier(pc.cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
        });
      },
      handOff);

  for (const Copy& c : copies) {
    RegionImage& o = out[c.request];
    o.x0 = c.x;
    o.y0 = c.y;
    o.image = unpackTarget(o.target, r.options, static_cast<const uint8_t*>(buffer.mapped) + c.offset,
                           c.w, c.h);
  }
  destroyBuffer(*r.ctx, buffer);
  return out;
}

}  // namespace gb
