// Following the application's objects: images (and swapchain images), views, framebuffers, render
// passes, buffers and their memory, debug names (descriptor sets: descriptors.cpp). Three changes, none
// visible in the application's output: attachment images and swapchains get TRANSFER_SRC usage and
// uniform/storage buffers too (so the layer can copy them), and an attachment a render pass writes
// but does not store (DONT_CARE) is stored.
#include <algorithm>

#include "app/layer/layer.h"

namespace gbl {

namespace {

bool canCopyFrom(DeviceData& d, VkFormat format, VkImageTiling tiling) {
  VkFormatProperties p{};
  d.instance->formatProperties(d.physical, format, &p);
  const VkFormatFeatureFlags f = tiling == VK_IMAGE_TILING_LINEAR ? p.linearTilingFeatures : p.optimalTilingFeatures;
  return f & VK_FORMAT_FEATURE_TRANSFER_SRC_BIT;
}

// An object the application destroys: forgotten before the call goes down (its handle may be reused).
template <class Map, class Handle>
void forget(DeviceData& d, Map& map, Handle handle) {
  std::unique_lock lock(d.objects);
  map.erase(handle);
}

VKAPI_ATTR VkResult VKAPI_CALL CreateImage(VkDevice device, const VkImageCreateInfo* info,
                                           const VkAllocationCallbacks* alloc, VkImage* image) {
  DeviceData& d = *deviceOf(device);
  VkImageCreateInfo patched = *info;
  // Attachments, and storage images (a G-buffer compute writes: dispatch_copies.cpp).
  const VkImageUsageFlags attachment =
      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_STORAGE_BIT;
  // A transient attachment (a tiler keeps it in tile memory) cannot be copied. On a device with no
  // lazily allocated memory the flag changes nothing but the usage allowed: the layer drops it and
  // copies the image; where such memory exists the application may bind it, so it stays transient
  // and a pick of it is refused with what to change (copy.cpp).
  const bool transient = info->usage & VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT;
  bool lazy = false;
  for (uint32_t i = 0; i < d.memory.memoryTypeCount; ++i)
    lazy |= (d.memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT) != 0;
  if ((info->usage & attachment) && (!transient || !lazy) && canCopyFrom(d, info->format, info->tiling)) {
    patched.usage &= ~VkImageUsageFlags(VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT);
    patched.usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  }
  VkResult r = d.vk.CreateImage(device, &patched, alloc, image);
  if (r == VK_SUCCESS && (info->usage & attachment)) {
    std::unique_lock lock(d.objects);
    d.images[*image] = ImageInfo{info->format, info->extent, info->samples, patched.usage, {}, VK_NULL_HANDLE, transient};
  }
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroyImage(VkDevice device, VkImage image, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  forget(d, d.images, image);
  forgetImageId(d, image);
  d.vk.DestroyImage(device, image, alloc);
}

VKAPI_ATTR VkResult VKAPI_CALL CreateSwapchainKHR(VkDevice device, const VkSwapchainCreateInfoKHR* info,
                                                  const VkAllocationCallbacks* alloc, VkSwapchainKHR* swapchain) {
  DeviceData& d = *deviceOf(device);
  VkSwapchainCreateInfoKHR patched = *info;
  VkSurfaceCapabilitiesKHR caps{};
  if (d.instance->surfaceCapabilities &&
      d.instance->surfaceCapabilities(d.physical, info->surface, &caps) == VK_SUCCESS &&
      (caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT))
    patched.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  VkResult r = d.vk.CreateSwapchainKHR(device, &patched, alloc, swapchain);
  if (r == VK_SUCCESS) {
    std::unique_lock lock(d.objects);
    d.swapchains[*swapchain] = ImageInfo{info->imageFormat, {info->imageExtent.width, info->imageExtent.height, 1},
                                         VK_SAMPLE_COUNT_1_BIT, patched.imageUsage, {}, *swapchain};
  }
  {
    std::lock_guard lock(d.frameLock);
    d.presents = true;  // frames end at vkQueuePresentKHR from now on
  }
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroySwapchainKHR(VkDevice device, VkSwapchainKHR swapchain, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  {
    std::unique_lock lock(d.objects);
    d.swapchains.erase(swapchain);
    d.swapchainImages.erase(swapchain);
    std::erase_if(d.images, [&](const auto& i) { return i.second.swapchain == swapchain; });
  }
  d.vk.DestroySwapchainKHR(device, swapchain, alloc);
}

VKAPI_ATTR VkResult VKAPI_CALL GetSwapchainImagesKHR(VkDevice device, VkSwapchainKHR swapchain, uint32_t* count,
                                                     VkImage* images) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.GetSwapchainImagesKHR(device, swapchain, count, images);
  if ((r == VK_SUCCESS || r == VK_INCOMPLETE) && images) {
    std::unique_lock lock(d.objects);
    auto it = d.swapchains.find(swapchain);
    if (it != d.swapchains.end()) {
      for (uint32_t i = 0; i < *count; ++i) d.images[images[i]] = it->second;
      d.swapchainImages[swapchain].assign(images, images + *count);
    }
  }
  return r;
}

VKAPI_ATTR VkResult VKAPI_CALL CreateImageView(VkDevice device, const VkImageViewCreateInfo* info,
                                               const VkAllocationCallbacks* alloc, VkImageView* view) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.CreateImageView(device, info, alloc, view);
  if (r == VK_SUCCESS) {
    std::unique_lock lock(d.objects);
    if (d.images.count(info->image))  // views of attachment images only
      d.views[*view] = ViewInfo{info->image, info->subresourceRange.baseMipLevel, info->subresourceRange.baseArrayLayer, {}};
  }
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroyImageView(VkDevice device, VkImageView view, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  forget(d, d.views, view);
  d.vk.DestroyImageView(device, view, alloc);
}

VKAPI_ATTR VkResult VKAPI_CALL CreateFramebuffer(VkDevice device, const VkFramebufferCreateInfo* info,
                                                 const VkAllocationCallbacks* alloc, VkFramebuffer* fb) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.CreateFramebuffer(device, info, alloc, fb);
  if (r == VK_SUCCESS) {
    FramebufferInfo f;
    if (!(info->flags & VK_FRAMEBUFFER_CREATE_IMAGELESS_BIT))
      f.views.assign(info->pAttachments, info->pAttachments + info->attachmentCount);
    std::unique_lock lock(d.objects);
    d.framebuffers[*fb] = f;
  }
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroyFramebuffer(VkDevice device, VkFramebuffer fb, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  forget(d, d.framebuffers, fb);
  d.vk.DestroyFramebuffer(device, fb, alloc);
}

bool readOnly(VkImageLayout l) {
  switch (l) {
    case VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_STENCIL_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL:
    case VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL: return true;
    default: return false;
  }
}

// Both render pass versions: what the layer needs of each attachment and subpass, and the store
// ops to patch (DONT_CARE on an attachment some subpass writes).
template <class Attachment, class Subpass>
RenderPassInfo describeRenderPass(Attachment* attachments, uint32_t count, const Subpass* subpasses, uint32_t subpassCount,
                                  const void* (*stencilFinal)(const Attachment&)) {
  RenderPassInfo rp;
  rp.attachments.resize(count);
  for (uint32_t a = 0; a < count; ++a) {
    rp.attachments[a].format = attachments[a].format;
    rp.attachments[a].samples = attachments[a].samples;
    rp.attachments[a].finalLayout = rp.attachments[a].stencilFinalLayout = attachments[a].finalLayout;
    if (auto* s = static_cast<const VkAttachmentDescriptionStencilLayout*>(stencilFinal(attachments[a])))
      rp.attachments[a].stencilFinalLayout = s->stencilFinalLayout;
    rp.attachments[a].written = attachments[a].loadOp == VK_ATTACHMENT_LOAD_OP_CLEAR;
    AttachmentOps& ops = rp.attachments[a].ops;
    ops.load = attachments[a].loadOp, ops.stencilLoad = attachments[a].stencilLoadOp;
    ops.store = attachments[a].storeOp, ops.stencilStore = attachments[a].stencilStoreOp;
  }
  for (uint32_t s = 0; s < subpassCount; ++s) {
    const Subpass& sp = subpasses[s];
    for (uint32_t c = 0; c < sp.colorAttachmentCount; ++c)
      if (sp.pColorAttachments[c].attachment < count) rp.attachments[sp.pColorAttachments[c].attachment].written = true;
    if (sp.pDepthStencilAttachment && sp.pDepthStencilAttachment->attachment < count &&
        !readOnly(sp.pDepthStencilAttachment->layout))
      rp.attachments[sp.pDepthStencilAttachment->attachment].written = true;
  }
  for (uint32_t s = 0; s < subpassCount; ++s) {
    std::vector<int>& colors = rp.subpassColors.emplace_back();
    for (uint32_t c = 0; c < subpasses[s].colorAttachmentCount; ++c)
      colors.push_back(subpasses[s].pColorAttachments[c].attachment < count ? int(subpasses[s].pColorAttachments[c].attachment) : -1);
    const auto* ds = subpasses[s].pDepthStencilAttachment;
    rp.subpassDepth.push_back(ds && ds->attachment < count ? int(ds->attachment) : -1);
  }
  if (subpassCount) {
    const Subpass& last = subpasses[subpassCount - 1];
    for (uint32_t c = 0; c < last.colorAttachmentCount; ++c) {
      const uint32_t a = last.pColorAttachments[c].attachment;
      rp.colors.push_back(a < count ? int(a) : -1);
    }
  }
  // The depth attachment: the last subpass's, else the last one any subpass draws with (a deferred
  // render pass whose lighting subpass reads the depth as an input attachment has none in its last).
  for (uint32_t s = subpassCount; s-- > 0 && rp.depth < 0;)
    if (subpasses[s].pDepthStencilAttachment && subpasses[s].pDepthStencilAttachment->attachment < count)
      rp.depth = int(subpasses[s].pDepthStencilAttachment->attachment);
  for (uint32_t a = 0; a < count; ++a) {
    if (!rp.attachments[a].written) continue;
    const FormatInfo& f = formatInfo(attachments[a].format);
    const bool colourOrDepth = !f.stencil || f.depth;
    if (colourOrDepth && attachments[a].storeOp == VK_ATTACHMENT_STORE_OP_DONT_CARE)
      attachments[a].storeOp = VK_ATTACHMENT_STORE_OP_STORE, rp.attachments[a].ops.storePatched = true;
    if (f.stencil && attachments[a].stencilStoreOp == VK_ATTACHMENT_STORE_OP_DONT_CARE)
      attachments[a].stencilStoreOp = VK_ATTACHMENT_STORE_OP_STORE, rp.attachments[a].ops.stencilStorePatched = true;
  }
  return rp;
}

const void* noStencilLayout(const VkAttachmentDescription&) { return nullptr; }
const void* stencilLayout2(const VkAttachmentDescription2& a) {
  for (auto* s = static_cast<const VkBaseInStructure*>(a.pNext); s; s = s->pNext)
    if (s->sType == VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_STENCIL_LAYOUT) return s;
  return nullptr;
}

VKAPI_ATTR VkResult VKAPI_CALL CreateRenderPass(VkDevice device, const VkRenderPassCreateInfo* info,
                                                const VkAllocationCallbacks* alloc, VkRenderPass* rp) {
  DeviceData& d = *deviceOf(device);
  std::vector<VkAttachmentDescription> attachments(info->pAttachments, info->pAttachments + info->attachmentCount);
  RenderPassInfo desc = describeRenderPass(attachments.data(), info->attachmentCount, info->pSubpasses,
                                           info->subpassCount, noStencilLayout);
  VkRenderPassCreateInfo patched = *info;
  patched.pAttachments = attachments.data();
  VkResult r = d.vk.CreateRenderPass(device, &patched, alloc, rp);
  if (r == VK_SUCCESS) {
    std::unique_lock lock(d.objects);
    d.renderPasses[*rp] = std::move(desc);
  }
  return r;
}

VkResult createRenderPass2(PFN_vkCreateRenderPass2 next, VkDevice device, const VkRenderPassCreateInfo2* info,
                           const VkAllocationCallbacks* alloc, VkRenderPass* rp) {
  DeviceData& d = *deviceOf(device);
  std::vector<VkAttachmentDescription2> attachments(info->pAttachments, info->pAttachments + info->attachmentCount);
  RenderPassInfo desc = describeRenderPass(attachments.data(), info->attachmentCount, info->pSubpasses,
                                           info->subpassCount, stencilLayout2);
  VkRenderPassCreateInfo2 patched = *info;
  patched.pAttachments = attachments.data();
  VkResult r = next(device, &patched, alloc, rp);
  if (r == VK_SUCCESS) {
    std::unique_lock lock(d.objects);
    d.renderPasses[*rp] = std::move(desc);
  }
  return r;
}
VKAPI_ATTR VkResult VKAPI_CALL CreateRenderPass2(VkDevice device, const VkRenderPassCreateInfo2* info,
                                                 const VkAllocationCallbacks* alloc, VkRenderPass* rp) {
  return createRenderPass2(deviceOf(device)->vk.CreateRenderPass2, device, info, alloc, rp);
}
VKAPI_ATTR VkResult VKAPI_CALL CreateRenderPass2KHR(VkDevice device, const VkRenderPassCreateInfo2* info,
                                                    const VkAllocationCallbacks* alloc, VkRenderPass* rp) {
  return createRenderPass2(deviceOf(device)->vk.CreateRenderPass2KHR, device, info, alloc, rp);
}

VKAPI_ATTR void VKAPI_CALL DestroyRenderPass(VkDevice device, VkRenderPass rp, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  forget(d, d.renderPasses, rp);
  d.vk.DestroyRenderPass(device, rp, alloc);
}

VKAPI_ATTR VkResult VKAPI_CALL CreateBuffer(VkDevice device, const VkBufferCreateInfo* info,
                                            const VkAllocationCallbacks* alloc, VkBuffer* buffer) {
  DeviceData& d = *deviceOf(device);
  VkBufferCreateInfo patched = *info;
  if (info->usage & (VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT))
    patched.usage |= VK_BUFFER_USAGE_TRANSFER_SRC_BIT;  // the camera may be in it
  VkResult r = d.vk.CreateBuffer(device, &patched, alloc, buffer);
  if (r == VK_SUCCESS) {
    std::unique_lock lock(d.objects);
    d.buffers[*buffer] = BufferInfo{info->size, patched.usage, VK_NULL_HANDLE, 0, {}};
  }
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroyBuffer(VkDevice device, VkBuffer buffer, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  forget(d, d.buffers, buffer);
  d.vk.DestroyBuffer(device, buffer, alloc);
}

void noteBinding(DeviceData& d, VkBuffer buffer, VkDeviceMemory memory, VkDeviceSize offset) {
  std::unique_lock lock(d.objects);
  auto it = d.buffers.find(buffer);
  if (it != d.buffers.end()) it->second.memory = memory, it->second.memoryOffset = offset;
}

VKAPI_ATTR VkResult VKAPI_CALL BindBufferMemory(VkDevice device, VkBuffer buffer, VkDeviceMemory memory, VkDeviceSize offset) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.BindBufferMemory(device, buffer, memory, offset);
  if (r == VK_SUCCESS) noteBinding(d, buffer, memory, offset);
  return r;
}

VkResult bindBufferMemory2(PFN_vkBindBufferMemory2 next, VkDevice device, uint32_t n, const VkBindBufferMemoryInfo* infos) {
  DeviceData& d = *deviceOf(device);
  VkResult r = next(device, n, infos);
  if (r == VK_SUCCESS)
    for (uint32_t i = 0; i < n; ++i) noteBinding(d, infos[i].buffer, infos[i].memory, infos[i].memoryOffset);
  return r;
}
VKAPI_ATTR VkResult VKAPI_CALL BindBufferMemory2(VkDevice device, uint32_t n, const VkBindBufferMemoryInfo* infos) {
  return bindBufferMemory2(deviceOf(device)->vk.BindBufferMemory2, device, n, infos);
}
VKAPI_ATTR VkResult VKAPI_CALL BindBufferMemory2KHR(VkDevice device, uint32_t n, const VkBindBufferMemoryInfo* infos) {
  return bindBufferMemory2(deviceOf(device)->vk.BindBufferMemory2KHR, device, n, infos);
}

VKAPI_ATTR VkResult VKAPI_CALL MapMemory(VkDevice device, VkDeviceMemory memory, VkDeviceSize offset, VkDeviceSize size,
                                         VkMemoryMapFlags flags, void** data) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.MapMemory(device, memory, offset, size, flags, data);
  if (r == VK_SUCCESS && data && *data) {
    std::unique_lock lock(d.objects);
    d.mapped[memory] = static_cast<uint8_t*>(*data) - offset;  // byte 0 of the memory (only offset.. is read)
  }
  return r;
}

VKAPI_ATTR void VKAPI_CALL UnmapMemory(VkDevice device, VkDeviceMemory memory) {
  DeviceData& d = *deviceOf(device);
  forget(d, d.mapped, memory);
  d.vk.UnmapMemory(device, memory);
}

VKAPI_ATTR void VKAPI_CALL FreeMemory(VkDevice device, VkDeviceMemory memory, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  forget(d, d.mapped, memory);
  d.vk.FreeMemory(device, memory, alloc);
}

VKAPI_ATTR VkResult VKAPI_CALL SetDebugUtilsObjectNameEXT(VkDevice device, const VkDebugUtilsObjectNameInfoEXT* info) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.SetDebugUtilsObjectNameEXT(device, info);
  if (!d.connected) return r;  // the loader asks vkGetInstanceProcAddr for it: idle devices come here too
  const std::string name = info->pObjectName ? info->pObjectName : "";
  std::unique_lock lock(d.objects);
  auto set = [&](auto& map, auto handle) {
    auto it = map.find(handle);
    if (it != map.end()) it->second.name = name;
  };
  switch (info->objectType) {
    case VK_OBJECT_TYPE_IMAGE: set(d.images, reinterpret_cast<VkImage>(info->objectHandle)); break;
    case VK_OBJECT_TYPE_IMAGE_VIEW: set(d.views, reinterpret_cast<VkImageView>(info->objectHandle)); break;
    case VK_OBJECT_TYPE_BUFFER: set(d.buffers, reinterpret_cast<VkBuffer>(info->objectHandle)); break;
    case VK_OBJECT_TYPE_RENDER_PASS: set(d.renderPasses, reinterpret_cast<VkRenderPass>(info->objectHandle)); break;
    case VK_OBJECT_TYPE_FRAMEBUFFER: set(d.framebuffers, reinterpret_cast<VkFramebuffer>(info->objectHandle)); break;
    default: break;
  }
  return r;
}

}  // namespace

std::vector<Hook> trackHooks() {
  return {GBL_HOOK(CreateImage),          GBL_HOOK(DestroyImage),          GBL_HOOK(CreateSwapchainKHR),
          GBL_HOOK(DestroySwapchainKHR),  GBL_HOOK(GetSwapchainImagesKHR), GBL_HOOK(CreateImageView),
          GBL_HOOK(DestroyImageView),     GBL_HOOK(CreateFramebuffer),     GBL_HOOK(DestroyFramebuffer),
          GBL_HOOK(CreateRenderPass),     GBL_HOOK(CreateRenderPass2),     GBL_HOOK(CreateRenderPass2KHR),
          GBL_HOOK(DestroyRenderPass),    GBL_HOOK(CreateBuffer),          GBL_HOOK(DestroyBuffer),
          GBL_HOOK(BindBufferMemory),     GBL_HOOK(BindBufferMemory2),     GBL_HOOK(BindBufferMemory2KHR),
          GBL_HOOK(MapMemory),            GBL_HOOK(UnmapMemory),           GBL_HOOK(FreeMemory),
          GBL_HOOK(SetDebugUtilsObjectNameEXT)};
}

}  // namespace gbl
