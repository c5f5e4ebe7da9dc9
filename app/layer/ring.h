// The ring the layer's copies land in (ring.cpp): host-visible buffers held while a recording copies
// into them or a frame waits to be read; the copies a recording made (attachments, the camera's
// bytes, bound buffers) and the frames they make up. Part of layer.h.
#pragma once
#include <vulkan/vulkan.h>

#include <atomic>
#include <cstdint>
#include <memory>
#include <mutex>
#include <string>
#include <utility>
#include <vector>

namespace gbl {

struct DeviceData;

// The staged ring's copy of one single-sampled attachment in the device's own tiling (staging.cpp):
// the application's queue copies image to image (tiled to tiled), and the layer's queue brings it
// to the host buffer at `offset` with the download, so the de-tiling never runs on the
// application's queue.
struct TileImage {
  VkDeviceSize offset = 0;  // the copy's place in the ring buffer (one per target of a recording)
  VkFormat format = VK_FORMAT_UNDEFINED;
  uint32_t width = 0, height = 0;
  VkImage image = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  VkDeviceSize bytes = 0;
};

struct RingBuffer {
  DeviceData* device = nullptr;
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceMemory memory = VK_NULL_HANDLE;
  // The staged ring (staging.cpp): `buffer` is device-local, and the host's copy of it is here.
  VkBuffer hostBuffer = VK_NULL_HANDLE;
  VkDeviceMemory hostMemory = VK_NULL_HANDLE;
  uint8_t* mapped = nullptr;
  VkDeviceSize size = 0;
  VkDeviceSize base = 0;  // the first byte copies may use (a shared buffer starts with its header)
  bool coherent = true;
  // Shared with the receiver (VK_EXT_external_memory_host): the memory is a file's mapping, which
  // the receiver maps too and reads in place; `id` names it on the wire.
  int fd = -1;
  uint32_t id = 0;
  size_t mappedBytes = 0;
  // Submissions that write it (a read is torn if this moves): in the shared header when shared.
  std::atomic<uint64_t> localSubmissions{0};
  std::atomic<uint64_t>* submissions = &localSubmissions;
  // A staged ring's shared host buffer downloaded on the layer's queue: the header's count, which
  // the thread sets to the frame's after each download (the receiver checks it as a submission count).
  std::atomic<uint64_t>* published = nullptr;
  std::atomic<int> holds{0};             // recordings that copy into it and frames not yet read from it
  // A staged ring's tile images (staging.cpp), held as long as the buffer: they have its slot's
  // holds, so a frame's tiles are not written again before its download.
  std::mutex tileLock;
  std::vector<TileImage> tiles;
  ~RingBuffer();
};
using RingRef = std::shared_ptr<RingBuffer>;

// A hold on a ring buffer for as long as this lives: a recording that copies into it, or a frame
// the thread has not read yet. A new recording takes a slot nobody holds, when there is one.
class HeldRing {
 public:
  explicit HeldRing(RingRef b) : buffer_(std::move(b)) { ++buffer_->holds; }
  HeldRing(HeldRing&& o) noexcept : buffer_(std::move(o.buffer_)) {}
  HeldRing& operator=(HeldRing&& o) noexcept {
    release();
    buffer_ = std::move(o.buffer_);
    return *this;
  }
  HeldRing(const HeldRing&) = delete;
  HeldRing& operator=(const HeldRing&) = delete;
  ~HeldRing() { release(); }

 private:
  void release() {
    if (buffer_) --buffer_->holds, buffer_.reset();
  }
  RingRef buffer_;
};

// What a bound-buffer copy was (Copy::target kBoundCopy): where the pass's descriptors bound it.
struct BoundInfo {
  std::string kind;                 // "uniform", "storage", "push_constants"
  uint32_t set = 0, binding = 0, index = 0;
  std::string name;                 // the buffer's debug name ("" : none)
  VkDeviceSize size = 0;            // the whole buffer's
  VkDeviceSize offset = 0, range = 0;  // the bound range (push constants: their offset and size)
};
constexpr int kCameraCopy = -1, kBoundCopy = -2;

// One attachment (or the camera's bytes) copied into a ring buffer by a recorded command buffer.
struct SampleStage;  // samples.cpp: the layer's copy of a multisampled attachment

struct Copy {
  int target = -1;          // index into Request::picks, or kCameraCopy, kBoundCopy
  RingRef buffer;
  VkDeviceSize offset = 0, stencilOffset = 0;
  uint32_t width = 0, height = 0;
  VkFormat format = VK_FORMAT_UNDEFINED;
  VkDeviceSize bytes = 0;   // the camera's
  int passOrdinal = 0;
  std::string pass;         // innermost label or render pass name, for people
  BoundInfo bound;          // kBoundCopy
  // A multisampled attachment: `samples` planes, each `sampleStride` bytes, from `stage`'s samples.
  uint32_t samples = 1;
  VkDeviceSize sampleStride = 0;
  std::shared_ptr<SampleStage> stage;
  // The staged ring's tile image of it (buffer's `tiles`): the download copies it to the host buffer.
  VkImage tile = VK_NULL_HANDLE;
};

// A buffer range (or push constant bytes) a pass's end copies into the ring (copy_buffers.cpp).
struct BufferCopy {
  VkBuffer source = VK_NULL_HANDLE;  // null: `inlineBytes` (push constants), written with vkCmdUpdateBuffer
  VkDeviceSize offset = 0, size = 0;
  std::vector<uint8_t> inlineBytes;
  Copy copy;                         // kCameraCopy or kBoundCopy, and where it lands in the ring
};

// A frame the application submitted with copies in it, waiting for its fences (stream.cpp).
struct PendingFrame {
  uint64_t appFrame = 0, stream = 0, endNs = 0;
  std::vector<Copy> copies;
  std::vector<std::pair<RingRef, uint64_t>> writes;  // each buffer's submission count at submission
  std::vector<VkFence> fences;
  std::vector<HeldRing> held;
  bool due = false;     // streamed (every N); else only its fences are recycled
  bool broken = false;  // a submission of it got no fence: never streamed
  bool granted = false; // a paced request's frame that took the receiver's grant (layer.h grants)
  bool reusable = false; // a recording of it may be submitted again (it writes the same ring bytes then)
};

}  // namespace gbl
