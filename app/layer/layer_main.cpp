// The layer's entry points: loader negotiation, vkGetInstanceProcAddr/vkGetDeviceProcAddr, and the
// instance and device chains (each keeps the next layer's functions). A device whose process has no
// receiver listening is passed straight through: vkGetDeviceProcAddr hands out the next layer's
// functions, so an idle layer costs nothing per call.
#include <cstdarg>
#include <cstdio>
#include <cstdlib>
#include <cstring>

#include <algorithm>
#include <chrono>

#include "app/layer/layer.h"
#include "views/live/live_wire.h"

#define GBL_EXPORT extern "C" __attribute__((visibility("default")))

namespace gbl {

namespace {

struct Globals {
  std::shared_mutex lock;
  std::unordered_map<void*, InstanceData*> instances;  // by dispatch key
  std::unordered_map<void*, DeviceData*> devices;
  bool claimed = false;  // the first device of the process streams; later ones pass through
};
// Never destroyed: the application may exit with the layer's thread still running.
Globals& globals() {
  static Globals* g = new Globals;
  return *g;
}
void* dispatchKey(const void* handle) { return *static_cast<void* const*>(handle); }

template <class T>
const T* findChain(const void* next, VkStructureType type, VkLayerFunction function) {
  for (auto* s = static_cast<const VkBaseInStructure*>(next); s; s = s->pNext)
    if (s->sType == type && reinterpret_cast<const T*>(s)->function == function) return reinterpret_cast<const T*>(s);
  return nullptr;
}

const std::unordered_map<std::string, PFN_vkVoidFunction>& hookTable() {
  static auto* table = [] {
    auto* t = new std::unordered_map<std::string, PFN_vkVoidFunction>;
    for (auto hooks : {trackHooks(), recordHooks(), descriptorHooks(), bindHooks(), submitHooks(), queueHooks()})
      for (const Hook& h : hooks) (*t)[h.name] = h.function;
    return t;
  }();
  return *table;
}

VKAPI_ATTR VkResult VKAPI_CALL CreateInstance(const VkInstanceCreateInfo* info, const VkAllocationCallbacks* alloc,
                                              VkInstance* instance) {
  auto* chain = const_cast<VkLayerInstanceCreateInfo*>(findChain<VkLayerInstanceCreateInfo>(
      info->pNext, VK_STRUCTURE_TYPE_LOADER_INSTANCE_CREATE_INFO, VK_LAYER_LINK_INFO));
  if (!chain || !chain->u.pLayerInfo) return VK_ERROR_INITIALIZATION_FAILED;
  PFN_vkGetInstanceProcAddr gipa = chain->u.pLayerInfo->pfnNextGetInstanceProcAddr;
  chain->u.pLayerInfo = chain->u.pLayerInfo->pNext;
  auto create = reinterpret_cast<PFN_vkCreateInstance>(gipa(VK_NULL_HANDLE, "vkCreateInstance"));
  // A Vulkan 1.0 application under gblens attach: the instance extensions VK_EXT_external_memory_host
  // needs (so that its ring is memory gblens reads in place, as a 1.1 application's is), where the
  // implementation has them; without them the instance is made as the application asked.
  const uint32_t api = info->pApplicationInfo && info->pApplicationInfo->apiVersion ? info->pApplicationInfo->apiVersion
                                                                                      : VK_API_VERSION_1_0;
  std::vector<const char*> extensions(info->ppEnabledExtensionNames, info->ppEnabledExtensionNames + info->enabledExtensionCount);
  auto has = [&](const char* name) {
    return std::any_of(extensions.begin(), extensions.end(), [&](const char* e) { return !std::strcmp(e, name); });
  };
  const size_t asked = extensions.size();
  if (api < VK_API_VERSION_1_1 && std::getenv(gb::wire::kSocketEnv))
    for (const char* e : {VK_KHR_GET_PHYSICAL_DEVICE_PROPERTIES_2_EXTENSION_NAME, VK_KHR_EXTERNAL_MEMORY_CAPABILITIES_EXTENSION_NAME})
      if (!has(e)) extensions.push_back(e);
  VkInstanceCreateInfo patched = *info;
  patched.enabledExtensionCount = uint32_t(extensions.size());
  patched.ppEnabledExtensionNames = extensions.data();
  VkResult r = create(&patched, alloc, instance);
  if (r == VK_ERROR_EXTENSION_NOT_PRESENT && extensions.size() > asked) {
    extensions.resize(asked);
    patched.enabledExtensionCount = uint32_t(asked);
    r = create(&patched, alloc, instance);
  }
  if (r != VK_SUCCESS) return r;
  auto* d = new InstanceData;
  d->instance = *instance;
  d->gipa = gipa;
  d->externalMemory = api >= VK_API_VERSION_1_1 || (has(VK_KHR_GET_PHYSICAL_DEVICE_PROPERTIES_2_EXTENSION_NAME) &&
                                                     has(VK_KHR_EXTERNAL_MEMORY_CAPABILITIES_EXTENSION_NAME));
  d->addedExtensions = extensions.size() > asked;
#define GBL_LOAD(member, name) d->member = reinterpret_cast<decltype(d->member)>(gipa(*instance, name))
  GBL_LOAD(destroyInstance, "vkDestroyInstance");
  GBL_LOAD(createDevice, "vkCreateDevice");
  GBL_LOAD(memoryProperties, "vkGetPhysicalDeviceMemoryProperties");
  GBL_LOAD(properties, "vkGetPhysicalDeviceProperties");
  GBL_LOAD(formatProperties, "vkGetPhysicalDeviceFormatProperties");
  GBL_LOAD(imageFormatProperties, "vkGetPhysicalDeviceImageFormatProperties");
  GBL_LOAD(surfaceCapabilities, "vkGetPhysicalDeviceSurfaceCapabilitiesKHR");
  GBL_LOAD(deviceExtensions, "vkEnumerateDeviceExtensionProperties");
  GBL_LOAD(properties2, "vkGetPhysicalDeviceProperties2");
  GBL_LOAD(queueFamilies, "vkGetPhysicalDeviceQueueFamilyProperties");
  if (api < VK_API_VERSION_1_1) GBL_LOAD(properties2, "vkGetPhysicalDeviceProperties2KHR");  // the extension's
#undef GBL_LOAD
  if (const VkApplicationInfo* a = info->pApplicationInfo) {
    d->application = a->pApplicationName ? a->pApplicationName : "";
    d->engine = a->pEngineName ? a->pEngineName : "";
    d->apiVersion = a->apiVersion ? a->apiVersion : VK_API_VERSION_1_0;
  }
  std::unique_lock lock(globals().lock);
  globals().instances[dispatchKey(*instance)] = d;
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroyInstance(VkInstance instance, const VkAllocationCallbacks* alloc) {
  InstanceData* d = instanceOf(instance);
  if (!d) return;
  d->destroyInstance(instance, alloc);
  std::unique_lock lock(globals().lock);
  globals().instances.erase(dispatchKey(instance));
  delete d;
}

// The host-pointer import alignment when the ring is to be shared memory, else 0: on a device whose
// memory is the host's (lavapipe, integrated GPUs) with VK_EXT_external_memory_host. A discrete GPU
// copies into imported host pages more slowly than into its driver's own host memory (H100: the
// copies of four 1080p targets 2.1 ms a frame against 1.4, docs/attach.md), and the application's
// frame time comes first: there the layer's thread copies finished frames out instead. An
// application of Vulkan 1.0 gets the instance extensions from CreateInstance and VK_KHR_external_memory
// from CreateDevice; where the implementation lacks them its frames are copied out too.
// `anyDevice`: the staged ring's host buffers (staging.cpp), which the layer's own queue writes, are
// imported host pages on a discrete GPU too.
VkDeviceSize hostImportAlignment(InstanceData& inst, VkPhysicalDevice physical, bool anyDevice = false) {
  VkPhysicalDeviceProperties props{};
  inst.properties(physical, &props);
  if (!anyDevice && props.deviceType != VK_PHYSICAL_DEVICE_TYPE_CPU && props.deviceType != VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU)
    return 0;
  uint32_t n = 0;
  if (!inst.externalMemory || !inst.deviceExtensions || !inst.properties2 ||
      inst.deviceExtensions(physical, nullptr, &n, nullptr) != VK_SUCCESS)
    return 0;
  std::vector<VkExtensionProperties> all(n);
  inst.deviceExtensions(physical, nullptr, &n, all.data());
  for (const char* needed : {VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME, VK_KHR_EXTERNAL_MEMORY_EXTENSION_NAME})
    if (std::none_of(all.begin(), all.end(), [&](const VkExtensionProperties& e) { return !std::strcmp(e.extensionName, needed); }))
      return 0;
  VkPhysicalDeviceExternalMemoryHostPropertiesEXT host{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_EXTERNAL_MEMORY_HOST_PROPERTIES_EXT};
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2, &host};
  inst.properties2(physical, &props2);
  return host.minImportedHostPointerAlignment;
}

VKAPI_ATTR VkResult VKAPI_CALL CreateDevice(VkPhysicalDevice physical, const VkDeviceCreateInfo* info,
                                            const VkAllocationCallbacks* alloc, VkDevice* device) {
  auto* chain = const_cast<VkLayerDeviceCreateInfo*>(findChain<VkLayerDeviceCreateInfo>(
      info->pNext, VK_STRUCTURE_TYPE_LOADER_DEVICE_CREATE_INFO, VK_LAYER_LINK_INFO));
  auto* loaderData = findChain<VkLayerDeviceCreateInfo>(info->pNext, VK_STRUCTURE_TYPE_LOADER_DEVICE_CREATE_INFO,
                                                        VK_LOADER_DATA_CALLBACK);
  InstanceData* inst = instanceOf(physical);
  if (!chain || !chain->u.pLayerInfo || !inst) return VK_ERROR_INITIALIZATION_FAILED;
  PFN_vkGetInstanceProcAddr gipa = chain->u.pLayerInfo->pfnNextGetInstanceProcAddr;
  PFN_vkGetDeviceProcAddr gdpa = chain->u.pLayerInfo->pfnNextGetDeviceProcAddr;
  chain->u.pLayerInfo = chain->u.pLayerInfo->pNext;
  // A receiver listening: the connection (and its request) first, so that the device can be made
  // with VK_EXT_external_memory_host, which lets the ring be memory the receiver reads in place.
  bool first = false;
  {
    std::unique_lock lock(globals().lock);
    first = !globals().claimed;
    globals().claimed = true;
  }
  Stream* stream = first ? openStream(*inst, physical) : nullptr;
  VkDeviceCreateInfo patched = *info;
  std::vector<const char*> extensions(info->ppEnabledExtensionNames, info->ppEnabledExtensionNames + info->enabledExtensionCount);
  // A discrete GPU's ring is staged in device memory, with a queue of the layer's for its downloads
  // into host buffers that are shared pages where the device can import them.
  QueuePlan staging;
  const bool staged = stream && planStaging(*inst, physical, patched, staging);
  VkDeviceSize hostAlignment = 0, stagedAlignment = 0;
  if (staged) {
    patched.queueCreateInfoCount = uint32_t(staging.infos.size());
    patched.pQueueCreateInfos = staging.infos.data();
    const char* shared = std::getenv("GBLENS_LAYER_STAGED_SHARED");  // "0": the host buffers copied out
    if (!shared || std::strcmp(shared, "0"))
      stagedAlignment = hostImportAlignment(*inst, physical, true);
  } else if (stream) {
    hostAlignment = hostImportAlignment(*inst, physical);
  }
  if (hostAlignment || stagedAlignment) {
    // VK_KHR_external_memory is core from 1.1; a 1.0 application's device enables it by name.
    for (const char* needed : {VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME, VK_KHR_EXTERNAL_MEMORY_EXTENSION_NAME})
      if ((needed == std::string(VK_EXT_EXTERNAL_MEMORY_HOST_EXTENSION_NAME) || inst->apiVersion < VK_API_VERSION_1_1) &&
          std::none_of(extensions.begin(), extensions.end(), [&](const char* e) { return !std::strcmp(e, needed); }))
        extensions.push_back(needed);
    patched.enabledExtensionCount = uint32_t(extensions.size());
    patched.ppEnabledExtensionNames = extensions.data();
  }
  auto create = reinterpret_cast<PFN_vkCreateDevice>(gipa(inst->instance, "vkCreateDevice"));
  VkResult r = create(physical, &patched, alloc, device);
  if (r != VK_SUCCESS && staging.ownQueue) {  // the device refused one more queue: downloads in the layer's batch
    staging.ownQueue = false;
    patched.queueCreateInfoCount = info->queueCreateInfoCount;
    patched.pQueueCreateInfos = info->pQueueCreateInfos;
    r = create(physical, &patched, alloc, device);
  }
  if (r != VK_SUCCESS) {
    if (stream) closeStream(stream);
    return r;
  }
  auto* d = new DeviceData;
  d->device = *device;
  d->physical = physical;
  d->instance = inst;
  d->setLoaderData = loaderData ? loaderData->u.pfnSetDeviceLoaderData : nullptr;
#define GBL_LOAD(name) d->vk.name = reinterpret_cast<PFN_vk##name>(gdpa(*device, "vk" #name));
  GBL_DEVICE_FUNCTIONS(GBL_LOAD)
#undef GBL_LOAD
  // As the loader does: VK_EXT_debug_utils's device functions come from the instance's chain.
#define GBL_LOAD(name) \
  if (!d->vk.name) d->vk.name = reinterpret_cast<PFN_vk##name>(gipa(inst->instance, "vk" #name));
  GBL_LOAD(SetDebugUtilsObjectNameEXT) GBL_LOAD(CmdBeginDebugUtilsLabelEXT) GBL_LOAD(CmdEndDebugUtilsLabelEXT)
#undef GBL_LOAD
  inst->memoryProperties(physical, &d->memory);
  d->hostImport = hostAlignment != 0 && d->vk.GetMemoryHostPointerPropertiesEXT;
  d->stagedShared = stagedAlignment != 0 && d->vk.GetMemoryHostPointerPropertiesEXT;
  d->hostAlignment = std::max<VkDeviceSize>(std::max(hostAlignment, stagedAlignment), 1);
  for (uint32_t q = 0; q < info->queueCreateInfoCount; ++q) d->createdFamilies.push_back(info->pQueueCreateInfos[q].queueFamilyIndex);
  {
    std::unique_lock lock(globals().lock);
    globals().devices[dispatchKey(*device)] = d;
  }
  d->connected = stream != nullptr;
  startStaging(*d, staging);
  if (stream) startStream(*d, stream);
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroyDevice(VkDevice device, const VkAllocationCallbacks* alloc) {
  DeviceData* d = deviceOf(device);
  if (!d) return;
  if (d->connected) {
    GBL_LOG("device destroyed: following %zu images, %zu views, %zu framebuffers, %zu render passes, %zu buffers, %zu "
            "descriptor sets, %zu command buffers, %zu mapped memories",
            d->images.size(), d->views.size(), d->framebuffers.size(), d->renderPasses.size(), d->buffers.size(),
            d->sets.size(), d->cmds.size(), d->mapped.size());
    stopStream(*d);
    d->vk.DeviceWaitIdle(device);
    {
      std::lock_guard lock(d->cmdLock);
      d->cmds.clear();  // releases the recordings' ring buffers
    }
    destroyRing(*d);
    destroyCopyTiming(*d);
    destroySamples(*d);
    destroyStaging(*d);
  }
  PFN_vkDestroyDevice destroy = d->vk.DestroyDevice;
  {
    std::unique_lock lock(globals().lock);
    globals().devices.erase(dispatchKey(device));
  }
  destroy(device, alloc);
  delete d;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL GetDeviceProcAddr(VkDevice device, const char* name);

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL GetInstanceProcAddr(VkInstance instance, const char* name) {
  if (!std::strcmp(name, "vkGetInstanceProcAddr")) return reinterpret_cast<PFN_vkVoidFunction>(GetInstanceProcAddr);
  if (!std::strcmp(name, "vkCreateInstance")) return reinterpret_cast<PFN_vkVoidFunction>(CreateInstance);
  if (!std::strcmp(name, "vkDestroyInstance")) return reinterpret_cast<PFN_vkVoidFunction>(DestroyInstance);
  if (!std::strcmp(name, "vkCreateDevice")) return reinterpret_cast<PFN_vkVoidFunction>(CreateDevice);
  if (!std::strcmp(name, "vkGetDeviceProcAddr")) return reinterpret_cast<PFN_vkVoidFunction>(GetDeviceProcAddr);
  if (!instance) return nullptr;
  // The loader fills a device's VK_EXT_debug_utils entries through vkGetInstanceProcAddr: the
  // layer's names and labels come from there (their hooks pass idle devices straight through).
  if (!std::strcmp(name, "vkSetDebugUtilsObjectNameEXT") || !std::strcmp(name, "vkCmdBeginDebugUtilsLabelEXT") ||
      !std::strcmp(name, "vkCmdEndDebugUtilsLabelEXT")) {
    auto it = hookTable().find(name);
    if (it != hookTable().end()) return it->second;
  }
  InstanceData* d = instanceOf(instance);
  return d ? d->gipa(instance, name) : nullptr;
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL GetDeviceProcAddr(VkDevice device, const char* name) {
  if (!std::strcmp(name, "vkGetDeviceProcAddr")) return reinterpret_cast<PFN_vkVoidFunction>(GetDeviceProcAddr);
  if (!std::strcmp(name, "vkDestroyDevice")) return reinterpret_cast<PFN_vkVoidFunction>(DestroyDevice);
  DeviceData* d = deviceOf(device);
  if (!d) return nullptr;
  PFN_vkVoidFunction next = d->vk.GetDeviceProcAddr(device, name);
  if (!d->connected || !next) return next;  // idle, or a function the device does not have
  auto it = hookTable().find(name);
  if (it != hookTable().end()) return it->second;
  // What only some requests need (the request came before the device was made).
  if (std::shared_ptr<const Request> req = currentRequest(*d))
    for (const Hook& h : structureHooks(*req))
      if (!std::strcmp(h.name, name)) return h.function;
  return next;
}

}  // namespace

DeviceData* deviceOf(const void* dispatchable) {
  std::shared_lock lock(globals().lock);
  auto it = globals().devices.find(dispatchKey(dispatchable));
  return it == globals().devices.end() ? nullptr : it->second;
}

InstanceData* instanceOf(const void* dispatchable) {
  std::shared_lock lock(globals().lock);
  auto it = globals().instances.find(dispatchKey(dispatchable));
  return it == globals().instances.end() ? nullptr : it->second;
}

bool logging() {
  static const bool on = [] {
    const char* v = std::getenv("GBLENS_LAYER_LOG");
    return v && *v && std::strcmp(v, "0") != 0;
  }();
  return on;
}

void logLine(const char* format, ...) {
  char line[512];
  va_list args;
  va_start(args, format);
  std::vsnprintf(line, sizeof(line), format, args);
  va_end(args);
  static const auto start = std::chrono::steady_clock::now();  // lines say when, from the first
  std::fprintf(stderr, "gblens layer: %9.3f ms %s\n",
               std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count(), line);
}

std::shared_ptr<const Request> currentRequest(DeviceData& d) {
  std::lock_guard lock(d.requestLock);
  return d.request;
}

}  // namespace gbl

GBL_EXPORT VKAPI_ATTR VkResult VKAPI_CALL vkNegotiateLoaderLayerInterfaceVersion(VkNegotiateLayerInterface* v) {
  if (!v || v->sType != LAYER_NEGOTIATE_INTERFACE_STRUCT) return VK_ERROR_INITIALIZATION_FAILED;
  if (v->loaderLayerInterfaceVersion > 2) v->loaderLayerInterfaceVersion = 2;
  v->pfnGetInstanceProcAddr = gbl::GetInstanceProcAddr;
  v->pfnGetDeviceProcAddr = gbl::GetDeviceProcAddr;
  v->pfnGetPhysicalDeviceProcAddr = nullptr;
  return VK_SUCCESS;
}

GBL_EXPORT VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetInstanceProcAddr(VkInstance instance, const char* name) {
  return gbl::GetInstanceProcAddr(instance, name);
}

GBL_EXPORT VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL vkGetDeviceProcAddr(VkDevice device, const char* name) {
  return gbl::GetDeviceProcAddr(device, name);
}
