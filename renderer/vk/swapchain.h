// The window's swapchain as a plain struct + free functions: images, views, the render pass the
// viewer draws its views and UI into, framebuffers and per-frame sync. The surface comes from
// the window system (app/), so nothing here knows about GLFW.
#pragma once
#include <vulkan/vulkan.h>

#include <vector>

#include "renderer/vk/context.h"

namespace gb {

struct Swapchain {
  VkSurfaceKHR surface = VK_NULL_HANDLE;
  VkSwapchainKHR swapchain = VK_NULL_HANDLE;
  VkSurfaceFormatKHR format{};
  VkPresentModeKHR presentMode = VK_PRESENT_MODE_FIFO_KHR;
  VkExtent2D extent{0, 0};
  uint32_t minImageCount = 2;
  std::vector<VkImage> images;
  std::vector<VkImageView> views;
  std::vector<VkFramebuffer> framebuffers;
  std::vector<VkSemaphore> renderDone;  // per image: presentation waits on it
  VkRenderPass renderPass = VK_NULL_HANDLE;  // one colour attachment, cleared, ends PRESENT_SRC
  VkSemaphore acquired = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;  // signalled when the last presented frame's commands finished
};

// Creates (or re-creates, after a resize) the swapchain for a surface of `width` x `height`
// framebuffer pixels. Prefers a UNORM format (Dear ImGui's colours are meant for one) and FIFO.
// Returns false when the surface has a zero extent (minimised): nothing to draw into.
bool createSwapchain(GpuContext& ctx, Swapchain& sc, uint32_t width, uint32_t height);
// Destroys everything but the surface (the window system owns it; destroyed with the instance).
void destroySwapchain(GpuContext& ctx, Swapchain& sc);

// Waits for the previous frame, acquires the next image and begins the command buffer and the
// render pass (cleared to `clear`). Returns false when the swapchain is out of date (re-create).
bool beginSwapchainFrame(GpuContext& ctx, Swapchain& sc, uint32_t& imageIndex, const float clear[4]);
// Ends the render pass and the command buffer, submits and presents. Returns false when the
// swapchain is out of date or suboptimal (re-create before the next frame).
bool endSwapchainFrame(GpuContext& ctx, Swapchain& sc, uint32_t imageIndex);

}  // namespace gb
