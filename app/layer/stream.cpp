// The layer's thread and its wire to the receiver (views/capture/live_wire.h). At vkCreateDevice the
// layer connects to the socket gblens attach named, says hello and waits (once, at most 5 s) for the
// request; from then on its own thread waits for the fences of submitted frames, copies a finished
// frame from the ring into the shared memory when the receiver has handed it back, and sends it;
// a frame that finds the receiver busy is dropped and counted, never queued. When the receiver goes
// away or detaches, the layer stops copying (idle).
#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <nlohmann/json.hpp>

#include "app/layer/layer.h"
#include "views/capture/live_wire.h"

namespace gbl {

using json = nlohmann::json;

struct Stream {
  DeviceData* d = nullptr;
  int socket = -1, wake = -1;
  std::thread thread;
  std::atomic<bool> stop{false};
  std::mutex lock;  // pending, outbox, reported
  std::deque<std::unique_ptr<PendingFrame>> pending;
  std::vector<std::string> outbox;
  std::set<std::string> reported;
  // The thread's own:
  int shm = -1;
  uint8_t* map = nullptr;
  size_t mapSize = 0;
  bool shmSent = false, receiverBusy = false;
  uint64_t sent = 0, dropped = 0, torn = 0;
  double copyMs = 0.0;
};

namespace {

void wakeUp(Stream& st) {
  uint64_t one = 1;
  (void)!write(st.wake, &one, sizeof(one));
}

bool parseRequest(const std::string& text, Request& r) {
  json j = json::parse(text, nullptr, false);
  if (!j.is_object() || j.value("type", "") != gb::wire::kRequest) return false;
  r.every = std::max(1u, j.value("every", 1u));
  r.only = j.value("only", uint64_t(0));
  r.suggest = j.value("suggest", false);
  r.giveUp = std::max(1u, j.value("give_up", 120u));
  if (j.contains("camera") && j["camera"].is_object()) {
    r.cameraBuffer = j["camera"].value("buffer", "");
    r.cameraBytes = j["camera"].value("bytes", uint64_t(0));
  }
  for (const json& t : j.value("targets", json::array())) {
    Pick p;
    p.target = int(r.picks.size());
    p.targetName = t.value("name", "");
    p.format = t.value("format", "");
    p.explicitSource = t.value("explicit", false);
    if (t.contains("pass") && t["pass"].is_string()) p.pass = t["pass"].get<std::string>();
    if (t.contains("pass") && t["pass"].is_number_integer()) p.passIndex = t["pass"].get<int>();
    p.name = t.value("attachment_name", "");
    p.color = t.value("color", -1);
    p.depth = t.value("depth", false);
    p.byFormat = t.value("by_format", "");
    r.picks.push_back(p);
  }
  return true;
}

// The frame's copies as one block of shared memory: colour texels as copied (B8G8R8A8 swapped to
// RGBA), depth/stencil as the depth plane then one stencil byte a texel (renderer/core/texels.h).
bool fill(Stream& st, const PendingFrame& f, const Request& req, json& targets, json& camera) {
  DeviceData& d = *st.d;
  size_t total = 0;
  std::vector<size_t> at;
  for (const Copy& c : f.copies) {
    at.push_back(total);
    const FormatInfo& fi = formatInfo(c.format);
    const size_t texels = size_t(c.width) * c.height;
    total = gb::wire::alignUp(total + (c.target < 0 ? c.bytes : texels * fi.bytes + (fi.stencil && fi.depth ? texels : 0)));
  }
  if (total > st.mapSize) {  // a new, larger file: the receiver maps the one that comes with the frame
    if (st.map) munmap(st.map, st.mapSize), close(st.shm);
    st.map = nullptr, st.mapSize = 0;
    st.shm = memfd_create("gblens-live", MFD_CLOEXEC);
    const size_t size = total + total / 2;
    if (st.shm < 0 || ftruncate(st.shm, off_t(size)) != 0) return false;
    void* p = mmap(nullptr, size, PROT_READ | PROT_WRITE, MAP_SHARED, st.shm, 0);
    if (p == MAP_FAILED) return false;
    st.map = static_cast<uint8_t*>(p), st.mapSize = size, st.shmSent = false;
  }
  for (size_t i = 0; i < f.copies.size(); ++i) {
    const Copy& c = f.copies[i];
    if (!c.buffer->coherent) {
      VkMappedMemoryRange range{VK_STRUCTURE_TYPE_MAPPED_MEMORY_RANGE, nullptr, c.buffer->memory, 0, VK_WHOLE_SIZE};
      d.vk.InvalidateMappedMemoryRanges(d.device, 1, &range);
    }
    const uint8_t* src = c.buffer->mapped + c.offset;
    uint8_t* dst = st.map + at[i];
    if (c.target < 0) {
      std::memcpy(dst, src, c.bytes);
      camera = {{"offset", at[i]}, {"bytes", c.bytes}};
      continue;
    }
    const FormatInfo& fi = formatInfo(c.format);
    const size_t texels = size_t(c.width) * c.height, plane = texels * fi.bytes;
    if (fi.bgra) {
      for (size_t k = 0; k < texels; ++k) {
        dst[4 * k + 0] = src[4 * k + 2], dst[4 * k + 1] = src[4 * k + 1];
        dst[4 * k + 2] = src[4 * k + 0], dst[4 * k + 3] = src[4 * k + 3];
      }
    } else {
      std::memcpy(dst, src, plane);
    }
    if (fi.stencil && fi.depth) std::memcpy(dst + plane, c.buffer->mapped + c.stencilOffset, texels);
    const Pick& p = req.picks[size_t(c.target)];
    targets.push_back({{"index", c.target}, {"name", p.targetName}, {"format", fi.storage}, {"vk_format", fi.vkName},
                       {"width", c.width}, {"height", c.height}, {"offset", at[i]},
                       {"bytes", plane + (fi.stencil && fi.depth ? texels : 0)}, {"pass", c.passOrdinal},
                       {"pass_name", c.pass}});
  }
  return true;
}

bool unchanged(const PendingFrame& f) {
  for (const auto& [buffer, count] : f.writes)
    if (buffer->submissions.load() != count) return false;
  return true;
}

json statsJson(Stream& st) {
  DeviceData& d = *st.d;
  std::lock_guard lock(d.frameLock);
  return {{"frames", d.frame.load()},     {"streamed", d.streamed}, {"sent", st.sent},
          {"dropped", st.dropped + d.droppedAtSource.load()}, {"torn", st.torn},        {"ring_bytes", d.ringBytes.load()},
          {"shm_bytes", st.mapSize},
          {"frame_ms", d.frameIntervals ? double(d.frameNsSum) / double(d.frameIntervals) * 1e-6 : 0.0},
          {"layer_ms_per_frame", d.frame ? double(d.hookNs.load() - std::min(d.hookNs.load(), d.allocNs.load())) / double(d.frame) * 1e-6 : 0.0},
          {"ring_allocation_ms", double(d.allocNs.load()) * 1e-6},
          {"thread_copy_ms", st.sent ? st.copyMs / double(st.sent) : 0.0}};
}

// Queues a message for the thread to send, once per key.
void sendOnce(DeviceData& d, const std::string& key, const std::string& message) {
  Stream* st = d.stream;
  if (!st) return;
  {
    std::lock_guard lock(st->lock);
    if (!st->reported.insert(key).second) return;
    st->outbox.push_back(message);
  }
  wakeUp(*st);
}

void goIdle(Stream& st) {
  st.d->streaming = false;
  if (st.socket >= 0) close(st.socket), st.socket = -1;
}

// A finished frame: sent if the receiver is free and the ring was not written meanwhile, else dropped.
void process(Stream& st, const PendingFrame& f) {
  DeviceData& d = *st.d;
  std::shared_ptr<const Request> req = currentRequest(d);
  if (!d.streaming || st.socket < 0 || !f.due || !req || (req->only && f.stream != req->only)) return;
  if (st.receiverBusy || !unchanged(f)) {
    GBL_LOG("frame %llu (streamed %llu): dropped, %s", (unsigned long long)f.appFrame, (unsigned long long)f.stream,
            st.receiverBusy ? "the receiver is busy" : "its ring buffer was submitted again");
    ++st.dropped;
    st.torn += !st.receiverBusy;
    return;
  }
  const auto start = std::chrono::steady_clock::now();
  json targets = json::array(), camera = nullptr;
  if (!fill(st, f, *req, targets, camera)) {
    report(d, "shm", "cannot make the shared memory for a frame: streaming stops");
    return goIdle(st);
  }
  if (!unchanged(f)) {  // the application submitted the ring's buffer again while it was read
    GBL_LOG("frame %llu: dropped, its ring buffer was submitted again while it was read", (unsigned long long)f.appFrame);
    ++st.dropped, ++st.torn;
    return;
  }
  GBL_LOG("frame %llu (streamed %llu): sent, %zu copies", (unsigned long long)f.appFrame, (unsigned long long)f.stream,
          f.copies.size());
  st.copyMs += std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  ++st.sent;
  json m = {{"type", gb::wire::kFrame}, {"stream", f.stream},   {"app_frame", f.appFrame}, {"end_ns", f.endNs},
            {"sent_ns", gb::wire::monotonicNs()}, {"targets", targets}, {"camera", camera}, {"shm_bytes", st.mapSize},
            {"stats", statsJson(st)}};
  if (!gb::wire::send(st.socket, m.dump(), st.shmSent ? -1 : st.shm)) return goIdle(st);
  st.shmSent = true;
  st.receiverBusy = true;
}

void recycle(DeviceData& d, PendingFrame& f) {
  for (VkFence fence : f.fences) returnFence(d, fence);
  f.fences.clear();
}

void readMessages(Stream& st) {
  std::string text;
  while (st.socket >= 0) {
    gb::wire::Received got = gb::wire::receive(st.socket, text, nullptr, 0);
    if (got == gb::wire::Received::Nothing) return;
    if (got == gb::wire::Received::Closed) return goIdle(st);  // the receiver closed or was killed
    json j = json::parse(text, nullptr, false);
    const std::string type = j.is_object() ? j.value("type", "") : "";
    if (type == gb::wire::kAck) st.receiverBusy = false;
    if (type == gb::wire::kDetach) return goIdle(st);
  }
}

void run(Stream& st) {
  DeviceData& d = *st.d;
  while (!st.stop) {
    readMessages(st);
    std::vector<std::string> out;
    std::unique_ptr<PendingFrame> front;
    {
      std::lock_guard lock(st.lock);
      out.swap(st.outbox);
      if (!st.pending.empty()) front = std::move(st.pending.front()), st.pending.pop_front();
    }
    for (const std::string& m : out)
      if (st.socket >= 0 && !gb::wire::send(st.socket, m)) goIdle(st);
    if (front) {
      VkResult r = front->fences.empty() ? VK_SUCCESS
                                         : d.vk.WaitForFences(d.device, uint32_t(front->fences.size()),
                                                              front->fences.data(), VK_TRUE, 2000000);
      if (r == VK_TIMEOUT) {  // not done yet: back to the front of the queue, and look at the socket
        std::lock_guard lock(st.lock);
        st.pending.push_front(std::move(front));
        continue;
      }
      if (r == VK_SUCCESS) process(st, *front);
      recycle(d, *front);
      continue;
    }
    pollfd fds[2] = {{st.wake, POLLIN, 0}, {st.socket, POLLIN, 0}};
    if (poll(fds, st.socket >= 0 ? 2 : 1, 100) > 0 && (fds[0].revents & POLLIN)) {
      uint64_t n;
      (void)!read(st.wake, &n, sizeof(n));
    }
  }
}

}  // namespace

bool connectStream(DeviceData& d) {
  const char* path = std::getenv(gb::wire::kSocketEnv);
  if (!path || !*path || std::strlen(path) >= sizeof(sockaddr_un::sun_path)) return false;
  int s = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strcpy(addr.sun_path, path);
  if (s < 0 || connect(s, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    if (s >= 0) close(s);
    return false;  // nobody listens: the layer stays out of the way
  }
  VkPhysicalDeviceProperties props{};
  d.instance->properties(d.physical, &props);
  json hello = {{"type", gb::wire::kHello}, {"version", gb::wire::kVersion},        {"pid", getpid()},
                {"application", d.instance->application}, {"engine", d.instance->engine}, {"device", props.deviceName}};
  // The request comes at once from a receiver that listens; the application waits for it once, here,
  // so that command buffers it records right away (once, e.g. per swapchain image) copy too.
  std::string text;
  auto request = std::make_shared<Request>();
  if (!gb::wire::send(s, hello.dump()) ||
      gb::wire::receive(s, text, nullptr, 5000) != gb::wire::Received::Message || !parseRequest(text, *request)) {
    close(s);
    return false;
  }
  auto* st = new Stream;
  st->d = &d;
  st->socket = s;
  st->wake = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  d.stream = st;
  {
    std::lock_guard lock(d.requestLock);
    d.request = request;
  }
  d.streaming = true;
  st->thread = std::thread(run, std::ref(*st));
  return true;
}

void stopStream(DeviceData& d) {
  Stream* st = d.stream;
  if (!st) return;
  st->stop = true;
  wakeUp(*st);
  st->thread.join();
  d.streaming = false;
  {
    std::lock_guard lock(d.frameLock);
    if (d.building) st->pending.push_back(std::move(d.building));
  }
  for (auto& f : st->pending) {  // the device is about to go: its fences are waited for and recycled
    if (!f->fences.empty()) d.vk.WaitForFences(d.device, uint32_t(f->fences.size()), f->fences.data(), VK_TRUE, UINT64_MAX);
    recycle(d, *f);
  }
  if (st->socket >= 0) close(st->socket);
  if (st->map) munmap(st->map, st->mapSize);
  if (st->shm >= 0) close(st->shm);
  close(st->wake);
  d.stream = nullptr;
  delete st;
}

void streamFrame(DeviceData& d, std::unique_ptr<PendingFrame> f) {
  Stream* st = d.stream;
  if (!st) return;
  {
    std::lock_guard lock(st->lock);
    st->pending.push_back(std::move(f));
  }
  wakeUp(*st);
}

void streamPasses(DeviceData& d, const std::vector<PassReport>& passes, uint64_t frame) {
  json list = json::array();
  for (const PassReport& p : passes) {
    json attachments = json::array();
    for (const PassReport::Attachment& a : p.attachments)
      attachments.push_back({{"role", a.role}, {"image", a.image}, {"view", a.view}, {"vk_format", a.format},
                             {"format", a.storage}, {"width", a.width}, {"height", a.height}, {"samples", a.samples},
                             {"written", a.written}, {"store_patched", a.storePatched}, {"why", a.why}});
    list.push_back({{"ordinal", p.ordinal}, {"dynamic", p.dynamic}, {"render_pass", p.renderPass},
                    {"labels", p.labels}, {"attachments", attachments}});
  }
  sendOnce(d, "passes", json{{"type", gb::wire::kPasses}, {"frame", frame}, {"passes", list}}.dump());
}

void streamNoMatch(DeviceData& d, uint64_t frames) {
  sendOnce(d, "nomatch", json{{"type", gb::wire::kNoMatch}, {"frames", frames}}.dump());
}

bool wasReported(DeviceData& d, const std::string& key) {
  Stream* st = d.stream;
  if (!st) return false;
  std::lock_guard lock(st->lock);
  return st->reported.count(key) > 0;
}

void report(DeviceData& d, const std::string& key, const std::string& text) {
  sendOnce(d, key, json{{"type", gb::wire::kReport}, {"key", key}, {"text", text}}.dump());
}

}  // namespace gbl
