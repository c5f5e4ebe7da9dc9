// tiler_deferred's Vulkan 1.0 plumbing (vk.h). GBLENS_VALIDATE=1 turns on VK_LAYER_KHRONOS_validation with
// synchronization validation and a messenger; every warning or error is printed and counted.
#include "vk.h"

#include <algorithm>
#include <cstring>

namespace td {

namespace {

int g_count = 0;

VKAPI_ATTR VkBool32 VKAPI_CALL on_message(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                          VkDebugUtilsMessageTypeFlagsEXT,
                                          const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) return VK_FALSE;
  ++g_count;
  std::fprintf(stderr, "tiler_deferred: validation error: %s\n", data->pMessage);
  return VK_FALSE;
}

bool validation_wanted() {
  const char* v = std::getenv("GBLENS_VALIDATE");
  return v && *v && std::strcmp(v, "0") != 0;
}

bool layer_present(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (const VkLayerProperties& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

bool layer_extension(const char* layer, const char* extension) {
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(layer, &n, nullptr);
  std::vector<VkExtensionProperties> list(n);
  vkEnumerateInstanceExtensionProperties(layer, &n, list.data());
  for (const VkExtensionProperties& e : list)
    if (std::strcmp(e.extensionName, extension) == 0) return true;
  return false;
}

uint32_t memory_type(const gpu& g, uint32_t bits, VkMemoryPropertyFlags want) {
  for (uint32_t i = 0; i < g.memory.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (g.memory.memoryTypes[i].propertyFlags & want) == want) return i;
  return UINT32_MAX;
}

VkDeviceMemory allocate(const gpu& g, const VkMemoryRequirements& req, uint32_t type) {
  if (type == UINT32_MAX) {
    std::fprintf(stderr, "tiler_deferred: no suitable memory type\n");
    std::exit(1);
  }
  VkMemoryAllocateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO;
  info.allocationSize = req.size;
  info.memoryTypeIndex = type;
  VkDeviceMemory m;
  TD_CHECK(vkAllocateMemory(g.device, &info, nullptr, &m));
  return m;
}

void create_instance(gpu& g, bool names) {
  VkApplicationInfo app{};
  app.sType = VK_STRUCTURE_TYPE_APPLICATION_INFO;
  app.pApplicationName = "tiler_deferred";
  app.applicationVersion = 1;
  app.apiVersion = VK_API_VERSION_1_0;
  const char* k_layer = "VK_LAYER_KHRONOS_validation";
  std::vector<const char*> layers, extensions;
  VkDebugUtilsMessengerCreateInfoEXT messenger{};
  messenger.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT;
  messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                          VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger.pfnUserCallback = on_message;
  const VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
  VkValidationFeaturesEXT features{};
  features.sType = VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT;
  features.pNext = &messenger;
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = &sync;
  const void* chain = nullptr;
  g.validation = validation_wanted();
  if (g.validation) {
    if (!layer_present(k_layer)) {
      std::fprintf(stderr, "tiler_deferred: GBLENS_VALIDATE=1 but %s is not installed\n", k_layer);
      std::exit(1);
    }
    layers.push_back(k_layer);
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
    chain = &messenger;
    // Synchronization validation, where the layer offers VK_EXT_validation_features.
    if (layer_extension(k_layer, VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME)) {
      extensions.push_back(VK_EXT_VALIDATION_FEATURES_EXTENSION_NAME);
      chain = &features;
    }
  }
  if (names && std::find_if(extensions.begin(), extensions.end(), [](const char* e) {
                 return std::strcmp(e, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) == 0;
               }) == extensions.end())
    extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  VkInstanceCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO;
  info.pNext = chain;
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  TD_CHECK(vkCreateInstance(&info, nullptr, &g.instance));
  if (names)
    g.set_name = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(vkGetInstanceProcAddr(g.instance, "vkSetDebugUtilsObjectNameEXT"));
  if (g.validation) {
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(g.instance, "vkCreateDebugUtilsMessengerEXT"));
    TD_CHECK(create(g.instance, &messenger, nullptr, &g.messenger));
  }
}

}  // namespace

int validation_count() { return g_count; }

void name_image(const gpu& g, VkImage image, const char* name) {
  if (!g.set_name) return;
  VkDebugUtilsObjectNameInfoEXT info{};
  info.sType = VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT;
  info.objectType = VK_OBJECT_TYPE_IMAGE;
  info.objectHandle = uint64_t(image);
  info.pObjectName = name;
  TD_CHECK(g.set_name(g.device, &info));
}

gpu open_gpu(bool names) {
  gpu g;
  create_instance(g, names);
  uint32_t n = 0;
  TD_CHECK(vkEnumeratePhysicalDevices(g.instance, &n, nullptr));
  if (n == 0) {
    std::fprintf(stderr, "tiler_deferred: no Vulkan device\n");
    std::exit(1);
  }
  std::vector<VkPhysicalDevice> all(n);
  TD_CHECK(vkEnumeratePhysicalDevices(g.instance, &n, all.data()));
  g.physical = all[0];
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(g.physical, &props);
  g.name = props.deviceName;
  g.limits = props.limits;
  vkGetPhysicalDeviceMemoryProperties(g.physical, &g.memory);
  for (uint32_t i = 0; i < g.memory.memoryTypeCount; ++i)
    if (g.memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT) g.has_lazy_memory = true;
  uint32_t families = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(g.physical, &families, nullptr);
  std::vector<VkQueueFamilyProperties> family(families);
  vkGetPhysicalDeviceQueueFamilyProperties(g.physical, &families, family.data());
  const VkQueueFlags want = VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT;
  g.family = UINT32_MAX;
  for (uint32_t i = 0; i < families && g.family == UINT32_MAX; ++i)
    if ((family[i].queueFlags & want) == want) g.family = i;
  if (g.family == UINT32_MAX) {
    std::fprintf(stderr, "tiler_deferred: %s has no graphics+compute queue\n", g.name.c_str());
    std::exit(1);
  }
  const float priority = 1.0f;
  VkDeviceQueueCreateInfo queue{};
  queue.sType = VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO;
  queue.queueFamilyIndex = g.family;
  queue.queueCount = 1;
  queue.pQueuePriorities = &priority;
  VkDeviceCreateInfo info{};  // no extensions, no features
  info.sType = VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue;
  TD_CHECK(vkCreateDevice(g.physical, &info, nullptr, &g.device));
  vkGetDeviceQueue(g.device, g.family, 0, &g.queue);
  VkCommandPoolCreateInfo pool{};
  pool.sType = VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO;
  pool.queueFamilyIndex = g.family;
  TD_CHECK(vkCreateCommandPool(g.device, &pool, nullptr, &g.pool));
  return g;
}

void close_gpu(gpu& g) {
  vkDestroyCommandPool(g.device, g.pool, nullptr);
  vkDestroyDevice(g.device, nullptr);
  if (g.messenger) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(g.instance, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(g.instance, g.messenger, nullptr);
  }
  vkDestroyInstance(g.instance, nullptr);
  g = gpu{};
}

image make_image(const gpu& g, VkFormat format, uint32_t width, uint32_t height, VkSampleCountFlagBits samples,
                 VkImageUsageFlags usage, bool prefer_lazy) {
  image i;
  i.format = format;
  i.aspect = format == VK_FORMAT_D32_SFLOAT ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
  VkImageCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO;
  info.imageType = VK_IMAGE_TYPE_2D;
  info.format = format;
  info.extent = {width, height, 1};
  info.mipLevels = 1;
  info.arrayLayers = 1;
  info.samples = samples;
  info.tiling = VK_IMAGE_TILING_OPTIMAL;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  TD_CHECK(vkCreateImage(g.device, &info, nullptr, &i.handle));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(g.device, i.handle, &req);
  uint32_t type = UINT32_MAX;
  if (prefer_lazy) type = memory_type(g, req.memoryTypeBits, VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT);
  i.lazy = type != UINT32_MAX;
  if (type == UINT32_MAX) type = memory_type(g, req.memoryTypeBits, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  if (type == UINT32_MAX) type = memory_type(g, req.memoryTypeBits, 0);
  i.memory = allocate(g, req, type);
  TD_CHECK(vkBindImageMemory(g.device, i.handle, i.memory, 0));
  VkImageViewCreateInfo view{};
  view.sType = VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO;
  view.image = i.handle;
  view.viewType = VK_IMAGE_VIEW_TYPE_2D;
  view.format = format;
  view.components = {VK_COMPONENT_SWIZZLE_IDENTITY, VK_COMPONENT_SWIZZLE_IDENTITY, VK_COMPONENT_SWIZZLE_IDENTITY,
                     VK_COMPONENT_SWIZZLE_IDENTITY};
  view.subresourceRange = {i.aspect, 0, 1, 0, 1};
  TD_CHECK(vkCreateImageView(g.device, &view, nullptr, &i.view));
  return i;
}

void drop_image(const gpu& g, image& i) {
  vkDestroyImageView(g.device, i.view, nullptr);
  vkDestroyImage(g.device, i.handle, nullptr);
  vkFreeMemory(g.device, i.memory, nullptr);
  i = image{};
}

buffer make_buffer(const gpu& g, VkDeviceSize size, VkBufferUsageFlags usage) {
  buffer b;
  b.size = size;
  VkBufferCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO;
  info.size = size;
  info.usage = usage;
  info.sharingMode = VK_SHARING_MODE_EXCLUSIVE;
  TD_CHECK(vkCreateBuffer(g.device, &info, nullptr, &b.handle));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(g.device, b.handle, &req);
  b.memory = allocate(g, req, memory_type(g, req.memoryTypeBits, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT |
                                                                      VK_MEMORY_PROPERTY_HOST_COHERENT_BIT));
  TD_CHECK(vkBindBufferMemory(g.device, b.handle, b.memory, 0));
  TD_CHECK(vkMapMemory(g.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  std::memset(b.mapped, 0, size_t(size));
  return b;
}

void drop_buffer(const gpu& g, buffer& b) {
  vkUnmapMemory(g.device, b.memory);
  vkDestroyBuffer(g.device, b.handle, nullptr);
  vkFreeMemory(g.device, b.memory, nullptr);
  b = buffer{};
}

VkShaderModule make_shader(const gpu& g, const uint32_t* code, size_t bytes) {
  VkShaderModuleCreateInfo info{};
  info.sType = VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO;
  info.codeSize = bytes;
  info.pCode = code;
  VkShaderModule m;
  TD_CHECK(vkCreateShaderModule(g.device, &info, nullptr, &m));
  return m;
}

VkCommandBuffer begin_frame_commands(const gpu& g) {
  VkCommandBufferAllocateInfo alloc{};
  alloc.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO;
  alloc.commandPool = g.pool;
  alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  alloc.commandBufferCount = 1;
  VkCommandBuffer cmd;
  TD_CHECK(vkAllocateCommandBuffers(g.device, &alloc, &cmd));
  VkCommandBufferBeginInfo begin{};
  begin.sType = VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO;
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  TD_CHECK(vkBeginCommandBuffer(cmd, &begin));
  return cmd;
}

void submit_and_wait(const gpu& g, VkCommandBuffer cmd) {
  TD_CHECK(vkEndCommandBuffer(cmd));
  VkFenceCreateInfo fence_info{};
  fence_info.sType = VK_STRUCTURE_TYPE_FENCE_CREATE_INFO;
  VkFence fence;
  TD_CHECK(vkCreateFence(g.device, &fence_info, nullptr, &fence));
  VkSubmitInfo submit{};
  submit.sType = VK_STRUCTURE_TYPE_SUBMIT_INFO;
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  TD_CHECK(vkQueueSubmit(g.queue, 1, &submit, fence));
  TD_CHECK(vkWaitForFences(g.device, 1, &fence, VK_TRUE, UINT64_MAX));
  vkDestroyFence(g.device, fence, nullptr);
  vkFreeCommandBuffers(g.device, g.pool, 1, &cmd);
}

}  // namespace td
