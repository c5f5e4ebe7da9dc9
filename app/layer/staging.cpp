// The staged ring of a discrete GPU (docs/attach.md "How the copies travel"): the application's
// command buffers copy the attachments into device-local memory at the end of their pass (a few
// hundredths of a millisecond), and the bytes cross PCIe into host memory only for a frame the
// receiver takes, on a queue of the layer's own (a transfer-only family where there is one) that
// the application's queue never waits for. Where no queue is left for the layer (lavapipe has one;
// GBLENS_LAYER_STAGED=1 forces the staged ring there, for tests), the download is recorded after the
// application's work in the layer's batch on its queue (samples.cpp submitFence).
#include <algorithm>
#include <cstdlib>
#include <cstring>

#include "app/layer/layer.h"

namespace gbl {

struct StagingState {
  bool ownQueue = false;
  bool graphics = false;  // the download's family is a graphics one (its own queue's, or the application's)
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t family = 0;
  VkCommandPool pool = VK_NULL_HANDLE;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
};

namespace {

// GBLENS_LAYER_STAGED: "1" the staged ring on any device (tests), "0" never; unset: discrete GPUs.
int stagedEnv() {
  const char* e = std::getenv("GBLENS_LAYER_STAGED");
  return !e ? -1 : std::strcmp(e, "0") ? 1 : 0;
}

// A tile image: a single-sampled 2D image of the attachment's format in optimal tiling, in
// device-local memory shared by the ring's queue families (no ownership transfers).
bool makeTile(DeviceData& d, TileImage& t) {
  VkImageCreateInfo ii{VK_STRUCTURE_TYPE_IMAGE_CREATE_INFO};
  ii.imageType = VK_IMAGE_TYPE_2D;
  ii.format = t.format;
  ii.extent = {t.width, t.height, 1};
  ii.mipLevels = ii.arrayLayers = 1;
  ii.samples = VK_SAMPLE_COUNT_1_BIT;
  ii.tiling = VK_IMAGE_TILING_OPTIMAL;
  ii.usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  if (d.ringFamilies.size() > 1) {
    ii.sharingMode = VK_SHARING_MODE_CONCURRENT;
    ii.queueFamilyIndexCount = uint32_t(d.ringFamilies.size());
    ii.pQueueFamilyIndices = d.ringFamilies.data();
  }
  if (d.vk.CreateImage(d.device, &ii, nullptr, &t.image) != VK_SUCCESS) return t.image = VK_NULL_HANDLE, false;
  VkMemoryRequirements req{};
  d.vk.GetImageMemoryRequirements(d.device, t.image, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = deviceLocalMemoryType(d, req.memoryTypeBits);
  if (ai.memoryTypeIndex == UINT32_MAX || d.vk.AllocateMemory(d.device, &ai, nullptr, &t.memory) != VK_SUCCESS ||
      d.vk.BindImageMemory(d.device, t.image, t.memory, 0) != VK_SUCCESS) {
    d.vk.DestroyImage(d.device, t.image, nullptr);
    if (t.memory) d.vk.FreeMemory(d.device, t.memory, nullptr);
    t.image = VK_NULL_HANDLE, t.memory = VK_NULL_HANDLE;
    return false;
  }
  t.bytes = req.size;
  d.ringBytes += t.bytes;
  return true;
}

}  // namespace

bool planStaging(InstanceData& inst, VkPhysicalDevice physical, const VkDeviceCreateInfo& info, QueuePlan& plan) {
  VkPhysicalDeviceProperties props{};
  inst.properties(physical, &props);
  const int env = stagedEnv();
  const bool discrete = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU;
  if (env == 0 || (env < 0 && !discrete)) return false;
  plan.staged = true;
  plan.infos.assign(info.pQueueCreateInfos, info.pQueueCreateInfos + info.queueCreateInfoCount);
  if (!inst.queueFamilies) return true;
  uint32_t n = 0;
  inst.queueFamilies(physical, &n, nullptr);
  std::vector<VkQueueFamilyProperties> families(n);
  inst.queueFamilies(physical, &n, families.data());
  // A transfer-only family first (the copy engines), then compute-only, then any that copies.
  auto rank = [&](uint32_t f) {
    const VkQueueFlags q = families[f].queueFlags;
    if (!(q & (VK_QUEUE_TRANSFER_BIT | VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT))) return 9;
    return !(q & (VK_QUEUE_GRAPHICS_BIT | VK_QUEUE_COMPUTE_BIT)) ? 0 : !(q & VK_QUEUE_GRAPHICS_BIT) ? 1 : 2;
  };
  std::vector<uint32_t> order(n);
  for (uint32_t f = 0; f < n; ++f) order[f] = f;
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return rank(a) < rank(b); });
  for (uint32_t f : order) {
    if (rank(f) == 9 || (families[f].queueFlags & VK_QUEUE_PROTECTED_BIT && !(families[f].queueFlags & VK_QUEUE_TRANSFER_BIT)))
      continue;
    uint32_t used = 0;
    int plain = -1;  // the application's unprotected queues of this family
    for (size_t k = 0; k < plan.infos.size(); ++k)
      if (plan.infos[k].queueFamilyIndex == f) {
        used += plan.infos[k].queueCount;
        if (plan.infos[k].flags == 0) plain = int(k);
      }
    if (used >= families[f].queueCount) continue;
    plan.family = f;
    plan.familyFlags = families[f].queueFlags;
    if (plain >= 0) {  // one more queue in the application's own info for the family (its priorities kept)
      VkDeviceQueueCreateInfo& q = plan.infos[size_t(plain)];
      plan.priorities.assign(q.pQueuePriorities, q.pQueuePriorities + q.queueCount);
      plan.priorities.push_back(0.5f);
      plan.index = q.queueCount;
      q.queueCount += 1;
      q.pQueuePriorities = plan.priorities.data();
    } else {
      plan.priorities = {0.5f};
      VkDeviceQueueCreateInfo q{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
      q.queueFamilyIndex = f;
      q.queueCount = 1;
      q.pQueuePriorities = plan.priorities.data();
      plan.infos.push_back(q);
      plan.index = 0;
    }
    plan.ownQueue = true;
    return true;
  }
  return true;  // staged, downloads in the layer's batch on the application's queue
}

void startStaging(DeviceData& d, const QueuePlan& plan) {
  if (!plan.staged) return;
  auto* s = new StagingState;
  d.staging = s;
  s->graphics = !plan.ownQueue || (plan.familyFlags & VK_QUEUE_GRAPHICS_BIT);
  for (uint32_t f : d.createdFamilies)
    if (std::find(d.ringFamilies.begin(), d.ringFamilies.end(), f) == d.ringFamilies.end()) d.ringFamilies.push_back(f);
  if (!plan.ownQueue) return;
  d.vk.GetDeviceQueue(d.device, plan.family, plan.index, &s->queue);
  if (d.setLoaderData) d.setLoaderData(d.device, s->queue);  // a dispatchable object the loader did not hand out
  VkCommandPoolCreateInfo pi{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pi.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pi.queueFamilyIndex = plan.family;
  VkCommandBufferAllocateInfo ai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  ai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  ai.commandBufferCount = 1;
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  if (d.vk.CreateCommandPool(d.device, &pi, nullptr, &s->pool) != VK_SUCCESS) return;
  ai.commandPool = s->pool;
  if (d.vk.AllocateCommandBuffers(d.device, &ai, &s->cmd) != VK_SUCCESS || d.vk.CreateFence(d.device, &fi, nullptr, &s->fence) != VK_SUCCESS)
    return;
  if (d.setLoaderData) d.setLoaderData(d.device, s->cmd);
  s->family = plan.family;
  s->ownQueue = true;
  if (std::find(d.ringFamilies.begin(), d.ringFamilies.end(), plan.family) == d.ringFamilies.end())
    d.ringFamilies.push_back(plan.family);
}

bool stagedOwnQueue(const DeviceData& d) { return d.staging && d.staging->ownQueue; }

bool tilesWanted(const DeviceData& d, bool depthStencil) {
  // Off unless GBLENS_LAYER_TILES=1 (or "colour": colour attachments only): measured on the H200
  // (docs/attach.md "Cost"), the image-to-image copies cost the application's queue more than the
  // image-to-buffer ones they replace (1.140x against 1.094x at 1080p streaming every frame).
  static const int mode = [] {
    const char* e = std::getenv("GBLENS_LAYER_TILES");
    return !e || !std::strcmp(e, "0") ? 0 : !std::strcmp(e, "colour") ? 1 : 2;
  }();
  // Depth/stencil tiles only where a graphics family downloads them: on the H200 a depth/stencil
  // image-to-buffer copy on the transfer-only family lost the device (driver 580.159), colour ones
  // did not; those go through the device buffer (de-tiled on the application's queue, as before).
  if (!d.staging || mode == 0) return false;
  return !depthStencil || (mode == 2 && d.staging->graphics);
}

VkImage ringTile(DeviceData& d, RingBuffer& ring, VkDeviceSize offset, VkFormat format, uint32_t width, uint32_t height) {
  std::lock_guard lock(ring.tileLock);
  for (TileImage& t : ring.tiles)
    if (t.offset == offset) {
      if (t.format == format && t.width == width && t.height == height) return t.image;
      d.vk.DestroyImage(d.device, t.image, nullptr);  // the slot's holds say nothing reads it now
      d.vk.FreeMemory(d.device, t.memory, nullptr);
      d.ringBytes -= t.bytes;
      t = ring.tiles.back();
      ring.tiles.pop_back();
      break;
    }
  TileImage t{offset, format, width, height};
  if (!makeTile(d, t)) return VK_NULL_HANDLE;  // this copy goes through the device buffer instead
  ring.tiles.push_back(t);
  return t.image;
}

void recordDownload(DeviceData& d, VkCommandBuffer cmd, const std::vector<Copy>& copies) {
  VkMemoryBarrier before{VK_STRUCTURE_TYPE_MEMORY_BARRIER};  // the copies (and samples' shaders) wrote the ring
  before.srcAccessMask = VK_ACCESS_MEMORY_WRITE_BIT;
  before.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
  d.vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_ALL_COMMANDS_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 1, &before, 0, nullptr, 0,
                          nullptr);
  for (const Copy& c : copies) {
    if (!c.buffer || !c.buffer->hostBuffer) continue;
    if (c.tile) {  // de-tiled here, on the layer's queue: the planes as the device buffer would hold them
      VkBufferImageCopy r[2]{};
      uint32_t n = 0;
      auto plane = [&](VkImageAspectFlags aspect, VkDeviceSize offset) {
        r[n].bufferOffset = offset;
        r[n].imageSubresource = {aspect, 0, 0, 1};
        r[n++].imageExtent = {c.width, c.height, 1};
      };
      const FormatInfo& f = formatInfo(c.format);
      if (f.depth || !f.stencil) plane(f.depth ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT, c.offset);
      if (f.stencil) plane(VK_IMAGE_ASPECT_STENCIL_BIT, f.depth ? c.stencilOffset : c.offset);
      d.vk.CmdCopyImageToBuffer(cmd, c.tile, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, c.buffer->hostBuffer, n, r);
      continue;
    }
    const VkBufferCopy region{c.offset, c.offset, copySize(c)};
    d.vk.CmdCopyBuffer(cmd, c.buffer->buffer, c.buffer->hostBuffer, 1, &region);
  }
  VkMemoryBarrier after{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  after.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  after.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  d.vk.CmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &after, 0, nullptr, 0, nullptr);
}

bool downloadFrame(DeviceData& d, const std::vector<Copy>& copies) {
  StagingState& s = *d.staging;
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  if (d.vk.ResetCommandBuffer(s.cmd, 0) != VK_SUCCESS || d.vk.BeginCommandBuffer(s.cmd, &bi) != VK_SUCCESS) return false;
  recordDownload(d, s.cmd, copies);
  d.vk.EndCommandBuffer(s.cmd);
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &s.cmd;
  d.vk.ResetFences(d.device, 1, &s.fence);
  if (d.vk.QueueSubmit(s.queue, 1, &si, s.fence) != VK_SUCCESS) return false;
  return d.vk.WaitForFences(d.device, 1, &s.fence, VK_TRUE, 2000000000ull) == VK_SUCCESS;
}

void destroyStaging(DeviceData& d) {
  if (!d.staging) return;
  StagingState& s = *d.staging;
  if (s.fence) d.vk.DestroyFence(d.device, s.fence, nullptr);
  if (s.pool) d.vk.DestroyCommandPool(d.device, s.pool, nullptr);
  delete d.staging;
  d.staging = nullptr;
}

}  // namespace gbl
