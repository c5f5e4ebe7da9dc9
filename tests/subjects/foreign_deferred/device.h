// foreign_deferred's Vulkan device: instance (with the validation layer and a messenger when
// GBLENS_VALIDATE=1), one graphics queue, memory and one-shot command helpers. No surface, no swapchain.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdio>
#include <cstdlib>
#include <string>

#define FD_CHECK(call)                                                                          \
  do {                                                                                          \
    VkResult fd_result_ = (call);                                                               \
    if (fd_result_ != VK_SUCCESS) {                                                             \
      std::fprintf(stderr, "foreign_deferred: %s failed (VkResult %d)\n", #call, int(fd_result_)); \
      std::exit(1);                                                                             \
    }                                                                                           \
  } while (0)

namespace fd {

struct device_t {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice gpu = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queue_family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};
  bool validation = false;
  std::string gpu_name;
  uint32_t sub_pixel_bits = 0;  // VkPhysicalDeviceLimits::subPixelPrecisionBits (camera.json, for error bounds)
};

// An image with its own memory and one view.
struct image_t {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = 0;
};

// A buffer with its own host-visible, coherent memory, mapped for its lifetime.
struct buffer_t {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;
};

device_t create_device();
void destroy_device(device_t& d);
// Validation messages (warnings and errors) seen so far; each was printed when it arrived.
int validation_messages();

image_t create_image(const device_t& d, VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage);
void destroy_image(const device_t& d, image_t& i);
buffer_t create_host_buffer(const device_t& d, VkDeviceSize size, VkBufferUsageFlags usage);
void destroy_buffer(const device_t& d, buffer_t& b);

VkShaderModule create_shader(const device_t& d, const uint32_t* code, size_t bytes);

// A primary command buffer, begun; submit_and_wait ends, submits, waits and frees it.
VkCommandBuffer begin_commands(const device_t& d);
void submit_and_wait(const device_t& d, VkCommandBuffer cmd);

}  // namespace fd
