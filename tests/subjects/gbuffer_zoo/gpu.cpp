// See gpu.h. GBLENS_VALIDATE=1 turns on VK_LAYER_KHRONOS_validation with synchronization validation;
// every warning or error the messenger receives is printed as "gbuffer_zoo: validation: ..." and
// counted (main() then exits 1).
#include "gpu.h"

#include <cstring>
#include <vector>

namespace zoo {

namespace {

int g_validation = 0;

VKAPI_ATTR VkBool32 VKAPI_CALL messenger_cb(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                            VkDebugUtilsMessageTypeFlagsEXT,
                                            const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT) {
    ++g_validation;
    std::fprintf(stderr, "gbuffer_zoo: validation: %s\n", data->pMessage);
  }
  return VK_FALSE;
}

bool want_validation() {
  const char* v = std::getenv("GBLENS_VALIDATE");
  return v && v[0] && std::strcmp(v, "0") != 0;
}

void create_instance(Gpu& g, bool validate) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "gbuffer_zoo";
  app.pEngineName = "zoo";
  app.apiVersion = VK_API_VERSION_1_1;
  VkDebugUtilsMessengerCreateInfoEXT m{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  m.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  m.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                  VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  m.pfnUserCallback = messenger_cb;
  const VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.pNext = &m;
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  const char* layer = "VK_LAYER_KHRONOS_validation";
  const char* ext = VK_EXT_DEBUG_UTILS_EXTENSION_NAME;
  VkInstanceCreateInfo ci{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ci.pApplicationInfo = &app;
  if (validate) {
    ci.pNext = &features;
    ci.enabledLayerCount = 1;
    ci.ppEnabledLayerNames = &layer;
    ci.enabledExtensionCount = 1;  // the messenger only: no object names, no labels
    ci.ppEnabledExtensionNames = &ext;
  }
  const VkResult r = vkCreateInstance(&ci, nullptr, &g.instance);
  if (r == VK_ERROR_LAYER_NOT_PRESENT) {
    std::fprintf(stderr, "gbuffer_zoo: GBLENS_VALIDATE is set but VK_LAYER_KHRONOS_validation is missing\n");
    std::exit(1);
  }
  ZOO_VK(r);
  if (validate) {
    auto fn = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(g.instance, "vkCreateDebugUtilsMessengerEXT"));
    ZOO_VK(fn(g.instance, &m, nullptr, &g.messenger));
  }
}

uint32_t find_memory(const Gpu& g, uint32_t bits, VkMemoryPropertyFlags flags) {
  for (uint32_t i = 0; i < g.memory.memoryTypeCount; ++i)
    if ((bits >> i & 1u) && (g.memory.memoryTypes[i].propertyFlags & flags) == flags) return i;
  std::fprintf(stderr, "gbuffer_zoo: no memory type with properties 0x%x\n", unsigned(flags));
  std::exit(1);
}

VkDeviceMemory allocate(const Gpu& g, VkMemoryRequirements req, VkMemoryPropertyFlags flags) {
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = find_memory(g, req.memoryTypeBits, flags);
  VkDeviceMemory mem;
  ZOO_VK(vkAllocateMemory(g.device, &ai, nullptr, &mem));
  return mem;
}

VkImageView make_view(const Gpu& g, VkImage image, VkFormat f, VkImageAspectFlags aspect) {
  VkImageViewCreateInfo vi{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
  vi.image = image;
  vi.viewType = VK_IMAGE_VIEW_TYPE_2D;
  vi.format = f;
  vi.subresourceRange = {aspect, 0, 1, 0, 1};
  VkImageView view;
  ZOO_VK(vkCreateImageView(g.device, &vi, nullptr, &view));
  return view;
}

}  // namespace

int validation_count() { return g_validation; }

Gpu open_gpu() {
  Gpu g;
  create_instance(g, want_validation());
  uint32_t count = 0;
  ZOO_VK(vkEnumeratePhysicalDevices(g.instance, &count, nullptr));
  if (count == 0) {
    std::fprintf(stderr, "gbuffer_zoo: no Vulkan physical device\n");
    std::exit(1);
  }
  std::vector<VkPhysicalDevice> all(count);
  ZOO_VK(vkEnumeratePhysicalDevices(g.instance, &count, all.data()));
  g.physical = all[0];
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(g.physical, &props);
  std::memcpy(g.name, props.deviceName, sizeof g.name);
  vkGetPhysicalDeviceMemoryProperties(g.physical, &g.memory);
  uint32_t nf = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(g.physical, &nf, nullptr);
  std::vector<VkQueueFamilyProperties> fams(nf);
  vkGetPhysicalDeviceQueueFamilyProperties(g.physical, &nf, fams.data());
  g.family = nf;
  for (uint32_t i = nf; i-- > 0;)
    if (fams[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) g.family = i;
  if (g.family == nf) {
    std::fprintf(stderr, "gbuffer_zoo: %s has no graphics queue\n", g.name);
    std::exit(1);
  }
  const float prio = 1.0f;
  VkDeviceQueueCreateInfo qi{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  qi.queueFamilyIndex = g.family;
  qi.queueCount = 1;
  qi.pQueuePriorities = &prio;
  VkPhysicalDeviceFeatures have{}, want{};
  vkGetPhysicalDeviceFeatures(g.physical, &have);
  if (!have.independentBlend) {
    std::fprintf(stderr, "gbuffer_zoo: %s lacks independentBlend (the decal's per-target write masks)\n", g.name);
    std::exit(1);
  }
  want.independentBlend = VK_TRUE;
  VkDeviceCreateInfo di{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  di.pEnabledFeatures = &want;
  di.queueCreateInfoCount = 1;
  di.pQueueCreateInfos = &qi;
  ZOO_VK(vkCreateDevice(g.physical, &di, nullptr, &g.device));
  vkGetDeviceQueue(g.device, g.family, 0, &g.queue);
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.queueFamilyIndex = g.family;
  ZOO_VK(vkCreateCommandPool(g.device, &pi, nullptr, &g.pool));
  return g;
}

void close_gpu(Gpu& g) {
  vkDestroyCommandPool(g.device, g.pool, nullptr);
  vkDestroyDevice(g.device, nullptr);
  if (g.messenger) {
    auto fn = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(g.instance, "vkDestroyDebugUtilsMessengerEXT"));
    fn(g.instance, g.messenger, nullptr);
  }
  vkDestroyInstance(g.instance, nullptr);
  g = Gpu{};
}

bool is_depth(VkFormat f) {
  return f == VK_FORMAT_D16_UNORM || f == VK_FORMAT_D32_SFLOAT || f == VK_FORMAT_D24_UNORM_S8_UINT ||
         f == VK_FORMAT_D32_SFLOAT_S8_UINT;
}

bool has_stencil(VkFormat f) { return f == VK_FORMAT_D24_UNORM_S8_UINT || f == VK_FORMAT_D32_SFLOAT_S8_UINT; }

VkImageAspectFlags all_aspects(VkFormat f) {
  if (!is_depth(f)) return VK_IMAGE_ASPECT_COLOR_BIT;
  return VK_IMAGE_ASPECT_DEPTH_BIT | (has_stencil(f) ? VK_IMAGE_ASPECT_STENCIL_BIT : 0);
}

Image make_image(const Gpu& g, VkFormat format, uint32_t w, uint32_t h, VkImageUsageFlags usage) {
  Image img;
  img.format = format;
  VkImageCreateInfo ci{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ci.imageType = VK_IMAGE_TYPE_2D;
  ci.format = format;
  ci.extent = {w, h, 1};
  ci.mipLevels = 1;
  ci.arrayLayers = 1;
  ci.samples = VK_SAMPLE_COUNT_1_BIT;
  ci.tiling = VK_IMAGE_TILING_OPTIMAL;
  ci.usage = usage;
  ci.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
  ZOO_VK(vkCreateImage(g.device, &ci, nullptr, &img.image));
  VkMemoryRequirements req;
  vkGetImageMemoryRequirements(g.device, img.image, &req);
  img.memory = allocate(g, req, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT);
  ZOO_VK(vkBindImageMemory(g.device, img.image, img.memory, 0));
  img.view = make_view(g, img.image, format, all_aspects(format));
  img.sample_view = has_stencil(format) ? make_view(g, img.image, format, VK_IMAGE_ASPECT_DEPTH_BIT) : img.view;
  return img;
}

void free_image(const Gpu& g, Image& i) {
  if (i.sample_view != i.view) vkDestroyImageView(g.device, i.sample_view, nullptr);
  vkDestroyImageView(g.device, i.view, nullptr);
  vkDestroyImage(g.device, i.image, nullptr);
  vkFreeMemory(g.device, i.memory, nullptr);
  i = Image{};
}

Buffer make_buffer(const Gpu& g, VkDeviceSize size, VkBufferUsageFlags usage) {
  Buffer b;
  b.size = size;
  VkBufferCreateInfo ci{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  ci.size = size;
  ci.usage = usage;
  ZOO_VK(vkCreateBuffer(g.device, &ci, nullptr, &b.buffer));
  VkMemoryRequirements req;
  vkGetBufferMemoryRequirements(g.device, b.buffer, &req);
  b.memory = allocate(g, req, VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT);
  ZOO_VK(vkBindBufferMemory(g.device, b.buffer, b.memory, 0));
  ZOO_VK(vkMapMemory(g.device, b.memory, 0, VK_WHOLE_SIZE, 0, &b.mapped));
  std::memset(b.mapped, 0, size_t(size));
  return b;
}

void free_buffer(const Gpu& g, Buffer& b) {
  vkUnmapMemory(g.device, b.memory);
  vkDestroyBuffer(g.device, b.buffer, nullptr);
  vkFreeMemory(g.device, b.memory, nullptr);
  b = Buffer{};
}

VkShaderModule make_shader(const Gpu& g, const uint32_t* words, size_t bytes) {
  VkShaderModuleCreateInfo ci{VK_STRUCTURE_TYPE_SHADER_MODULE_CREATE_INFO};
  ci.codeSize = bytes;
  ci.pCode = words;
  VkShaderModule m;
  ZOO_VK(vkCreateShaderModule(g.device, &ci, nullptr, &m));
  return m;
}

VkCommandBuffer start_commands(const Gpu& g) {
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.commandPool = g.pool;
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkCommandBuffer cmd;
  ZOO_VK(vkAllocateCommandBuffers(g.device, &ai, &cmd));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  ZOO_VK(vkBeginCommandBuffer(cmd, &bi));
  return cmd;
}

void finish_commands(const Gpu& g, VkCommandBuffer cmd) {
  ZOO_VK(vkEndCommandBuffer(cmd));
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence;
  ZOO_VK(vkCreateFence(g.device, &fi, nullptr, &fence));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  ZOO_VK(vkQueueSubmit(g.queue, 1, &si, fence));
  ZOO_VK(vkWaitForFences(g.device, 1, &fence, VK_TRUE, UINT64_MAX));
  vkDestroyFence(g.device, fence, nullptr);
  vkFreeCommandBuffers(g.device, g.pool, 1, &cmd);
}

}  // namespace zoo
