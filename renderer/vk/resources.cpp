// Buffer/image creation, staging uploads and one-shot submission.
#include "renderer/vk/resources.h"

#include <cstring>
#include <string>

#include "renderer/vk/check.h"

namespace gb {

uint32_t findMemoryType(const GpuContext& ctx, uint32_t typeBits, VkMemoryPropertyFlags required,
                        VkMemoryPropertyFlags preferred) {
  for (int pass = 0; pass < 2; ++pass) {
    VkMemoryPropertyFlags want = pass == 0 ? (required | preferred) : required;
    for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i)
      if ((typeBits & (1u << i)) && (ctx.memory.memoryTypes[i].propertyFlags & want) == want) return i;
  }
  return UINT32_MAX;
}

Buffer createBuffer(GpuContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use, const char* name) {
  Buffer b;
  b.size = size;
  VkBufferCreateInfo bci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bci.size = size > 0 ? size : 16;
  bci.usage = usage;
  if (!ctx.sharedFamilies.empty()) {  // the graphics and the compute queue's families (context.h)
    bci.sharingMode = VK_SHARING_MODE_CONCURRENT;
    bci.queueFamilyIndexCount = uint32_t(ctx.sharedFamilies.size());
    bci.pQueueFamilyIndices = ctx.sharedFamilies.data();
  }
  VK_CHECK(vkCreateBuffer(ctx.device, &bci, nullptr, &b.buffer));
  setName(ctx, uint64_t(b.buffer), VK_OBJECT_TYPE_BUFFER, name);
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(ctx.device, b.buffer, &req);
  VkMemoryPropertyFlags required = 0, preferred = 0;
  switch (use) {
    case MemoryUse::Device: required = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT; break;
    case MemoryUse::Upload:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT;  // resizable BAR where present
      break;
    case MemoryUse::Readback:
      required = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
      preferred = VK_MEMORY_PROPERTY_HOST_CACHED_BIT;
      break;
  }
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = findMemoryType(ctx, req.memoryTypeBits, required, preferred);
  GB_ASSERT(mai.memoryTypeIndex != UINT32_MAX);
  VK_CHECK(vkAllocateMemory(ctx.device, &mai, nullptr, &b.memory));
  setName(ctx, uint64_t(b.memory), VK_OBJECT_TYPE_DEVICE_MEMORY, name);
  VK_CHECK(vkBindBufferMemory(ctx.device, b.buffer, b.memory, 0));
  if (use != MemoryUse::Device) VK_CHECK(vkMapMemory(ctx.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  return b;
}

void destroyBuffer(GpuContext& ctx, Buffer& b) {
  if (b.buffer) vkDestroyBuffer(ctx.device, b.buffer, nullptr);
  if (b.memory) vkFreeMemory(ctx.device, b.memory, nullptr);
  b = Buffer{};
}

bool isDepthFormat(VkFormat f) {
  switch (f) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_X8_D24_UNORM_PACK32: return true;
    default: return false;
  }
}

bool hasStencil(VkFormat f) {
  return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT || f == VK_FORMAT_D16_UNORM_S8_UINT;
}

VkImageAspectFlags aspectsOf(VkFormat f) {
  if (!isDepthFormat(f)) return VK_IMAGE_ASPECT_COLOR_BIT;
  return VK_IMAGE_ASPECT_DEPTH_BIT | (hasStencil(f) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
}

uint32_t bytesPerPixel(VkFormat f) {
  switch (f) {
    case VK_FORMAT_R8_UNORM:
    case VK_FORMAT_S8_UINT: return 1;
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_R16_UNORM: return 2;
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
    case VK_FORMAT_R8G8B8A8_SNORM:
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32:
    case VK_FORMAT_R16G16_UNORM:
    case VK_FORMAT_R16G16_SNORM:
    case VK_FORMAT_R16G16_SFLOAT:
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_R32_UINT:
    case VK_FORMAT_D32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:  // depth aspect copies out as 4 bytes
    case VK_FORMAT_D24_UNORM_S8_UINT:   // depth aspect copies out as 4 bytes (24 bits used)
    case VK_FORMAT_X8_D24_UNORM_PACK32: return 4;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R16G16B16A16_SNORM:
    case VK_FORMAT_R16G16B16A16_UNORM:
    case VK_FORMAT_R32G32_SFLOAT: return 8;
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: GB_ASSERT(!"bytesPerPixel: format not listed"); return 0;
  }
}

// A view named after its image (and aspect): RenderDoc lists views beside images.
// `usage` (non-zero): the view's own usage, a subset of an EXTENDED_USAGE image's.
static VkImageView makeImageView(GpuContext& ctx, VkImage image, VkFormat format, VkImageAspectFlags aspect,
                                 uint32_t mips, const char* name, const char* suffix, VkImageUsageFlags usage = 0) {
  VkImageViewUsageCreateInfo uci{VK_STRUCTURE_TYPE_IMAGE_VIEW_USAGE_CREATE_INFO};
  uci.usage = usage;
  VkImageViewCreateInfo vci{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  if (usage) vci.pNext = &uci;
  vci.image = image;
  vci.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vci.format = format;
  vci.subresourceRange = {aspect, 0, mips, 0, 1};
  VkImageView view;
  VK_CHECK(vkCreateImageView(ctx.device, &vci, nullptr, &view));
  if (name) setName(ctx, uint64_t(view), VK_OBJECT_TYPE_IMAGE_VIEW, (std::string(name) + suffix).c_str());
  return view;
}

Image createImage(GpuContext& ctx, const ImageDesc& desc) {
  Image img;
  img.desc = desc;
  VkImageCreateInfo ici{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ici.imageType = VK_IMAGE_TYPE_2D;
  ici.format = desc.format;
  ici.extent = {desc.width, desc.height, 1};
  ici.mipLevels = desc.mipLevels;
  ici.arrayLayers = 1;
  ici.samples = VK_SAMPLE_COUNT_1_BIT;
  ici.tiling = VK_IMAGE_TILING_OPTIMAL;
  ici.usage = desc.usage | (desc.transient ? VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT : 0);
  const bool clearable = desc.clearFormat != VK_FORMAT_UNDEFINED;
  if (clearable) {
    GB_ASSERT(!desc.transient && !isDepthFormat(desc.format));
    ici.usage |= VK_IMAGE_USAGE_STORAGE_BIT;
    ici.flags = VK_IMAGE_CREATE_MUTABLE_FORMAT_BIT | VK_IMAGE_CREATE_EXTENDED_USAGE_BIT;
  }
  ici.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  if (!ctx.sharedFamilies.empty()) {
    ici.sharingMode = VK_SHARING_MODE_CONCURRENT;
    ici.queueFamilyIndexCount = uint32_t(ctx.sharedFamilies.size());
    ici.pQueueFamilyIndices = ctx.sharedFamilies.data();
  }
  VK_CHECK(vkCreateImage(ctx.device, &ici, nullptr, &img.image));
  setName(ctx, uint64_t(img.image), VK_OBJECT_TYPE_IMAGE, desc.name);

  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(ctx.device, img.image, &req);
  uint32_t type = UINT32_MAX;
  if (desc.transient && ctx.features.lazilyAllocatedMemory) {
    type = findMemoryType(ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT);
    img.lazilyAllocated = type != UINT32_MAX;
  }
  if (type == UINT32_MAX) type = findMemoryType(ctx, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  GB_ASSERT(type != UINT32_MAX);
  VkMemoryAllocateInfo mai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  mai.allocationSize = req.size;
  mai.memoryTypeIndex = type;
  VK_CHECK(vkAllocateMemory(ctx.device, &mai, nullptr, &img.memory));
  setName(ctx, uint64_t(img.memory), VK_OBJECT_TYPE_DEVICE_MEMORY, desc.name);
  VK_CHECK(vkBindImageMemory(ctx.device, img.image, img.memory, 0));

  img.view = makeImageView(ctx, img.image, desc.format, aspectsOf(desc.format), desc.mipLevels, desc.name, "",
                           clearable ? desc.usage : 0);
  if (clearable)
    img.clearView = makeImageView(ctx, img.image, desc.clearFormat, VK_IMAGE_ASPECT_COLOR_BIT, 1, desc.name, ".clear",
                                  VK_IMAGE_USAGE_STORAGE_BIT);
  if (isDepthFormat(desc.format)) {
    img.depthView = makeImageView(ctx, img.image, desc.format, VK_IMAGE_ASPECT_DEPTH_BIT, 1, desc.name, ".depth");
    if (hasStencil(desc.format))
      img.stencilView =
          makeImageView(ctx, img.image, desc.format, VK_IMAGE_ASPECT_STENCIL_BIT, 1, desc.name, ".stencil");
  }
  return img;
}

void destroyImage(GpuContext& ctx, Image& img) {
  for (VkImageView v : {img.view, img.depthView, img.stencilView, img.clearView})
    if (v) vkDestroyImageView(ctx.device, v, nullptr);
  if (img.image) vkDestroyImage(ctx.device, img.image, nullptr);
  if (img.memory) vkFreeMemory(ctx.device, img.memory, nullptr);
  img = Image{};
}

void submitOnce(GpuContext& ctx, const std::function<void(VkCommandBuffer)>& record) {
  VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cai.commandPool = ctx.commandPool;
  cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &cai, &cmd));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
  record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  VK_CHECK(vkQueueSubmit(ctx.queue, 1, &si, VK_NULL_HANDLE));
  VK_CHECK(vkQueueWaitIdle(ctx.queue));
  vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &cmd);
}

void hostReadBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = srcStage;
  mb.srcAccessMask = srcAccess;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_HOST_BIT;
  mb.dstAccessMask = VK_ACCESS_2_HOST_READ_BIT;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cmd, &dep);
}

uint32_t wholeImageCopies(const ImageDesc& d, VkBufferImageCopy (&copies)[2]) {
  copies[0] = copies[1] = VkBufferImageCopy{};
  uint32_t n = 0;
  copies[n].imageSubresource = {isDepthFormat(d.format) ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT)
                                                        : VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT),
                                0, 0, 1};
  copies[n++].imageExtent = {d.width, d.height, 1};
  if (hasStencil(d.format)) {
    copies[n].bufferOffset = VkDeviceSize(d.width) * d.height * bytesPerPixel(d.format);
    copies[n].imageSubresource = {VK_IMAGE_ASPECT_STENCIL_BIT, 0, 0, 1};
    copies[n++].imageExtent = {d.width, d.height, 1};
  }
  return n;
}

void uploadBuffer(GpuContext& ctx, Buffer& dst, const void* data, VkDeviceSize size) {
  if (size == 0) return;
  Buffer staging = createBuffer(ctx, size, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload, "staging");
  std::memcpy(staging.mapped, data, size);
  submitOnce(ctx, [&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, size};
    vkCmdCopyBuffer(cmd, staging.buffer, dst.buffer, 1, &region);
  });
  destroyBuffer(ctx, staging);
}

VkImageMemoryBarrier2 imageMemoryBarrier(VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                                         VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                                         VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  VkImageMemoryBarrier2 b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  b.srcStageMask = srcStage;
  b.srcAccessMask = srcAccess;
  b.dstStageMask = dstStage;
  b.dstAccessMask = dstAccess;
  b.oldLayout = from;
  b.newLayout = to;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = range;
  return b;
}

void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess) {
  const VkImageMemoryBarrier2 b = imageMemoryBarrier(image, range, from, to, srcStage, srcAccess, dstStage, dstAccess);
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &b;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void uploadTexture(GpuContext& ctx, Image& img, std::span<const uint8_t> rgba8) {
  const ImageDesc& d = img.desc;
  GB_ASSERT(rgba8.size() == size_t(d.width) * d.height * 4);
  Buffer staging = createBuffer(ctx, rgba8.size(), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload, "staging");
  std::memcpy(staging.mapped, rgba8.data(), rgba8.size());
  submitOnce(ctx, [&](VkCommandBuffer cmd) {
    imageBarrier(cmd, img.image, {VK_IMAGE_ASPECT_COLOR_BIT, 0, d.mipLevels, 0, 1}, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_PIPELINE_STAGE_2_NONE, 0, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {d.width, d.height, 1};
    vkCmdCopyBufferToImage(cmd, staging.buffer, img.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
    int32_t w = int32_t(d.width), h = int32_t(d.height);
    for (uint32_t mip = 1; mip < d.mipLevels; ++mip) {
      imageBarrier(cmd, img.image, {VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, 1, 0, 1}, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                   VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT);
      VkImageBlit blit{};
      blit.srcSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, 0, 1};
      blit.srcOffsets[1] = {w, h, 1};
      w = w > 1 ? w / 2 : 1;
      h = h > 1 ? h / 2 : 1;
      blit.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, mip, 0, 1};
      blit.dstOffsets[1] = {w, h, 1};
      vkCmdBlitImage(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, img.image,
                     VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &blit, VK_FILTER_LINEAR);
      imageBarrier(cmd, img.image, {VK_IMAGE_ASPECT_COLOR_BIT, mip - 1, 1, 0, 1}, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT, 0,
                   VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
    imageBarrier(cmd, img.image, {VK_IMAGE_ASPECT_COLOR_BIT, d.mipLevels - 1, 1, 0, 1}, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_PIPELINE_STAGE_2_TRANSFER_BIT,
                 VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                 VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
  });
  destroyBuffer(ctx, staging);
}

}  // namespace gb
