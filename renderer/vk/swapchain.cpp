// Swapchain creation, re-creation on resize, and the acquire/submit/present of one frame.
#include "renderer/vk/swapchain.h"

#include <algorithm>

#include "renderer/vk/check.h"

namespace gb {

static void destroyImageResources(GpuContext& ctx, Swapchain& sc) {
  for (VkFramebuffer f : sc.framebuffers) vkDestroyFramebuffer(ctx.device, f, nullptr);
  for (VkImageView v : sc.views) vkDestroyImageView(ctx.device, v, nullptr);
  for (VkSemaphore s : sc.renderDone) vkDestroySemaphore(ctx.device, s, nullptr);
  sc.framebuffers.clear();
  sc.views.clear();
  sc.renderDone.clear();
  sc.images.clear();
}

static VkSurfaceFormatKHR chooseFormat(GpuContext& ctx, VkSurfaceKHR surface) {
  uint32_t n = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physical, surface, &n, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(n);
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(ctx.physical, surface, &n, formats.data()));
  GB_ASSERT(!formats.empty());
  for (VkFormat want : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const VkSurfaceFormatKHR& f : formats)
      if (f.format == want && f.colorSpace == VK_COLOR_SPACE_SRGB_NONLINEAR_KHR) return f;
  return formats[0];
}

static VkRenderPass createPresentPass(GpuContext& ctx, VkFormat format) {
  VkAttachmentDescription a{};
  a.format = format;
  a.samples = VK_SAMPLE_COUNT_1_BIT;
  a.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
  a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
  a.stencilLoadOp = VK_ATTACHMENT_LOAD_OP_DONT_CARE;
  a.stencilStoreOp = VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  a.finalLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  VkAttachmentReference ref{0, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL};
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = 1;
  sub.pColorAttachments = &ref;
  // The acquire semaphore is waited at COLOR_ATTACHMENT_OUTPUT: the layout transition must wait too.
  VkSubpassDependency dep{};
  dep.srcSubpass = VK_SUBPASS_EXTERNAL;
  dep.dstSubpass = 0;
  dep.srcStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dep.dstStageMask = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  dep.srcAccessMask = 0;
  dep.dstAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
  VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  ci.attachmentCount = 1;
  ci.pAttachments = &a;
  ci.subpassCount = 1;
  ci.pSubpasses = &sub;
  ci.dependencyCount = 1;
  ci.pDependencies = &dep;
  VkRenderPass rp;
  VK_CHECK(vkCreateRenderPass(ctx.device, &ci, nullptr, &rp));
  return rp;
}

// What does not change with the size, made on first use: the surface format, the present pass,
// the acquire semaphore, the frame fence and the command buffer.
static void createOnce(GpuContext& ctx, Swapchain& sc) {
  sc.format = chooseFormat(ctx, sc.surface);
  sc.renderPass = createPresentPass(ctx, sc.format.format);
  VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VK_CHECK(vkCreateSemaphore(ctx.device, &si, nullptr, &sc.acquired));
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  fi.flags = VK_FENCE_CREATE_SIGNALED_BIT;
  VK_CHECK(vkCreateFence(ctx.device, &fi, nullptr, &sc.fence));
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = ctx.commandPool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &ai, &sc.cmd));
}

// Per swapchain image: a view, a framebuffer of the present pass and a render-done semaphore.
static void createImageResources(GpuContext& ctx, Swapchain& sc) {
  uint32_t n = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, sc.swapchain, &n, nullptr));
  sc.images.resize(n);
  VK_CHECK(vkGetSwapchainImagesKHR(ctx.device, sc.swapchain, &n, sc.images.data()));
  for (VkImage img : sc.images) {
    VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    vi.image = img;
    vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
    vi.format = sc.format.format;
    vi.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView view;
    VK_CHECK(vkCreateImageView(ctx.device, &vi, nullptr, &view));
    sc.views.push_back(view);
    VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fi.renderPass = sc.renderPass;
    fi.attachmentCount = 1;
    fi.pAttachments = &view;
    fi.width = sc.extent.width;
    fi.height = sc.extent.height;
    fi.layers = 1;
    VkFramebuffer fb;
    VK_CHECK(vkCreateFramebuffer(ctx.device, &fi, nullptr, &fb));
    sc.framebuffers.push_back(fb);
    VkSemaphoreCreateInfo si{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    VkSemaphore s;
    VK_CHECK(vkCreateSemaphore(ctx.device, &si, nullptr, &s));
    sc.renderDone.push_back(s);
  }
}

bool createSwapchain(GpuContext& ctx, Swapchain& sc, uint32_t width, uint32_t height) {
  GB_ASSERT(sc.surface);
  VkBool32 supported = VK_FALSE;
  VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physical, ctx.queueFamily, sc.surface, &supported));
  GB_ASSERT(supported);
  if (sc.fence) VK_CHECK(vkWaitForFences(ctx.device, 1, &sc.fence, VK_TRUE, UINT64_MAX));
  vkDeviceWaitIdle(ctx.device);

  VkSurfaceCapabilitiesKHR caps;
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx.physical, sc.surface, &caps));
  VkExtent2D extent = caps.currentExtent;
  if (extent.width == UINT32_MAX) {
    extent.width = std::clamp(width, caps.minImageExtent.width, caps.maxImageExtent.width);
    extent.height = std::clamp(height, caps.minImageExtent.height, caps.maxImageExtent.height);
  }
  if (extent.width == 0 || extent.height == 0 || width == 0 || height == 0) return false;
  if (!sc.renderPass) createOnce(ctx, sc);

  sc.minImageCount = std::max(2u, caps.minImageCount);
  if (caps.maxImageCount) sc.minImageCount = std::min(sc.minImageCount, caps.maxImageCount);
  VkSwapchainCreateInfoKHR ci{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  ci.surface = sc.surface;
  ci.minImageCount = sc.minImageCount;
  ci.imageFormat = sc.format.format;
  ci.imageColorSpace = sc.format.colorSpace;
  ci.imageExtent = extent;
  ci.imageArrayLayers = 1;
  ci.imageUsage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  ci.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  ci.preTransform = caps.currentTransform;
  ci.compositeAlpha = (caps.supportedCompositeAlpha & VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR)
                          ? VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR
                          : VkCompositeAlphaFlagBitsKHR(caps.supportedCompositeAlpha & -caps.supportedCompositeAlpha);
  ci.presentMode = sc.presentMode;  // FIFO: always supported, and the viewer renders on demand anyway
  ci.clipped = VK_TRUE;
  VkSwapchainKHR old = sc.swapchain;
  ci.oldSwapchain = old;
  VK_CHECK(vkCreateSwapchainKHR(ctx.device, &ci, nullptr, &sc.swapchain));
  destroyImageResources(ctx, sc);
  if (old) vkDestroySwapchainKHR(ctx.device, old, nullptr);
  sc.extent = extent;
  createImageResources(ctx, sc);
  return true;
}

void destroySwapchain(GpuContext& ctx, Swapchain& sc) {
  if (!ctx.device) return;
  vkDeviceWaitIdle(ctx.device);
  destroyImageResources(ctx, sc);
  if (sc.swapchain) vkDestroySwapchainKHR(ctx.device, sc.swapchain, nullptr);
  if (sc.renderPass) vkDestroyRenderPass(ctx.device, sc.renderPass, nullptr);
  if (sc.acquired) vkDestroySemaphore(ctx.device, sc.acquired, nullptr);
  if (sc.fence) vkDestroyFence(ctx.device, sc.fence, nullptr);
  if (sc.cmd) vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &sc.cmd);
  VkSurfaceKHR surface = sc.surface;
  sc = Swapchain{};
  sc.surface = surface;
}

bool beginSwapchainFrame(GpuContext& ctx, Swapchain& sc, uint32_t& imageIndex, const float clear[4]) {
  VK_CHECK(vkWaitForFences(ctx.device, 1, &sc.fence, VK_TRUE, UINT64_MAX));
  VkResult res = vkAcquireNextImageKHR(ctx.device, sc.swapchain, UINT64_MAX, sc.acquired, VK_NULL_HANDLE, &imageIndex);
  if (res == VK_ERROR_OUT_OF_DATE_KHR) return false;
  if (res != VK_SUBOPTIMAL_KHR) VK_CHECK(res);
  VK_CHECK(vkResetFences(ctx.device, 1, &sc.fence));
  VK_CHECK(vkResetCommandBuffer(sc.cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(sc.cmd, &bi));
  VkClearValue cv{};
  for (int i = 0; i < 4; ++i) cv.color.float32[i] = clear[i];
  VkRenderPassBeginInfo rbi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  rbi.renderPass = sc.renderPass;
  rbi.framebuffer = sc.framebuffers[imageIndex];
  rbi.renderArea = {{0, 0}, sc.extent};
  rbi.clearValueCount = 1;
  rbi.pClearValues = &cv;
  vkCmdBeginRenderPass(sc.cmd, &rbi, VK_SUBPASS_CONTENTS_INLINE);
  return true;
}

bool endSwapchainFrame(GpuContext& ctx, Swapchain& sc, uint32_t imageIndex) {
  vkCmdEndRenderPass(sc.cmd);
  VK_CHECK(vkEndCommandBuffer(sc.cmd));
  VkPipelineStageFlags wait = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.waitSemaphoreCount = 1;
  si.pWaitSemaphores = &sc.acquired;
  si.pWaitDstStageMask = &wait;
  si.commandBufferCount = 1;
  si.pCommandBuffers = &sc.cmd;
  si.signalSemaphoreCount = 1;
  si.pSignalSemaphores = &sc.renderDone[imageIndex];
  VK_CHECK(vkQueueSubmit(ctx.queue, 1, &si, sc.fence));
  VkPresentInfoKHR pi{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  pi.waitSemaphoreCount = 1;
  pi.pWaitSemaphores = &sc.renderDone[imageIndex];
  pi.swapchainCount = 1;
  pi.pSwapchains = &sc.swapchain;
  pi.pImageIndices = &imageIndex;
  VkResult res = vkQueuePresentKHR(ctx.queue, &pi);
  if (res == VK_ERROR_OUT_OF_DATE_KHR || res == VK_SUBOPTIMAL_KHR) return false;
  VK_CHECK(res);
  return true;
}

}  // namespace gb
