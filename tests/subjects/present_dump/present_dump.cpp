// A test-only Vulkan layer, written apart from gblens's own (app/layer), that writes what an
// application presents: at each present it waits for the queue, copies the presented swapchain
// image to host memory and writes it to GBLENS_TEST_DUMP_FILE.N (N: the present's number, 0 the
// first) as "W H FORMAT\n" followed by the raw texels; GBLENS_TEST_DUMP_FRAME=N writes only that one. The attach tests compare an application's presented
// images with the gblens layer on and off, and with what the gblens layer streamed. Enabled by
// ENABLE_GBLENS_TEST_DUMP=1 (an implicit layer found through XDG_DATA_DIRS).
#include <vulkan/vk_layer.h>
#include <vulkan/vulkan.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <mutex>
#include <string>
#include <unordered_map>
#include <vector>

namespace {

struct Device {
  VkDevice device = VK_NULL_HANDLE;
  PFN_vkGetDeviceProcAddr gdpa = nullptr;
  PFN_vkSetDeviceLoaderData setLoaderData = nullptr;
  VkPhysicalDeviceMemoryProperties memory{};
  uint32_t family = 0;
  std::unordered_map<VkSwapchainKHR, std::vector<VkImage>> images;
  std::unordered_map<VkSwapchainKHR, VkSwapchainCreateInfoKHR> info;
  int presents = 0;
  template <class F>
  F get(const char* name) const {
    return reinterpret_cast<F>(gdpa(device, name));
  }
};

std::mutex lock;
struct Instance {
  VkInstance instance;
  PFN_vkGetInstanceProcAddr gipa;
};
std::unordered_map<void*, Instance>& instances() {
  static auto* m = new std::unordered_map<void*, Instance>;
  return *m;
}
std::unordered_map<void*, Device*>& devices() {
  static auto* m = new std::unordered_map<void*, Device*>;
  return *m;
}
void* key(const void* h) { return *static_cast<void* const*>(h); }
Device* deviceOf(const void* h) {
  std::lock_guard g(lock);
  return devices()[key(h)];
}

VKAPI_ATTR VkResult VKAPI_CALL CreateInstance(const VkInstanceCreateInfo* info, const VkAllocationCallbacks* a, VkInstance* out) {
  auto* chain = const_cast<VkLayerInstanceCreateInfo*>(static_cast<const VkLayerInstanceCreateInfo*>(info->pNext));
  while (chain && !(chain->sType == VK_STRUCTURE_TYPE_LOADER_INSTANCE_CREATE_INFO && chain->function == VK_LAYER_LINK_INFO))
    chain = const_cast<VkLayerInstanceCreateInfo*>(static_cast<const VkLayerInstanceCreateInfo*>(chain->pNext));
  PFN_vkGetInstanceProcAddr gipa = chain->u.pLayerInfo->pfnNextGetInstanceProcAddr;
  chain->u.pLayerInfo = chain->u.pLayerInfo->pNext;
  VkResult r = reinterpret_cast<PFN_vkCreateInstance>(gipa(nullptr, "vkCreateInstance"))(info, a, out);
  if (r == VK_SUCCESS) {
    std::lock_guard g(lock);
    instances()[key(*out)] = {*out, gipa};
  }
  return r;
}

VKAPI_ATTR VkResult VKAPI_CALL CreateDevice(VkPhysicalDevice pd, const VkDeviceCreateInfo* info, const VkAllocationCallbacks* a,
                                            VkDevice* out) {
  VkLayerDeviceCreateInfo* link = nullptr;
  PFN_vkSetDeviceLoaderData setData = nullptr;
  for (auto* c = static_cast<const VkLayerDeviceCreateInfo*>(info->pNext); c; c = static_cast<const VkLayerDeviceCreateInfo*>(c->pNext))
    if (c->sType == VK_STRUCTURE_TYPE_LOADER_DEVICE_CREATE_INFO) {
      if (c->function == VK_LAYER_LINK_INFO) link = const_cast<VkLayerDeviceCreateInfo*>(c);
      if (c->function == VK_LOADER_DATA_CALLBACK) setData = c->u.pfnSetDeviceLoaderData;
    }
  PFN_vkGetInstanceProcAddr gipa = link->u.pLayerInfo->pfnNextGetInstanceProcAddr;
  PFN_vkGetDeviceProcAddr gdpa = link->u.pLayerInfo->pfnNextGetDeviceProcAddr;
  link->u.pLayerInfo = link->u.pLayerInfo->pNext;
  VkResult r = reinterpret_cast<PFN_vkCreateDevice>(gipa(nullptr, "vkCreateDevice"))(pd, info, a, out);
  if (r != VK_SUCCESS) return r;
  auto* d = new Device;
  d->device = *out;
  d->gdpa = gdpa;
  d->setLoaderData = setData;
  d->family = info->pQueueCreateInfos[0].queueFamilyIndex;
  std::lock_guard g(lock);
  const Instance& in = instances()[key(pd)];
  reinterpret_cast<PFN_vkGetPhysicalDeviceMemoryProperties>(in.gipa(in.instance, "vkGetPhysicalDeviceMemoryProperties"))(
      pd, &d->memory);
  devices()[key(*out)] = d;
  return r;
}

VKAPI_ATTR VkResult VKAPI_CALL CreateSwapchainKHR(VkDevice device, const VkSwapchainCreateInfoKHR* info,
                                                  const VkAllocationCallbacks* a, VkSwapchainKHR* out) {
  Device* d = deviceOf(device);
  VkSwapchainCreateInfoKHR patched = *info;
  patched.imageUsage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;  // Xvfb's surfaces (lavapipe) allow it
  VkResult r = d->get<PFN_vkCreateSwapchainKHR>("vkCreateSwapchainKHR")(device, &patched, a, out);
  if (r == VK_SUCCESS) d->info[*out] = *info;
  return r;
}

VKAPI_ATTR VkResult VKAPI_CALL GetSwapchainImagesKHR(VkDevice device, VkSwapchainKHR sc, uint32_t* n, VkImage* images) {
  Device* d = deviceOf(device);
  VkResult r = d->get<PFN_vkGetSwapchainImagesKHR>("vkGetSwapchainImagesKHR")(device, sc, n, images);
  if (images && r == VK_SUCCESS) d->images[sc].assign(images, images + *n);
  return r;
}

// The presented image, read back once the queue is idle (the application's rendering is done and
// its semaphores signalled; present still waits on them after this).
void dump(Device& d, VkQueue queue, VkImage image, const VkSwapchainCreateInfoKHR& sc, const char* file) {
  const VkDeviceSize bytes = VkDeviceSize(sc.imageExtent.width) * sc.imageExtent.height * 4;
  d.get<PFN_vkQueueWaitIdle>("vkQueueWaitIdle")(queue);
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, nullptr, 0, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT};
  VkBuffer buffer;
  d.get<PFN_vkCreateBuffer>("vkCreateBuffer")(d.device, &bi, nullptr, &buffer);
  VkMemoryRequirements req;
  d.get<PFN_vkGetBufferMemoryRequirements>("vkGetBufferMemoryRequirements")(d.device, buffer, &req);
  const VkMemoryPropertyFlags visible = VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
  uint32_t type = 0;
  while (!(req.memoryTypeBits & (1u << type)) || (d.memory.memoryTypes[type].propertyFlags & visible) != visible) ++type;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, nullptr, req.size, type};
  VkDeviceMemory memory;
  d.get<PFN_vkAllocateMemory>("vkAllocateMemory")(d.device, &ai, nullptr, &memory);
  d.get<PFN_vkBindBufferMemory>("vkBindBufferMemory")(d.device, buffer, memory, 0);
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO, nullptr, 0, d.family};
  VkCommandPool pool;
  d.get<PFN_vkCreateCommandPool>("vkCreateCommandPool")(d.device, &pi, nullptr, &pool);
  VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO, nullptr, pool, VK_COMMAND_BUFFER_LEVEL_PRIMARY, 1};
  VkCommandBuffer cmd;
  d.get<PFN_vkAllocateCommandBuffers>("vkAllocateCommandBuffers")(d.device, &cai, &cmd);
  d.setLoaderData(d.device, cmd);
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  d.get<PFN_vkBeginCommandBuffer>("vkBeginCommandBuffer")(cmd, &begin);
  VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
  b.srcAccessMask = 0;
  b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  b.oldLayout = VK_IMAGE_LAYOUT_PRESENT_SRC_KHR;
  b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
  b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  b.image = image;
  b.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  auto barrier = d.get<PFN_vkCmdPipelineBarrier>("vkCmdPipelineBarrier");
  barrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {sc.imageExtent.width, sc.imageExtent.height, 1};
  d.get<PFN_vkCmdCopyImageToBuffer>("vkCmdCopyImageToBuffer")(cmd, image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer, 1, &region);
  std::swap(b.oldLayout, b.newLayout);
  b.srcAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  b.dstAccessMask = 0;
  barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_BOTTOM_OF_PIPE_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
  VkBufferMemoryBarrier host{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER, nullptr, VK_ACCESS_TRANSFER_WRITE_BIT, VK_ACCESS_HOST_READ_BIT,
                             VK_QUEUE_FAMILY_IGNORED, VK_QUEUE_FAMILY_IGNORED, buffer, 0, VK_WHOLE_SIZE};
  barrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &host, 0, nullptr);
  d.get<PFN_vkEndCommandBuffer>("vkEndCommandBuffer")(cmd);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &cmd;
  d.get<PFN_vkQueueSubmit>("vkQueueSubmit")(queue, 1, &si, VK_NULL_HANDLE);
  d.get<PFN_vkQueueWaitIdle>("vkQueueWaitIdle")(queue);
  void* p = nullptr;
  d.get<PFN_vkMapMemory>("vkMapMemory")(d.device, memory, 0, VK_WHOLE_SIZE, 0, &p);
  if (FILE* f = std::fopen(file, "wb")) {
    std::fprintf(f, "%u %u %d\n", sc.imageExtent.width, sc.imageExtent.height, int(sc.imageFormat));
    std::fwrite(p, 1, size_t(bytes), f);
    std::fclose(f);
  }
  d.get<PFN_vkUnmapMemory>("vkUnmapMemory")(d.device, memory);
  d.get<PFN_vkDestroyCommandPool>("vkDestroyCommandPool")(d.device, pool, nullptr);
  d.get<PFN_vkDestroyBuffer>("vkDestroyBuffer")(d.device, buffer, nullptr);
  d.get<PFN_vkFreeMemory>("vkFreeMemory")(d.device, memory, nullptr);
}

VKAPI_ATTR VkResult VKAPI_CALL QueuePresentKHR(VkQueue queue, const VkPresentInfoKHR* info) {
  Device* d = deviceOf(queue);
  const char* frame = std::getenv("GBLENS_TEST_DUMP_FRAME");
  const char* file = std::getenv("GBLENS_TEST_DUMP_FILE");
  const int n = d->presents++;
  if (file && (!frame || n == std::atoi(frame)) && info->swapchainCount == 1)
    dump(*d, queue, d->images[info->pSwapchains[0]][info->pImageIndices[0]], d->info[info->pSwapchains[0]],
         (std::string(file) + "." + std::to_string(n)).c_str());
  return d->get<PFN_vkQueuePresentKHR>("vkQueuePresentKHR")(queue, info);
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL GetDeviceProcAddr(VkDevice device, const char* name);

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL GetInstanceProcAddr(VkInstance instance, const char* name) {
  if (!std::strcmp(name, "vkGetInstanceProcAddr")) return reinterpret_cast<PFN_vkVoidFunction>(GetInstanceProcAddr);
  if (!std::strcmp(name, "vkGetDeviceProcAddr")) return reinterpret_cast<PFN_vkVoidFunction>(GetDeviceProcAddr);
  if (!std::strcmp(name, "vkCreateInstance")) return reinterpret_cast<PFN_vkVoidFunction>(CreateInstance);
  if (!std::strcmp(name, "vkCreateDevice")) return reinterpret_cast<PFN_vkVoidFunction>(CreateDevice);
  if (!instance) return nullptr;
  std::lock_guard g(lock);
  return instances()[key(instance)].gipa(instance, name);
}

VKAPI_ATTR PFN_vkVoidFunction VKAPI_CALL GetDeviceProcAddr(VkDevice device, const char* name) {
  if (!std::strcmp(name, "vkGetDeviceProcAddr")) return reinterpret_cast<PFN_vkVoidFunction>(GetDeviceProcAddr);
  if (!std::strcmp(name, "vkCreateSwapchainKHR")) return reinterpret_cast<PFN_vkVoidFunction>(CreateSwapchainKHR);
  if (!std::strcmp(name, "vkGetSwapchainImagesKHR")) return reinterpret_cast<PFN_vkVoidFunction>(GetSwapchainImagesKHR);
  if (!std::strcmp(name, "vkQueuePresentKHR")) return reinterpret_cast<PFN_vkVoidFunction>(QueuePresentKHR);
  return deviceOf(device)->gdpa(device, name);
}

}  // namespace

extern "C" __attribute__((visibility("default"))) VKAPI_ATTR VkResult VKAPI_CALL
vkNegotiateLoaderLayerInterfaceVersion(VkNegotiateLayerInterface* v) {
  if (v->loaderLayerInterfaceVersion > 2) v->loaderLayerInterfaceVersion = 2;
  v->pfnGetInstanceProcAddr = GetInstanceProcAddr;
  v->pfnGetDeviceProcAddr = GetDeviceProcAddr;
  v->pfnGetPhysicalDeviceProcAddr = nullptr;
  return VK_SUCCESS;
}
