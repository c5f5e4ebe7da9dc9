// Buffers, images and one-shot command submission as plain structs + free functions
// (in the manner of niagara's resources.h). One allocation per resource: gblens holds few.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <span>

#include "renderer/vk/context.h"
#include "renderer/vk/debug_utils.h"  // setName: every buffer and image the renderer creates is named

namespace gb {

enum class MemoryUse { Device, Upload, Readback };

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;  // host-visible buffers stay mapped
};

struct ImageDesc {
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 1, height = 1;
  uint32_t mipLevels = 1;
  VkImageUsageFlags usage = 0;
  bool transient = false;  // transient attachment: lazily allocated memory when the device has it
  // Set: the image also gets a storage view in this format of the same texel size (compute writes
  // to formats that have no storage support themselves, such as sRGB: clear_gbuffer's zeros, the
  // compute tone map's sRGB-encoded texels): MUTABLE_FORMAT and EXTENDED_USAGE, the other views
  // restricted to `usage`.
  VkFormat clearFormat = VK_FORMAT_UNDEFINED;
  const char* name = nullptr;
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;         // every aspect (attachments)
  VkImageView depthView = VK_NULL_HANDLE;    // depth aspect only (sampling / input attachment)
  VkImageView stencilView = VK_NULL_HANDLE;  // stencil aspect only
  VkImageView clearView = VK_NULL_HANDLE;    // storage view in desc.clearFormat (when set)
  ImageDesc desc;
  bool lazilyAllocated = false;  // memory came from a LAZILY_ALLOCATED type
};

uint32_t findMemoryType(const GpuContext& ctx, uint32_t typeBits, VkMemoryPropertyFlags required,
                        VkMemoryPropertyFlags preferred = 0);

// `name` (RenderDoc, validation messages): what the buffer holds, as the shaders call it.
Buffer createBuffer(GpuContext& ctx, VkDeviceSize size, VkBufferUsageFlags usage, MemoryUse use,
                    const char* name = nullptr);
void destroyBuffer(GpuContext& ctx, Buffer& buffer);

Image createImage(GpuContext& ctx, const ImageDesc& desc);
void destroyImage(GpuContext& ctx, Image& image);

bool isDepthFormat(VkFormat format);
bool hasStencil(VkFormat format);
VkImageAspectFlags aspectsOf(VkFormat format);
uint32_t bytesPerPixel(VkFormat format);  // of the aspect copied to a buffer (depth aspect for D/S)

// Records into a fresh command buffer, submits, waits. For uploads and read-backs outside a frame.
void submitOnce(GpuContext& ctx, const std::function<void(VkCommandBuffer)>& record);

// Makes device writes (by srcStage/srcAccess) visible to the host once the submission's fence
// has signalled: every read-back ends with it.
void hostReadBarrier(VkCommandBuffer cmd, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess);

// One image layout transition / dependency: the barrier (the frame graph batches these), or
// recorded now (uploads and one-off copies).
VkImageMemoryBarrier2 imageMemoryBarrier(VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                                         VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                                         VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);
void imageBarrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout from,
                  VkImageLayout to, VkPipelineStageFlags2 srcStage, VkAccessFlags2 srcAccess,
                  VkPipelineStageFlags2 dstStage, VkAccessFlags2 dstAccess);

// The buffer <-> image copy regions of a whole single-mip image, tightly packed: colour or depth
// aspect, then for depth/stencil formats one stencil byte per texel after the depth. Returns the count.
uint32_t wholeImageCopies(const ImageDesc& desc, VkBufferImageCopy (&copies)[2]);

// Copies bytes into a device-local buffer through a staging buffer.
void uploadBuffer(GpuContext& ctx, Buffer& dst, const void* data, VkDeviceSize size);

// Uploads RGBA8 level 0, generates the mip chain by blits and leaves the image SHADER_READ_ONLY.
void uploadTexture(GpuContext& ctx, Image& image, std::span<const uint8_t> rgba8);

}  // namespace gb
