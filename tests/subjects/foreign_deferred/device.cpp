// The instance, device and small resource helpers of foreign_deferred (see device.h). Validation is
// asked for by GBLENS_VALIDATE=1 (the variable gblens's tests set everywhere); any warning or error
// is printed at once and counted, and main() exits non-zero when the count is not zero.
#include "device.h"

#include <cstring>
#include <vector>

namespace fd {

namespace {

int g_messages = 0;

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  ++g_messages;
  const bool error = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  std::fprintf(stderr, "foreign_deferred: validation %s: %s\n", error ? "error" : "warning", data->pMessage);
  return VK_FALSE;
}

bool validation_wanted() {
  const char* v = std::getenv("GBLENS_VALIDATE");
  return v && *v && std::strcmp(v, "0") != 0;
}

bool has_layer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const VkLayerProperties& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

uint32_t memory_type(const device_t& d, uint32_t bits, VkMemoryPropertyFlags want) {
  for (uint32_t i = 0; i < d.memory.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (d.memory.memoryTypes[i].propertyFlags & want) == want) return i;
  std::fprintf(stderr, "foreign_deferred: no memory type with flags 0x%x\n", unsigned(want));
  std::exit(1);
}

VkDeviceMemory allocate(const device_t& d, const VkMemoryRequirements& req, VkMemoryPropertyFlags want) {
  VkMemoryAllocateInfo alloc{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  alloc.allocationSize = req.size;
  alloc.memoryTypeIndex = memory_type(d, req.memoryTypeBits, want);
  VkDeviceMemory memory;
  FD_CHECK(vkAllocateMemory(d.device, &alloc, nullptr, &memory));
  return memory;
}

void create_instance(device_t& d) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "foreign_deferred";
  app.apiVersion = VK_API_VERSION_1_1;
  std::vector<const char*> layers, extensions;
  VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = on_message;
  // Synchronization validation too: the render passes' dependencies are this app's own.
  VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &sync;
  features.pNext = &messenger;
  d.validation = validation_wanted();
  if (d.validation) {
    if (!has_layer("VK_LAYER_KHRONOS_validation")) {
      std::fprintf(stderr, "foreign_deferred: GBLENS_VALIDATE=1 but VK_LAYER_KHRONOS_validation is not installed\n");
      std::exit(1);
    }
    layers.push_back("VK_LAYER_KHRONOS_validation");
    // The messenger is the only use of debug utils: no object names, no labels.
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  }
  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pNext = d.validation ? &features : nullptr;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  FD_CHECK(vkCreateInstance(&info, nullptr, &d.instance));
  if (d.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(d.instance, "vkCreateDebugUtilsMessengerEXT"));
    FD_CHECK(create(d.instance, &messenger, nullptr, &d.messenger));
  }
}

}  // namespace

int validation_messages() { return g_messages; }

device_t create_device() {
  device_t d;
  create_instance(d);
  uint32_t n = 0;
  FD_CHECK(vkEnumeratePhysicalDevices(d.instance, &n, nullptr));
  if (n == 0) {
    std::fprintf(stderr, "foreign_deferred: no Vulkan device\n");
    std::exit(1);
  }
  std::vector<VkPhysicalDevice> gpus(n);
  FD_CHECK(vkEnumeratePhysicalDevices(d.instance, &n, gpus.data()));
  d.gpu = gpus[0];
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(d.gpu, &props);
  d.gpu_name = props.deviceName;
  d.sub_pixel_bits = props.limits.subPixelPrecisionBits;
  vkGetPhysicalDeviceMemoryProperties(d.gpu, &d.memory);

  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(d.gpu, &families, nullptr);
  std::vector<VkQueueFamilyProperties> family(families);
  vkGetPhysicalDeviceQueueFamilyProperties(d.gpu, &families, family.data());
  d.queue_family = families;
  for (uint32_t i = 0; i < families && d.queue_family == families; ++i)
    if (family[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) d.queue_family = i;
  if (d.queue_family == families) {
    std::fprintf(stderr, "foreign_deferred: %s has no graphics queue\n", d.gpu_name.c_str());
    std::exit(1);
  }
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue.queueFamilyIndex = d.queue_family;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue;
  FD_CHECK(vkCreateDevice(d.gpu, &info, nullptr, &d.device));
  vkGetDeviceQueue(d.device, d.queue_family, 0, &d.queue);
  VkCommandPoolCreateInfo pool{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool.queueFamilyIndex = d.queue_family;
  FD_CHECK(vkCreateCommandPool(d.device, &pool, nullptr, &d.pool));
  return d;
}

void destroy_device(device_t& d) {
  vkDestroyCommandPool(d.device, d.pool, nullptr);
  vkDestroyDevice(d.device, nullptr);
  if (d.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(d.instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(d.instance, d.messenger, nullptr);
  }
  vkDestroyInstance(d.instance, nullptr);
  d = device_t{};
}

image_t create_image(const device_t& d, VkFormat format, uint32_t width, uint32_t height, VkImageUsageFlags usage) {
  image_t i;
  i.format = format;
  const bool depth = format == VK_FORMAT_D32_SFLOAT;
  i.aspect = depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageCreateInfo info{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = VK_SAMPLE_COUNT_1_BIT;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  FD_CHECK(vkCreateImage(d.device, &info, nullptr, &i.image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(d.device, i.image, &req);
  i.memory = allocate(d, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  FD_CHECK(vkBindImageMemory(d.device, i.image, i.memory, 0));
  VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  view.image = i.image;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.subresourceRange = {i.aspect, 0, 1, 0, 1};
  FD_CHECK(vkCreateImageView(d.device, &view, nullptr, &i.view));
  return i;
}

void destroy_image(const device_t& d, image_t& i) {
  vkDestroyImageView(d.device, i.view, nullptr);
  vkDestroyImage(d.device, i.image, nullptr);
  vkFreeMemory(d.device, i.memory, nullptr);
  i = image_t{};
}

buffer_t create_host_buffer(const device_t& d, VkDeviceSize size, VkBufferUsageFlags usage) {
  buffer_t b;
  b.size = size;
  VkBufferCreateInfo info{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  info.size = size;
  info.usage = usage;
  FD_CHECK(vkCreateBuffer(d.device, &info, nullptr, &b.buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(d.device, b.buffer, &req);
  b.memory = allocate(d, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  FD_CHECK(vkBindBufferMemory(d.device, b.buffer, b.memory, 0));
  FD_CHECK(vkMapMemory(d.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  return b;
}

void destroy_buffer(const device_t& d, buffer_t& b) {
  vkUnmapMemory(d.device, b.memory);
  vkDestroyBuffer(d.device, b.buffer, nullptr);
  vkFreeMemory(d.device, b.memory, nullptr);
  b = buffer_t{};
}

VkShaderModule create_shader(const device_t& d, const uint32_t* code, size_t bytes) {
  VkShaderModuleCreateInfo info{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  info.codeSize = bytes;
  info.pCode = code;
  VkShaderModule m;
  FD_CHECK(vkCreateShaderModule(d.device, &info, nullptr, &m));
  return m;
}

VkCommandBuffer begin_commands(const device_t& d) {
  VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  alloc.commandPool = d.pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd;
  FD_CHECK(vkAllocateCommandBuffers(d.device, &alloc, &cmd));
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  FD_CHECK(vkBeginCommandBuffer(cmd, &begin));
  return cmd;
}

void submit_and_wait(const device_t& d, VkCommandBuffer cmd) {
  FD_CHECK(vkEndCommandBuffer(cmd));
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  FD_CHECK(vkCreateFence(d.device, &fence_info, nullptr, &fence));
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  FD_CHECK(vkQueueSubmit(d.queue, 1, &submit, fence));
  FD_CHECK(vkWaitForFences(d.device, 1, &fence, VK_TRUE, UINT64_MAX));
  vkDestroyFence(d.device, fence, nullptr);
  vkFreeCommandBuffers(d.device, d.pool, 1, &cmd);
}

}  // namespace fd
