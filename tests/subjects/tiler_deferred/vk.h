// tiler_deferred's Vulkan 1.0 plumbing: instance (validation only with GBLENS_VALIDATE=1), device without
// extensions, one queue, images/buffers with their own memory, shader modules and pipeline helpers.
#pragma once
#include <vulkan/vulkan.h>

#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

#define TD_CHECK(call)                                                                          \
  do {                                                                                          \
    const VkResult td_result_ = (call);                                                         \
    if (td_result_ != VK_SUCCESS) {                                                             \
      std::fprintf(stderr, "tiler_deferred: %s failed (VkResult %d)\n", #call, int(td_result_)); \
      std::exit(1);                                                                             \
    }                                                                                           \
  } while (0)

namespace td {

struct gpu {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkPhysicalDeviceMemoryProperties memory{};
  VkPhysicalDeviceLimits limits{};
  std::string name;
  bool validation = false;
  bool has_lazy_memory = false;  // a memory type with LAZILY_ALLOCATED exists
  PFN_vkSetDebugUtilsObjectNameEXT set_name = nullptr;  // open_gpu(true)
};

struct image {
  VkImage handle = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkImageAspectFlags aspect = 0;
  bool lazy = false;  // bound to a LAZILY_ALLOCATED memory type
};

// Host-visible, coherent, mapped for its lifetime.
struct buffer {
  VkBuffer handle = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize size = 0;
  void* mapped = nullptr;
};

// `names`: VK_EXT_debug_utils enabled so that name_image names images (the compute mode; the others name nothing).
gpu open_gpu(bool names = false);
void name_image(const gpu& g, VkImage image, const char* name);
void close_gpu(gpu& g);
int validation_count();  // warnings + errors reported so far (each printed when it came)

image make_image(const gpu& g, VkFormat format, uint32_t width, uint32_t height, VkSampleCountFlagBits samples,
                 VkImageUsageFlags usage, bool prefer_lazy);
void drop_image(const gpu& g, image& i);
buffer make_buffer(const gpu& g, VkDeviceSize size, VkBufferUsageFlags usage);
void drop_buffer(const gpu& g, buffer& b);

VkShaderModule make_shader(const gpu& g, const uint32_t* code, size_t bytes);
// Bindings 0..n-1 of the given types, one descriptor each, visible to `stages`.
VkDescriptorSetLayout make_set_layout(const gpu& g, const std::vector<VkDescriptorType>& types,
                                      VkShaderStageFlags stages);
VkPipelineLayout make_pipeline_layout(const gpu& g, const std::vector<VkDescriptorSetLayout>& sets,
                                      uint32_t push_bytes, VkShaderStageFlags push_stages);

struct raster_desc {
  VkShaderModule vert = VK_NULL_HANDLE, frag = VK_NULL_HANDLE;
  VkPipelineLayout layout = VK_NULL_HANDLE;
  VkRenderPass pass = VK_NULL_HANDLE;
  uint32_t subpass = 0;
  uint32_t colors = 1;
  VkSampleCountFlagBits samples = VK_SAMPLE_COUNT_1_BIT;
  bool depth = false;     // reverse-Z: test GREATER, write on
  bool vertices = false;  // the scene's vertex format (else a full-screen triangle from gl_VertexIndex)
  uint32_t width = 0, height = 0;
};
VkPipeline make_raster_pipeline(const gpu& g, const raster_desc& d);
VkPipeline make_compute_pipeline(const gpu& g, VkShaderModule module, VkPipelineLayout layout);

VkCommandBuffer begin_frame_commands(const gpu& g);
// Ends, submits (the frame's one vkQueueSubmit), waits on a fence, frees.
void submit_and_wait(const gpu& g, VkCommandBuffer cmd);

}  // namespace td
