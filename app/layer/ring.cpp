// The ring the layer's copies land in: three slots of host-visible memory (cached where the device
// has it), taken in turn by the command buffers that copy. A slot's buffer is replaced by a larger
// one when a recording needs more room; the old one lives while a recording or a frame in flight
// still holds it (shared ownership). Fences for the frames' submissions come from a small pool.
#include <sys/mman.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <nlohmann/json.hpp>

#include "app/layer/stream.h"
#include "views/live/live_wire.h"

namespace gbl {

namespace {

constexpr VkDeviceSize kAlign = 256;  // copies' buffer offsets (depth/stencil copies need 4)
constexpr size_t kMaxFences = 16;     // frames the GPU may still run with copies in them

uint32_t memoryType(const DeviceData& d, uint32_t bits, bool& coherent) {
  // Cached and coherent, then cached (invalidated before reading), then whatever is host-visible.
  const VkMemoryPropertyFlags wants[] = {
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_CACHED_BIT,
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT | VK_MEMORY_PROPERTY_HOST_COHERENT_BIT,
      VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT};
  for (VkMemoryPropertyFlags want : wants)
    for (uint32_t i = 0; i < d.memory.memoryTypeCount; ++i)
      if ((bits & (1u << i)) && (d.memory.memoryTypes[i].propertyFlags & want) == want) {
        coherent = d.memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_HOST_COHERENT_BIT;
        return i;
      }
  return UINT32_MAX;
}

}  // namespace

uint32_t deviceLocalMemoryType(const DeviceData& d, uint32_t bits) {
  for (uint32_t i = 0; i < d.memory.memoryTypeCount; ++i)
    if ((bits & (1u << i)) && (d.memory.memoryTypes[i].propertyFlags & VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT)) return i;
  for (uint32_t i = 0; i < d.memory.memoryTypeCount; ++i)  // every device has one; kept for a device that lies
    if (bits & (1u << i)) return i;
  return UINT32_MAX;
}

namespace {

// A buffer whose memory is a shared file's mapping, imported with VK_EXT_external_memory_host:
// the receiver maps the same file. Its first kHeader bytes hold the submission count.
constexpr VkDeviceSize kHeader = 256;

RingRef allocateShared(DeviceData& d, VkDeviceSize size) {
  auto r = std::make_shared<RingBuffer>();
  r->device = &d;
  VkExternalMemoryBufferCreateInfo external{VK_STRUCTURE_TYPE_EXTERNAL_MEMORY_BUFFER_CREATE_INFO};
  external.handleTypes = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
  // The buffer spans the whole file (its size a multiple of the import alignment), header included.
  const VkDeviceSize align = std::max<VkDeviceSize>(d.hostAlignment, uint64_t(sysconf(_SC_PAGESIZE)));
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO, &external};
  bi.size = (size + kHeader + align - 1) / align * align;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;  // samples.cpp writes it too
  if (d.vk.CreateBuffer(d.device, &bi, nullptr, &r->buffer) != VK_SUCCESS) return nullptr;
  r->size = bi.size;
  VkMemoryRequirements req{};
  d.vk.GetBufferMemoryRequirements(d.device, r->buffer, &req);
  const VkDeviceSize bytes = (std::max(req.size, bi.size) + align - 1) / align * align;
  r->fd = memfd_create("gblens-ring", MFD_CLOEXEC);
  void* p = r->fd >= 0 && ftruncate(r->fd, off_t(bytes)) == 0
                ? mmap(nullptr, bytes, PROT_READ | PROT_WRITE, MAP_SHARED, r->fd, 0)
                : MAP_FAILED;
  if (p == MAP_FAILED) return nullptr;
  r->mapped = static_cast<uint8_t*>(p);
  r->mappedBytes = bytes;  // unmapped by the destructor from here on
  VkMemoryHostPointerPropertiesEXT host{VK_STRUCTURE_TYPE_MEMORY_HOST_POINTER_PROPERTIES_EXT};
  if (d.vk.GetMemoryHostPointerPropertiesEXT(d.device, VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT, p, &host) !=
      VK_SUCCESS)
    return nullptr;
  bool coherent = false;
  VkImportMemoryHostPointerInfoEXT import{VK_STRUCTURE_TYPE_IMPORT_MEMORY_HOST_POINTER_INFO_EXT};
  import.handleType = VK_EXTERNAL_MEMORY_HANDLE_TYPE_HOST_ALLOCATION_BIT_EXT;
  import.pHostPointer = p;
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO, &import};
  ai.allocationSize = bytes;
  ai.memoryTypeIndex = memoryType(d, req.memoryTypeBits & host.memoryTypeBits, coherent);
  // The receiver cannot invalidate caches: only coherent memory is read in place.
  if (ai.memoryTypeIndex == UINT32_MAX || !coherent || d.vk.AllocateMemory(d.device, &ai, nullptr, &r->memory) != VK_SUCCESS ||
      d.vk.BindBufferMemory(d.device, r->buffer, r->memory, 0) != VK_SUCCESS)
    return nullptr;
  r->base = kHeader;
  r->submissions = new (p) std::atomic<uint64_t>(0);
  r->id = ++d.nextRingId;  // (reserve holds the ring's lock)
  return r;
}

// The staged ring (staging.cpp): the buffer the GPU copies into in device-local memory, shared by
// the queue families that use it, and its host copy, mapped.
RingRef allocateStaged(DeviceData& d, VkDeviceSize size) {
  auto r = std::make_shared<RingBuffer>();
  r->device = &d;
  r->size = size;
  auto make = [&](VkBufferUsageFlags usage, bool host, VkBuffer& buffer, VkDeviceMemory& memory) {
    VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
    bi.size = size;
    bi.usage = usage;
    if (d.ringFamilies.size() > 1) {  // the application's queues write it, the layer's reads it
      bi.sharingMode = VK_SHARING_MODE_CONCURRENT;
      bi.queueFamilyIndexCount = uint32_t(d.ringFamilies.size());
      bi.pQueueFamilyIndices = d.ringFamilies.data();
    }
    if (d.vk.CreateBuffer(d.device, &bi, nullptr, &buffer) != VK_SUCCESS) return false;
    VkMemoryRequirements req{};
    d.vk.GetBufferMemoryRequirements(d.device, buffer, &req);
    VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
    ai.allocationSize = req.size;
    ai.memoryTypeIndex = host ? memoryType(d, req.memoryTypeBits, r->coherent) : deviceLocalMemoryType(d, req.memoryTypeBits);
    return ai.memoryTypeIndex != UINT32_MAX && d.vk.AllocateMemory(d.device, &ai, nullptr, &memory) == VK_SUCCESS &&
           d.vk.BindBufferMemory(d.device, buffer, memory, 0) == VK_SUCCESS;
  };
  const VkBufferUsageFlags gpu = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;
  if (d.stagedShared) {  // the host side a shared file gblens reads in place (its header included)
    if (RingRef shared = allocateShared(d, size)) {
      shared->hostBuffer = shared->buffer, shared->hostMemory = shared->memory;
      shared->buffer = VK_NULL_HANDLE, shared->memory = VK_NULL_HANDLE;
      r = shared;
      r->size = shared->size;
      size = shared->size;  // the device buffer mirrors the whole file: the copies' offsets are the same
      if (!make(gpu, false, r->buffer, r->memory)) return nullptr;
      if (stagedOwnQueue(d)) {  // downloads only for the frames sent: the thread publishes their counts
        r->published = r->submissions;
        r->submissions = &r->localSubmissions;
      }  // else every submission's batch downloads: the header counts submissions, as a shared ring's
      d.ringBytes += 2 * size;
      return r;
    }
    d.stagedShared = false;  // this device cannot share its host memory after all: frames are copied out
  }
  void* p = nullptr;
  if (!make(gpu, false, r->buffer, r->memory) ||
      !make(VK_BUFFER_USAGE_TRANSFER_DST_BIT, true, r->hostBuffer, r->hostMemory) ||
      d.vk.MapMemory(d.device, r->hostMemory, 0, VK_WHOLE_SIZE, 0, &p) != VK_SUCCESS)
    return nullptr;  // the destructor frees what was made
  r->mapped = static_cast<uint8_t*>(p);
  d.ringBytes += 2 * size;
  return r;
}

// A ring buffer of `size` bytes; its time counts as the application's (allocNs) unless the layer's
// thread makes it (`onThread`: threadAllocNs).
RingRef allocate(DeviceData& d, VkDeviceSize size, bool onThread = false) {
  const auto start = std::chrono::steady_clock::now();
  struct Timed {  // allocations are counted apart from the per-frame time (they happen once, or on a resize)
    std::atomic<uint64_t>& ns;
    std::chrono::steady_clock::time_point start;
    ~Timed() { ns += uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count()); }
  } timed{onThread ? d.threadAllocNs : d.allocNs, start};
  if (d.hostImport) {
    if (RingRef shared = allocateShared(d, size)) {
      d.ringBytes += shared->size;
      return shared;
    }
    d.hostImport = false;  // this device cannot share its host memory after all: frames are copied out
    GBL_LOG("a shared ring buffer could not be made: frames are copied out of the ring from now on");
  }
  if (d.staging) {
    RingRef staged = allocateStaged(d, size);
    return staged;
  }
  auto r = std::make_shared<RingBuffer>();
  r->device = &d;
  r->size = size;
  VkBufferCreateInfo bi{VK_STRUCTURE_TYPE_BUFFER_CREATE_INFO};
  bi.size = size;
  bi.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT;  // samples.cpp writes it too
  if (d.vk.CreateBuffer(d.device, &bi, nullptr, &r->buffer) != VK_SUCCESS) return nullptr;
  VkMemoryRequirements req{};
  d.vk.GetBufferMemoryRequirements(d.device, r->buffer, &req);
  VkMemoryAllocateInfo ai{VK_STRUCTURE_TYPE_MEMORY_ALLOCATE_INFO};
  ai.allocationSize = req.size;
  ai.memoryTypeIndex = memoryType(d, req.memoryTypeBits, r->coherent);
  void* p = nullptr;
  if (ai.memoryTypeIndex == UINT32_MAX || d.vk.AllocateMemory(d.device, &ai, nullptr, &r->memory) != VK_SUCCESS ||
      d.vk.BindBufferMemory(d.device, r->buffer, r->memory, 0) != VK_SUCCESS ||
      d.vk.MapMemory(d.device, r->memory, 0, VK_WHOLE_SIZE, 0, &p) != VK_SUCCESS)
    return nullptr;  // the destructor frees what was made
  r->mapped = static_cast<uint8_t*>(p);
  d.ringBytes += size;
  return r;
}

}  // namespace

RingBuffer::~RingBuffer() {
  if (!device) return;
  DeviceData& d = *device;
  if (buffer) d.vk.DestroyBuffer(d.device, buffer, nullptr);
  if (memory) d.vk.FreeMemory(d.device, memory, nullptr);  // unmaps it, unless it is a shared file's
  if (hostBuffer) d.vk.DestroyBuffer(d.device, hostBuffer, nullptr);
  if (hostMemory) d.vk.FreeMemory(d.device, hostMemory, nullptr);
  for (const TileImage& t : tiles) {
    d.vk.DestroyImage(d.device, t.image, nullptr);
    d.vk.FreeMemory(d.device, t.memory, nullptr);
    d.ringBytes -= t.bytes;
  }
  if (fd >= 0) {
    if (mapped) munmap(mapped, mappedBytes);
    close(fd);
    if (id) sendOnce(d, "retire:" + std::to_string(id), nlohmann::json{{"type", gb::wire::kRetire}, {"id", id}}.dump());
  }
  if (mapped && (fd < 0 || base)) d.ringBytes -= hostMemory ? 2 * size : size;
}

int takeSlot(DeviceData& d, bool reusable) {
  std::lock_guard lock(d.ringLock);
  // The next slot that nobody holds (no recording copies into it, no frame waits to be read from
  // it). When all three are held, a command buffer submitted once does not copy (its frame is
  // dropped here, before any work); one that is submitted again and again (recorded once per
  // swapchain image) shares the next slot: the thread drops a frame whose buffer was submitted
  // again while it read it.
  int slot = reusable ? int(d.nextSlot % 3) : -1;
  for (uint32_t i = 0; i < 3; ++i) {
    const int k = int((d.nextSlot + i) % 3);
    if (!d.slots[k] || d.slots[k]->holds == 0) {
      slot = k;
      break;
    }
  }
  if (slot < 0) {
    ++d.droppedAtSource;
    GBL_LOG("a recording finds every ring slot held: its frame is dropped");
    return -1;
  }
  d.nextSlot = uint32_t(slot) + 1;
  GBL_LOG("a recording takes ring slot %d (holds %d %d %d)", slot, d.slots[0] ? d.slots[0]->holds.load() : 0,
          d.slots[1] ? d.slots[1]->holds.load() : 0, d.slots[2] ? d.slots[2]->holds.load() : 0);
  return slot;
}

bool reserve(DeviceData& d, CmdState& s, VkDeviceSize bytes, RingRef& buffer, VkDeviceSize& offset) {
  const VkDeviceSize need = (bytes + kAlign - 1) / kAlign * kAlign;
  if (s.ringPending) {  // no copies this frame: what the rest of it needs counts for the buffers the thread makes
    s.total += need;
    std::lock_guard lock(d.ringLock);
    d.largestRecording = std::max(d.largestRecording, s.total);
    d.ringWanted = std::max(d.ringWanted, d.largestRecording / 4 * 5 / kAlign * kAlign + kAlign);
    return false;
  }
  if (s.slot < 0 && (s.slot = takeSlot(d, s.reusable)) < 0) return false;
  s.total += need;
  if (s.buffer && s.used + need <= s.buffer->size - s.buffer->base) {
    buffer = s.buffer;
    offset = s.buffer->base + s.used;
    s.used += need;
    return true;
  }
  std::lock_guard lock(d.ringLock);
  d.largestRecording = std::max(d.largestRecording, s.total);
  RingRef& slot = d.slots[s.slot];
  if (!slot || slot == s.buffer || slot->size - slot->base < need) {
    // A new buffer for the slot, sized for the largest recording seen (a quarter more), so that a
    // recording's whole frame soon fits one buffer and resizes allocate once, not every frame.
    const VkDeviceSize size = std::max(need, d.largestRecording) / 4 * 5 / kAlign * kAlign + kAlign;
    // A recording submitted once, streaming (not one frame asked for exactly): the layer's thread
    // makes every slot's buffer (growRing) and this frame goes without copies, so the application
    // never waits for an allocation (at 4K on an H200 a quarter of a second when the receiver connects).
    std::shared_ptr<const Request> req = currentRequest(d);
    if (!s.reusable && d.stream && req && req->ringOffThread && req->onlyFrame < 0) {
      d.ringWanted = std::max(d.ringWanted, size);
      s.ringPending = true;
      ++d.droppedForRing;
      wakeStream(d);
      return false;
    }
    RingRef grown = allocate(d, size);
    if (!grown) return false;
    slot = grown;
  }
  s.buffer = slot;
  s.held.emplace_back(slot);
  s.used = need;
  buffer = slot;
  offset = slot->base;
  return true;
}

void growRing(DeviceData& d) {
  VkDeviceSize want = 0;
  {
    std::lock_guard lock(d.ringLock);
    want = d.ringWanted;
  }
  if (!want) return;
  for (int k = 0; k < 3; ++k) {
    {
      std::lock_guard lock(d.ringLock);
      if (d.slots[k] && d.slots[k]->size - d.slots[k]->base >= want) continue;
    }
    RingRef grown = allocate(d, want, true);  // without the lock: recordings go on meanwhile
    if (!grown) {
      report(d, "memory", "out of host-visible memory for the copies: streaming stops");
      d.streaming = false;
      break;
    }
    std::lock_guard lock(d.ringLock);
    if (!d.slots[k] || d.slots[k]->size - d.slots[k]->base < want) d.slots[k] = grown;  // a holder keeps the old one
  }
  std::lock_guard lock(d.ringLock);
  if (d.ringWanted == want) d.ringWanted = 0;
}

VkFence takeFence(DeviceData& d) {
  std::lock_guard lock(d.ringLock);
  if (!d.freeFences.empty()) {
    VkFence f = d.freeFences.back();
    d.freeFences.pop_back();
    return f;
  }
  if (d.fenceCount >= kMaxFences) return VK_NULL_HANDLE;  // the GPU is far behind: this frame is not streamed
  VkFenceCreateInfo fi{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence f = VK_NULL_HANDLE;
  if (d.vk.CreateFence(d.device, &fi, nullptr, &f) != VK_SUCCESS) return VK_NULL_HANDLE;
  ++d.fenceCount;
  return f;
}

void returnFence(DeviceData& d, VkFence f) {
  releaseSamples(d, f);
  d.vk.ResetFences(d.device, 1, &f);
  std::lock_guard lock(d.ringLock);
  d.freeFences.push_back(f);
}

void destroyRing(DeviceData& d) {
  std::lock_guard lock(d.ringLock);
  for (RingRef& s : d.slots) s.reset();
  for (VkFence f : d.freeFences) d.vk.DestroyFence(d.device, f, nullptr);
  d.freeFences.clear();
}

}  // namespace gbl
