// Instance/device creation, device choice (--device), and the validation messenger.
#include "renderer/vk/context.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>

#include "renderer/vk/check.h"
#include "renderer/vk/debug_utils.h"

namespace gb {

const char* vkResultName(VkResult r) {
  switch (r) {
#define GB_CASE(x) \
  case x:          \
    return #x;
    GB_CASE(VK_SUCCESS)
    GB_CASE(VK_NOT_READY)
    GB_CASE(VK_TIMEOUT)
    GB_CASE(VK_INCOMPLETE)
    GB_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    GB_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    GB_CASE(VK_ERROR_INITIALIZATION_FAILED)
    GB_CASE(VK_ERROR_DEVICE_LOST)
    GB_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    GB_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    GB_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    GB_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    GB_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    GB_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    GB_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    GB_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    GB_CASE(VK_SUBOPTIMAL_KHR)
    GB_CASE(VK_ERROR_SURFACE_LOST_KHR)
#undef GB_CASE
    default:
      return "VK_ERROR_(unknown)";
  }
}

void vkFail(VkResult r, const char* call, const char* file, int line) {
  std::fprintf(stderr, "gblens: Vulkan call failed with %s (%d): %s (%s:%d)\n", vkResultName(r), r, call,
               file, line);
  std::abort();
}

ValidationLog& validationLog() {
  static ValidationLog log;
  return log;
}

bool validationRequestedByEnvironment() {
  const char* v = std::getenv("GBLENS_VALIDATE");
  return v && *v && std::strcmp(v, "0") != 0;
}

// The one place where validation messages are filtered. Each entry names why it is ignored.
static bool ignoredMessage(const VkDebugUtilsMessengerCallbackDataEXT* data) {
  static const char* const kIgnoredIds[] = {
      // Informational best-practice notes are below the warning level and never reach here;
      // nothing is filtered at warning level or above yet.
      nullptr,
  };
  for (const char* id : kIgnoredIds)
    if (id && data->pMessageIdName && std::strcmp(id, data->pMessageIdName) == 0) return true;
  return false;
}

static VKAPI_ATTR VkBool32 VKAPI_CALL onDebugMessage(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                     VkDebugUtilsMessageTypeFlagsEXT,
                                                     const VkDebugUtilsMessengerCallbackDataEXT* data, void*) {
  if (severity < VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT || ignoredMessage(data)) return VK_FALSE;
  ValidationLog& log = validationLog();
  bool error = severity >= VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  (error ? log.errors : log.warnings)++;
  std::string text = std::string(error ? "validation error: " : "validation warning: ") + data->pMessage;
  if (log.echo) std::fprintf(stderr, "gblens: %s\n", text.c_str());
  std::lock_guard<std::mutex> lock(log.mutex);
  log.messages.push_back(std::move(text));
  return VK_FALSE;
}

static const char* typeName(VkPhysicalDeviceType t) {
  switch (t) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

static std::vector<VkPhysicalDevice> physicalDevices(VkInstance instance) {
  uint32_t n = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, nullptr));
  std::vector<VkPhysicalDevice> devices(n);
  VK_CHECK(vkEnumeratePhysicalDevices(instance, &n, devices.data()));
  return devices;
}

std::vector<std::string> listDevices(VkInstance instance) {
  std::vector<std::string> out;
  auto devices = physicalDevices(instance);
  for (size_t i = 0; i < devices.size(); ++i) {
    VkPhysicalDeviceProperties p;
    vkGetPhysicalDeviceProperties(devices[i], &p);
    out.push_back(std::to_string(i) + ": " + p.deviceName + " (" + typeName(p.deviceType) + ")");
  }
  return out;
}

static bool hasLayer(const char* name) {
  uint32_t n = 0;
  vkEnumerateInstanceLayerProperties(&n, nullptr);
  std::vector<VkLayerProperties> layers(n);
  vkEnumerateInstanceLayerProperties(&n, layers.data());
  for (auto& l : layers)
    if (std::strcmp(l.layerName, name) == 0) return true;
  return false;
}

static bool hasDeviceExtension(VkPhysicalDevice pd, const char* name) {
  uint32_t n = 0;
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateDeviceExtensionProperties(pd, nullptr, &n, exts.data());
  for (auto& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) return true;
  return false;
}

// --device NAME|INDEX, or the first discrete, then integrated GPU, else whatever is first (lavapipe).
static VkPhysicalDevice chooseDevice(VkInstance instance, const std::string& wanted) {
  auto devices = physicalDevices(instance);
  if (devices.empty()) {
    std::fprintf(stderr, "gblens: no Vulkan device found (is mesa-vulkan-drivers installed?)\n");
    std::exit(2);
  }
  if (!wanted.empty()) {
    char* end = nullptr;
    long index = std::strtol(wanted.c_str(), &end, 10);
    if (end && *end == '\0') {
      if (index >= 0 && size_t(index) < devices.size()) return devices[index];
    } else {
      for (auto d : devices) {
        VkPhysicalDeviceProperties p;
        vkGetPhysicalDeviceProperties(d, &p);
        if (std::strstr(p.deviceName, wanted.c_str())) return d;
      }
    }
    std::fprintf(stderr, "gblens: --device %s: no such device; available:\n", wanted.c_str());
    for (auto& line : listDevices(instance)) std::fprintf(stderr, "  %s\n", line.c_str());
    std::exit(2);
  }
  for (auto type : {VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU, VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU}) {
    for (auto d : devices) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(d, &p);
      if (p.deviceType == type) return d;
    }
  }
  return devices[0];
}

// The instance (validation layer and synchronization validation when asked) and the messenger
// that counts validation messages.
static void createInstance(GpuContext& ctx, const ContextOptions& options) {
  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = "gblens";
  app.apiVersion = VK_API_VERSION_1_3;

  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  for (auto& e : options.instanceExtensions) extensions.push_back(e.c_str());
  if (ctx.validation) {
    if (!hasLayer("VK_LAYER_KHRONOS_validation")) {
      std::fprintf(stderr, "gblens: validation requested but VK_LAYER_KHRONOS_validation is not installed "
                           "(apt-get install vulkan-validationlayers)\n");
      std::exit(2);
    }
    layers.push_back("VK_LAYER_KHRONOS_validation");
  }
  // Debug utils whenever the loader offers it (it is cheap): the validation messenger, and the object
  // names and pass labels RenderDoc and Nsight show.
  const bool debugUtils = debugUtilsAvailable();
  if (debugUtils) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  VkDebugUtilsMessengerCreateInfoEXT messengerInfo{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messengerInfo.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messengerInfo.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT |
                              VK_DEBUG_UTILS_MESSAGE_TYPE_GENERAL_BIT_EXT;
  messengerInfo.pfnUserCallback = onDebugMessage;

  // Synchronization validation checks the barriers the frame graph derives from declared usage.
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;
  features.pNext = &messengerInfo;

  VkInstanceCreateInfo ici{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  ici.pApplicationInfo = &app;
  ici.enabledLayerCount = uint32_t(layers.size());
  ici.ppEnabledLayerNames = layers.data();
  ici.enabledExtensionCount = uint32_t(extensions.size());
  ici.ppEnabledExtensionNames = extensions.data();
  if (!debugUtils) features.pNext = nullptr;
  ici.pNext = ctx.validation ? static_cast<void*>(&features) : debugUtils ? static_cast<void*>(&messengerInfo) : nullptr;
  VK_CHECK(vkCreateInstance(&ici, nullptr, &ctx.instance));

  auto createMessenger = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(ctx.instance, "vkCreateDebugUtilsMessengerEXT"));
  if (createMessenger) VK_CHECK(createMessenger(ctx.instance, &messengerInfo, nullptr, &ctx.messenger));
}

// The chosen device's properties, driver, queue family (graphics + compute) and the features
// gblens can use on it (ctx.features).
static void describeDevice(GpuContext& ctx) {
  vkGetPhysicalDeviceProperties(ctx.physical, &ctx.properties);
  vkGetPhysicalDeviceMemoryProperties(ctx.physical, &ctx.memory);
  ctx.deviceName = ctx.properties.deviceName;
  ctx.isCpu = ctx.properties.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU;

  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &driver;
  vkGetPhysicalDeviceProperties2(ctx.physical, &props2);
  ctx.driverName = std::string(driver.driverName) + ": " + driver.driverInfo;

  uint32_t qn = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical, &qn, nullptr);
  std::vector<VkQueueFamilyProperties> families(qn);
  vkGetPhysicalDeviceQueueFamilyProperties(ctx.physical, &qn, families.data());
  ctx.queueFamily = UINT32_MAX;
  for (uint32_t i = 0; i < qn; ++i) {
    if ((families[i].queueFlags & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ==
        (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) {
      ctx.queueFamily = i;
      break;
    }
  }
  GB_ASSERT(ctx.queueFamily != UINT32_MAX);
  // Async compute: a family with compute but no graphics (NVIDIA's queues of one family are
  // time-sliced, not concurrent: docs/perf-gpu.md). GBLENS_OVERLAP=off leaves it out, so an A/B
  // run measures the shared images too.
  const char* overlap = std::getenv("GBLENS_OVERLAP");
  ctx.computeFamily = ctx.queueFamily;
  if (!(overlap && std::strcmp(overlap, "off") == 0))
    for (uint32_t i = 0; i < qn; ++i)
      if ((families[i].queueFlags & VK_QUEUE_COMPUTE_BIT) && !(families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) &&
          families[i].queueCount > 0 && families[i].timestampValidBits > 0) {
        ctx.computeFamily = i;
        break;
      }
  if (ctx.computeFamily != ctx.queueFamily) ctx.sharedFamilies = {ctx.queueFamily, ctx.computeFamily};
  ctx.features.timestamps = families[ctx.queueFamily].timestampValidBits > 0;

  VkPhysicalDeviceFeatures supported{};
  vkGetPhysicalDeviceFeatures(ctx.physical, &supported);
  ctx.features.pipelineStatistics = supported.pipelineStatisticsQuery;
  ctx.features.depthClamp = supported.depthClamp;
  ctx.features.fragmentStoresAndAtomics = supported.fragmentStoresAndAtomics;
  ctx.features.primitiveId = supported.geometryShader;
  ctx.features.float64 = supported.shaderFloat64;
  for (uint32_t i = 0; i < ctx.memory.memoryTypeCount; ++i)
    if (ctx.memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT)
      ctx.features.lazilyAllocatedMemory = true;
}

// What the device supports of the features and extensions gblens enables.
namespace {
struct DeviceSupport {
  VkPhysicalDeviceFeatures core{};
  VkBool32 maintenance4 = VK_FALSE, scalarBlockLayout = VK_FALSE;
  std::vector<const char*> extensions;  // to enable
};
}  // namespace

// Reads the device's Vulkan 1.2/1.3 features and the optional rasterization-order extension;
// exits with a message when VK_KHR_push_descriptor, which gblens needs, is missing.
static DeviceSupport querySupport(GpuContext& ctx, const ContextOptions& options) {
  DeviceSupport s;
  vkGetPhysicalDeviceFeatures(ctx.physical, &s.core);
  s.extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  if (options.swapchain) s.extensions.push_back(VK_KHR_SWAPCHAIN_EXTENSION_NAME);

  VkPhysicalDeviceRasterizationOrderAttachmentAccessFeaturesEXT rasterOrder{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_FEATURES_EXT};
  VkPhysicalDeviceVulkan13Features v13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features v12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceFeatures2 f2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  v13.pNext = &v12;
  f2.pNext = &v13;
  vkGetPhysicalDeviceFeatures2(ctx.physical, &f2);
  if (hasDeviceExtension(ctx.physical, VK_EXT_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_EXTENSION_NAME)) {
    v12.pNext = &rasterOrder;
    vkGetPhysicalDeviceFeatures2(ctx.physical, &f2);
    ctx.features.rasterOrderAttachmentAccess = rasterOrder.rasterizationOrderColorAttachmentAccess;
    if (ctx.features.rasterOrderAttachmentAccess)
      s.extensions.push_back(VK_EXT_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_EXTENSION_NAME);
  }
  if (!hasDeviceExtension(ctx.physical, VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME)) {
    std::fprintf(stderr, "gblens: device %s lacks VK_KHR_push_descriptor, which gblens needs\n",
                 ctx.deviceName.c_str());
    std::exit(2);
  }
  s.maintenance4 = v13.maintenance4;
  s.scalarBlockLayout = v12.scalarBlockLayout;
  ctx.features.timelineSemaphore = v12.timelineSemaphore;
  ctx.features.visibilityResolve = s.core.shaderStorageImageWriteWithoutFormat && s.core.geometryShader;
  return s;
}

// The device with one queue (and one of a compute-only family: GpuContext::computeQueue) and only the features gblens uses (so behaviour matches between
// devices), the push-descriptor entry point and the command pool.
static void createDevice(GpuContext& ctx, const DeviceSupport& s) {
  VkPhysicalDeviceFeatures2 enabled{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  enabled.features.depthClamp = s.core.depthClamp;
  enabled.features.depthBiasClamp = s.core.depthBiasClamp;
  enabled.features.pipelineStatisticsQuery = s.core.pipelineStatisticsQuery;
  enabled.features.fragmentStoresAndAtomics = s.core.fragmentStoresAndAtomics;
  enabled.features.shaderSampledImageArrayDynamicIndexing = s.core.shaderSampledImageArrayDynamicIndexing;
  enabled.features.samplerAnisotropy = s.core.samplerAnisotropy;
  enabled.features.multiDrawIndirect = s.core.multiDrawIndirect;
  enabled.features.shaderStorageImageWriteWithoutFormat = s.core.shaderStorageImageWriteWithoutFormat;
  enabled.features.independentBlend = s.core.independentBlend;
  enabled.features.geometryShader = s.core.geometryShader;  // gl_PrimitiveID in the primitive_id target
  enabled.features.shaderFloat64 = s.core.shaderFloat64;    // light setup on the GPU
  VkPhysicalDeviceVulkan13Features e13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  e13.synchronization2 = VK_TRUE;
  e13.maintenance4 = s.maintenance4;  // relaxed interface matching (unused vertex outputs)
  VkPhysicalDeviceVulkan12Features e12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  e12.separateDepthStencilLayouts = VK_TRUE;
  e12.hostQueryReset = VK_TRUE;
  e12.timelineSemaphore = ctx.features.timelineSemaphore;
  e12.scalarBlockLayout = s.scalarBlockLayout;
  VkPhysicalDeviceRasterizationOrderAttachmentAccessFeaturesEXT eRaster{
      VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_RASTERIZATION_ORDER_ATTACHMENT_ACCESS_FEATURES_EXT};
  eRaster.rasterizationOrderColorAttachmentAccess = ctx.features.rasterOrderAttachmentAccess;
  enabled.pNext = &e13;
  e13.pNext = &e12;
  if (ctx.features.rasterOrderAttachmentAccess) e12.pNext = &eRaster;

  const float priority = 1.0f;
  VkDeviceQueueCreateInfo qci[2] = {{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO}, {VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO}};
  qci[0].queueFamilyIndex = ctx.queueFamily;
  qci[1].queueFamilyIndex = ctx.computeFamily;
  for (VkDeviceQueueCreateInfo& q : qci) {
    q.queueCount = 1;
    q.pQueuePriorities = &priority;
  }
  VkDeviceCreateInfo dci{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  dci.pNext = &enabled;
  dci.queueCreateInfoCount = ctx.computeFamily != ctx.queueFamily ? 2 : 1;
  dci.pQueueCreateInfos = qci;
  dci.enabledExtensionCount = uint32_t(s.extensions.size());
  dci.ppEnabledExtensionNames = s.extensions.data();
  VK_CHECK(vkCreateDevice(ctx.physical, &dci, nullptr, &ctx.device));
  vkGetDeviceQueue(ctx.device, ctx.queueFamily, 0, &ctx.queue);
  vkGetDeviceQueue(ctx.device, ctx.computeFamily, 0, &ctx.computeQueue);
  ctx.cmdPushDescriptorSet = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetDeviceProcAddr(ctx.device, "vkCmdPushDescriptorSetKHR"));
  GB_ASSERT(ctx.cmdPushDescriptorSet);
  if (debugUtilsAvailable()) loadDebugUtils(ctx);  // the instance enabled it (createInstance)
  if (ctx.computeQueue != ctx.queue) {  // as Nsight's timeline names them
    setName(ctx, uint64_t(ctx.queue), VK_OBJECT_TYPE_QUEUE, "graphics");
    setName(ctx, uint64_t(ctx.computeQueue), VK_OBJECT_TYPE_QUEUE, "compute");
  }

  VkCommandPoolCreateInfo pci{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pci.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pci.queueFamilyIndex = ctx.queueFamily;
  VK_CHECK(vkCreateCommandPool(ctx.device, &pci, nullptr, &ctx.commandPool));
  ctx.computePool = ctx.commandPool;
  if (ctx.computeFamily != ctx.queueFamily) {
    pci.queueFamilyIndex = ctx.computeFamily;
    VK_CHECK(vkCreateCommandPool(ctx.device, &pci, nullptr, &ctx.computePool));
  }
}

GpuContext createContext(const ContextOptions& options) {
  GpuContext ctx;
  ctx.validation = options.validation || validationRequestedByEnvironment();
  createInstance(ctx, options);
  ctx.physical = chooseDevice(ctx.instance, options.device);
  describeDevice(ctx);
  createDevice(ctx, querySupport(ctx, options));
  if (!options.quiet) {
    uint32_t v = ctx.properties.apiVersion;
    std::fprintf(stderr, "gblens: device: %s (%s), Vulkan %u.%u.%u, %s%s\n", ctx.deviceName.c_str(),
                 typeName(ctx.properties.deviceType), VK_API_VERSION_MAJOR(v), VK_API_VERSION_MINOR(v),
                 VK_API_VERSION_PATCH(v), ctx.driverName.c_str(), ctx.validation ? ", validation on" : "");
  }
  return ctx;
}

void destroyContext(GpuContext& ctx) {
  if (ctx.device) {
    vkDeviceWaitIdle(ctx.device);
    if (ctx.computePool != ctx.commandPool) vkDestroyCommandPool(ctx.device, ctx.computePool, nullptr);
    vkDestroyCommandPool(ctx.device, ctx.commandPool, nullptr);
    vkDestroyDevice(ctx.device, nullptr);
  }
  if (ctx.messenger) {
    auto destroyMessenger = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(ctx.instance, "vkDestroyDebugUtilsMessengerEXT"));
    if (destroyMessenger) destroyMessenger(ctx.instance, ctx.messenger, nullptr);
  }
  if (ctx.instance) vkDestroyInstance(ctx.instance, nullptr);
  ctx = GpuContext{};
}

int reportValidation(const GpuContext& ctx) {
  if (!ctx.validation) return 0;
  ValidationLog& log = validationLog();
  int n = log.errors + log.warnings;
  if (n) std::fprintf(stderr, "gblens: %d validation message(s) (%d errors)\n", n, int(log.errors));
  return n;
}

}  // namespace gb
