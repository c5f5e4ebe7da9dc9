// gbuffer_zoo's Vulkan plumbing: instance (validation + messenger when GBLENS_VALIDATE=1), device,
// one queue, images, host-visible buffers, shader modules and one-shot command buffers. Headless.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>

#define ZOO_VK(call)                                                                     \
  do {                                                                                   \
    const VkResult zoo_r_ = (call);                                                      \
    if (zoo_r_ != VK_SUCCESS) {                                                          \
      std::fprintf(stderr, "gbuffer_zoo: %s returned VkResult %d\n", #call, int(zoo_r_)); \
      std::exit(1);                                                                      \
    }                                                                                    \
  } while (0)

namespace zoo {

struct Gpu {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};
  char name[VK_MAX_PHYSICAL_DEVICE_NAME_SIZE] = {};
};

struct Image {
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;         // every aspect (attachments)
  VkImageView sample_view = VK_NULL_HANDLE;  // depth aspect only for depth formats, else == view
  VkFormat format = VK_FORMAT_UNDEFINED;
};

struct Buffer {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;
};

Gpu open_gpu();
void close_gpu(Gpu& g);
// Warnings and errors the validation messenger has printed so far.
int validation_count();

bool is_depth(VkFormat f);
bool has_stencil(VkFormat f);
VkImageAspectFlags all_aspects(VkFormat f);

Image make_image(const Gpu& g, VkFormat format, uint32_t w, uint32_t h, VkImageUsageFlags usage);
void free_image(const Gpu& g, Image& i);
Buffer make_buffer(const Gpu& g, VkDeviceSize size, VkBufferUsageFlags usage);
void free_buffer(const Gpu& g, Buffer& b);
VkShaderModule make_shader(const Gpu& g, const uint32_t* words, size_t bytes);

VkCommandBuffer start_commands(const Gpu& g);
void finish_commands(const Gpu& g, VkCommandBuffer cmd);  // end, submit, wait, free

}  // namespace zoo
