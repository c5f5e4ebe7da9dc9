// A finished frame to the receiver. Where the ring is shared memory (VK_EXT_external_memory_host:
// ring.cpp), the frame message names the ring buffers and offsets and the receiver reads the texels
// in place, the buffers held until it hands the frame back; otherwise the thread copies the frame
// into a shared-memory file of its own (buffer 0) first. Either way one frame at a time: a frame
// that finds the receiver busy is dropped and counted. Texels are as the GPU copied them
// (depth/stencil: the depth plane, then a stencil byte a texel: renderer/core/texels.h); B8G8R8A8
// attachments are marked, and the receiver swaps R and B back.
#include <sys/mman.h>
#include <unistd.h>

#include <chrono>
#include <cstring>

#include "app/layer/stream.h"
#include "views/live/live_wire.h"

namespace gbl {

using json = nlohmann::json;

namespace {

size_t copyBytes(const Copy& c) { return size_t(copySize(c)); }

}  // namespace

VkDeviceSize copySize(const Copy& c) {
  if (c.target < 0) return c.bytes;
  if (c.samples > 1) return c.sampleStride * c.samples;
  const FormatInfo& f = formatInfo(c.format);
  const VkDeviceSize texels = VkDeviceSize(c.width) * c.height, plane = texels * f.bytes;
  return f.stencil && f.depth ? (plane + 3) / 4 * 4 + texels : plane;  // the stencil plane at a multiple of 4
}

namespace {

json targetJson(const Request& req, const Copy& c, uint32_t buffer, size_t offset) {
  const FormatInfo& f = formatInfo(c.format);
  return {{"index", c.target},  {"name", req.picks[size_t(c.target)].targetName}, {"format", f.storage},
          {"vk_format", f.vkName}, {"bgra", f.bgra}, {"width", c.width}, {"height", c.height}, {"buffer", buffer},
          {"offset", offset}, {"bytes", copyBytes(c)}, {"pass", c.passOrdinal}, {"pass_name", c.pass},
          {"samples", c.samples}, {"sample_stride", c.samples > 1 ? c.sampleStride : 0}};
}

// A bound buffer's range (or the push constants) and where its bytes are.
json boundJson(const Copy& c, uint32_t buffer, size_t offset) {
  const BoundInfo& b = c.bound;
  const json data = {{"buffer", buffer}, {"offset", offset}, {"bytes", c.bytes}};
  if (b.kind == "push_constants")
    return {{"kind", b.kind}, {"offset", b.offset}, {"size", b.range}, {"pass", c.passOrdinal}, {"data", data}};
  return {{"kind", b.kind}, {"set", b.set},   {"binding", b.binding}, {"index", b.index}, {"name", b.name},
          {"size", b.size}, {"offset", b.offset}, {"range", b.range}, {"pass", c.passOrdinal}, {"data", data}};
}

// The frame message's entry for one copy: a target, the camera or a bound buffer.
void describe(const Request& req, const Copy& c, uint32_t buffer, size_t offset, json& targets, json& camera, json& bound) {
  if (c.target == kCameraCopy)
    camera = {{"buffer", buffer}, {"offset", offset}, {"bytes", c.bytes}};
  else if (c.target == kBoundCopy)
    bound.push_back(boundJson(c, buffer, offset));
  else
    targets.push_back(targetJson(req, c, buffer, offset));
}

bool allShared(const PendingFrame& f) {
  for (const Copy& c : f.copies)
    if (c.buffer->fd < 0) return false;
  return true;
}

// The frame read in place: the receiver maps each ring buffer once (sent with its file), and checks
// the submission counts in their headers before and after reading (a buffer a reused command
// buffer wrote again meanwhile makes the frame torn, and it drops it).
bool describeShared(Stream& st, const PendingFrame& f, const Request& req, json& targets, json& camera, json& bound,
                    json& counts) {
  for (const auto& [buffer, count] : f.writes) {
    if (!st.sentBuffers.count(buffer->id)) {
      const json m = {{"type", gb::wire::kBuffer}, {"id", buffer->id}, {"bytes", buffer->size}};
      if (!gb::wire::send(st.socket, m.dump(), buffer->fd)) return false;
      st.sentBuffers.insert(buffer->id);
    }
    counts.push_back({buffer->id, count});
  }
  for (const Copy& c : f.copies) describe(req, c, c.buffer->id, size_t(c.offset), targets, camera, bound);
  return true;
}

// The frame copied out of the ring into buffer 0 (a file that grows when a frame needs more).
bool fill(Stream& st, const PendingFrame& f, const Request& req, json& targets, json& camera, json& bound) {
  DeviceData& d = *st.d;
  size_t total = 0;
  std::vector<size_t> at;
  for (const Copy& c : f.copies) {
    at.push_back(total);
    total = gb::wire::alignUp(total + copyBytes(c));
  }
  if (total > st.mapSize) {
    if (st.map) munmap(st.map, st.mapSize), close(st.shm);
    st.map = nullptr, st.mapSize = 0;
    st.shm = memfd_create("gblens-live", MFD_CLOEXEC);
    const size_t size = total + total / 2;
    if (st.shm < 0 || ftruncate(st.shm, off_t(size)) != 0) return false;
    void* p = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, st.shm, 0);
    if (p == MAP_FAILED) return false;
    st.map = static_cast<uint8_t*>(p), st.mapSize = size, st.shmSent = false;
  }
  if (!st.shmSent) {
    if (!gb::wire::send(st.socket, json{{"type", gb::wire::kBuffer}, {"id", 0}, {"bytes", st.mapSize}}.dump(), st.shm))
      return false;
    st.shmSent = true;
  }
  for (size_t i = 0; i < f.copies.size(); ++i) {
    const Copy& c = f.copies[i];
    if (!c.buffer->coherent) {
      VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr,
                                c.buffer->hostMemory ? c.buffer->hostMemory : c.buffer->memory, 0, VK_WHOLE_SIZE};
      d.vk.InvalidateMappedMemoryRanges(d.device, 1, &range);
    }
    std::memcpy(st.map + at[i], c.buffer->mapped + c.offset, copyBytes(c));
    describe(req, c, 0, at[i], targets, camera, bound);
  }
  return true;
}

bool unchanged(const PendingFrame& f) {
  for (const auto& [buffer, count] : f.writes)
    if (buffer->submissions->load() != count) return false;
  return true;
}

}  // namespace

json statsJson(Stream& st) {
  DeviceData& d = *st.d;
  std::lock_guard lock(d.frameLock);
  const uint64_t hook = d.hookNs.load(), alloc = std::min(hook, d.allocNs.load());
  return {{"frames", d.frame.load()},
          {"streamed", d.streamed},
          {"sent", st.sent},
          {"dropped", st.dropped + d.droppedAtSource.load()},
          {"torn", st.torn},
          {"ring_bytes", d.ringBytes.load()},
          {"ring_shared", d.hostImport},
          {"shm_bytes", st.mapSize},
          {"frame_ms", d.frameIntervals ? double(d.frameNsSum) / double(d.frameIntervals) * 1e-6 : 0.0},
          {"layer_ms_per_frame", d.frame ? double(hook - alloc) / double(d.frame) * 1e-6 : 0.0},
          {"ring_allocation_ms", double(d.allocNs.load()) * 1e-6},  // in the application's threads
          {"ring_allocation_thread_ms", double(d.threadAllocNs.load()) * 1e-6},
          {"frames_waiting_for_ring", d.droppedForRing.load()},
          {"thread_copy_ms", st.sent ? st.copyMs / double(st.sent) : 0.0},
          {"ring_staged", d.staging != nullptr},
          {"ring_staged_shared", d.staging != nullptr && d.stagedShared},
          {"ring_tile_copies", d.tileCopies.load()},
          {"storage_copies", d.storageCopies.load()},
          {"paced", st.request && st.request->paced},  // one frame a ready (the viewer's pace)
          {"copied_frames", d.copiedFrames.load()},
          {"not_asked", d.notAsked.load()},  // paced: frames due that the receiver had not asked for
          {"ring_download", !d.staging ? "none" : stagedOwnQueue(d) ? "layer queue" : "application queue"},
          {"download_ms", st.sent ? st.downloadMs / double(st.sent) : 0.0},
          {"copy_gpu", copyTimingJson(d)}};  // GBLENS_LAYER_TIMESTAMPS=1 only
}

void giveBack(DeviceData& d, const PendingFrame& f) {
  if (f.granted) --d.grantsUsed;
}

namespace {

// A frame whose ring bytes were written again before it was sent: counted, a capture's hold let go,
// its grant given back.
void dropTorn(Stream& st, const PendingFrame& f, bool only) {
  ++st.dropped, ++st.torn;
  if (only) releaseCapture(*st.d);
  giveBack(*st.d, f);
}

}  // namespace

void process(Stream& st, std::unique_ptr<PendingFrame> f) {
  DeviceData& d = *st.d;
  std::shared_ptr<const Request> req = currentRequest(d);
  if (!d.streaming || st.socket < 0 || !f->due || !req) return;
  const bool only = req->onlyFrame >= 0;
  // --capture-frame N: frame N alone is due, and submissions that would write its ring buffers again
  // wait until it is read (submit.cpp); one found written again all the same is said, not sent.
  if (only && !unchanged(*f)) {
    report(d, "torn", "frame " + std::to_string(f->appFrame) + ": its copies were written again before the layer read them");
    return releaseCapture(d);
  }
  if (!only && !unchanged(*f)) {
    GBL_LOG("frame %llu (streamed %llu): dropped, its ring buffer was submitted again", (unsigned long long)f->appFrame,
            (unsigned long long)f->stream);
    return dropTorn(st, *f, only);
  }
  // Busy: it waits for the receiver's ack; a newer one takes its place. A frame of --capture-frames
  // never finds one waiting (the next frame's submission waited until this one was read).
  if (st.receiverBusy) {
    if (st.waiting) {
      GBL_LOG("frame %llu: dropped, a newer one waits for the receiver", (unsigned long long)st.waiting->appFrame);
      ++st.dropped;
      --d.toReceiver;
      giveBack(d, *st.waiting);
    }
    ++d.toReceiver;  // still on its way (stream.cpp run() counts it off when process returns)
    st.waiting = std::move(f);
    return;
  }
  const uint64_t ready = gb::wire::monotonicNs();
  const auto start = std::chrono::steady_clock::now();
  json targets = json::array(), camera = nullptr, bound = json::array(), counts = json::array();
  // A recording submitted again writes the same ring bytes at its next run: read in place, nearly
  // every frame of a quick application (vkcube, 2 ms a frame on lavapipe) was written again while
  // gblens decoded it, and none came. Such a frame is copied out here at once instead (a memcpy,
  // checked against the submission counts after it).
  const bool shared = allShared(*f) && !f->reusable;
  // The staged ring on a queue of the layer's: this frame's bytes cross to the host now (only the
  // frames sent ever do).
  if (stagedOwnQueue(d)) {
    const auto down = std::chrono::steady_clock::now();
    if (!downloadFrame(d, f->copies)) {
      report(d, "download", "the layer's queue did not bring a frame's copies to the host: streaming stops");
      return goIdle(st);
    }
    st.downloadMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - down).count();
    // The application wrote the device ring again before the download had it.
    if (!unchanged(*f)) return dropTorn(st, *f, only);
    for (const auto& [buffer, count] : f->writes)
      if (buffer->published) buffer->published->store(count);  // what the receiver will check
  }
  if (!(shared ? describeShared(st, *f, *req, targets, camera, bound, counts) : fill(st, *f, *req, targets, camera, bound))) {
    report(d, "shm", "cannot share a frame's memory with the receiver: streaming stops");
    return goIdle(st);
  }
  if (!shared && !unchanged(*f)) {  // the application submitted the ring's buffer again while it was read
    GBL_LOG("frame %llu: dropped, its ring buffer was submitted again while it was read", (unsigned long long)f->appFrame);
    return dropTorn(st, *f, only);
  }
  st.copyMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ++st.sent;
  GBL_LOG("frame %llu (streamed %llu): sent, %zu copies%s", (unsigned long long)f->appFrame, (unsigned long long)f->stream,
          f->copies.size(), shared ? " (read in place)" : "");
  if (only && !shared) releaseCapture(d);  // copied out: the ring may be written again
  const uint64_t number = f->stream;
  json m = {{"type", gb::wire::kFrame}, {"stream", number}, {"app_frame", f->appFrame}, {"end_ns", f->endNs},
            {"ready_ns", ready},       {"targets", targets},   {"camera", camera},         {"writes", counts},
            {"stats", statsJson(st)}};
  if (req->boundBuffers.on) m["bound_buffers"] = bound;
  if (!gb::wire::send(st.socket, m.dump())) return goIdle(st);
  st.receiverBusy = d.receiverBusy = true;
  if (shared) st.atReceiver = std::move(f);  // its buffers stay held until the receiver hands the frame back
}

}  // namespace gbl
