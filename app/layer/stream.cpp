// The layer's thread and its wire to the receiver (views/live/live_wire.h). At vkCreateDevice the
// layer connects to the socket gblens attach named, says hello and waits (once, at most 5 s) for the
// request; from then on its own thread waits for the fences of submitted frames and hands each
// finished one to send.cpp, and sends the layer's reports. When the receiver goes away or detaches,
// the layer stops copying (idle).
#include <fcntl.h>
#include <poll.h>
#include <sys/eventfd.h>
#include <sys/mman.h>
#include <sys/socket.h>
#include <sys/un.h>
#include <unistd.h>

#include <chrono>
#include <cstring>
#include <cstdlib>
#include <nlohmann/json.hpp>

#include "app/layer/stream.h"
#include "views/live/live_wire.h"

namespace gbl {

// GBLENS_LAYER_COMPUTE=0: no copies after dispatches (nor the compute sets followed for them), for
// measuring what they cost (docs/attach.md "Targets written by compute").
static bool computeCopiesOn() {
  static const bool on = [] {
    const char* e = std::getenv("GBLENS_LAYER_COMPUTE");
    return !e || std::strcmp(e, "0") != 0;
  }();
  return on;
}

using json = nlohmann::json;


namespace {

void wakeUp(Stream& st) {
  uint64_t one = 1;
  (void)!write(st.wake, &one, sizeof(one));
}

// {"pass": ORDINAL or "label"} as a layout's live source writes it.
PassPick passPick(const json& j) {
  PassPick p;
  p.on = j.is_object();
  if (!p.on || !j.contains("pass")) return p;
  if (j["pass"].is_string()) p.pass = j["pass"].get<std::string>();
  if (j["pass"].is_number_integer()) p.passIndex = j["pass"].get<int>();
  return p;
}

bool parseRequest(const std::string& text, Request& r) {
  json j = json::parse(text, nullptr, false);
  if (!j.is_object() || j.value("type", "") != gb::wire::kRequest) return false;
  r.every = std::max(1u, j.value("every", 1u));
  r.onlyFrame = j.contains("only_frame") && j["only_frame"].is_number_integer() ? j["only_frame"].get<int64_t>() : -1;
  r.lastFrame = j.contains("last_frame") && j["last_frame"].is_number_integer() ? j["last_frame"].get<int64_t>() : r.onlyFrame;
  if (r.lastFrame < r.onlyFrame) r.lastFrame = r.onlyFrame;
  r.suggest = j.value("suggest", false);
  r.ringOffThread = j.value("ring_off_thread", false);
  r.paced = j.value("paced", false) && r.onlyFrame < 0;
  r.giveUp = std::max(1u, j.value("give_up", 120u));
  if (j.contains("camera") && j["camera"].is_object()) {
    r.cameraBuffer = j["camera"].value("buffer", "");
    r.cameraBytes = j["camera"].value("bytes", uint64_t(0));
    if (const json live = j["camera"].value("live", json()); live.is_object()) {
      r.liveCamera = passPick(live);
      r.cameraSet = live.value("set", 0u);
      r.cameraBinding = live.value("binding", 0u);
      r.cameraIndex = live.value("index", 0u);
      r.cameraPushConstants = live.value("push_constants", false);
    }
  }
  if (j.contains("bound_buffers")) {
    r.boundBuffers = passPick(j["bound_buffers"]);
    if (r.boundBuffers.on) r.boundMaxBytes = std::max<uint64_t>(4, j["bound_buffers"].value("max_bytes", uint64_t(4) << 20));
  }
  for (const json& t : j.value("targets", json::array())) {
    Pick p;
    p.target = int(r.picks.size());
    p.targetName = t.value("name", "");
    p.format = t.value("format", "");
    p.explicitSource = t.value("explicit", false);
    const json live = t.value("live", json::object());  // as the layout writes a live source
    if (live.contains("pass") && live["pass"].is_string()) p.pass = live["pass"].get<std::string>();
    if (live.contains("pass") && live["pass"].is_number_integer()) p.passIndex = live["pass"].get<int>();
    p.name = live.value("name", "");
    p.color = live.value("color", -1);
    p.depth = live.value("depth", false);
    p.byFormat = live.value("format", "");
    p.subpass = live.value("subpass", -1);
    p.attachment = live.value("attachment", -1);
    if (const json storage = live.value("storage", json::object()); storage.is_object() && storage.contains("set"))
      p.storageSet = storage.value("set", -1), p.storageBinding = storage.value("binding", -1);
    r.storagePicks |= (p.storageSet >= 0 || (!p.name.empty() && p.attachment < 0 && p.subpass < 0 && p.passIndex < 0)) &&
                    computeCopiesOn();
    r.picks.push_back(p);
  }
  return true;
}

}  // namespace

void wakeStream(DeviceData& d) {
  if (d.stream) wakeUp(*d.stream);
}

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
  releaseCapture(*st.d);
  if (st.socket >= 0) close(st.socket), st.socket = -1;
  st.atReceiver.reset();
  if (st.waiting) st.waiting.reset(), --st.d->toReceiver;
  st.receiverBusy = st.d->receiverBusy = false;
}

namespace {

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
    if (type == gb::wire::kAck) {  // the receiver's buffers are free again: the frame waiting goes now
      st.receiverBusy = st.d->receiverBusy = false;
      // --capture-frame(s): a frame read in place is read now (one copied out was let go when sent;
      // the hold now may be the next frame's of a range, waiting below or still on the GPU).
      if (st.atReceiver) releaseCapture(*st.d);
      st.atReceiver.reset();
      if (st.waiting) {
        process(st, std::move(st.waiting));
        --st.d->toReceiver;
      }
    }
    if (type == gb::wire::kReady) {  // a paced receiver wants the next frame (or the next two)
      const uint64_t want = st.d->grantsUsed + std::clamp(j.value("frames", 1u), 1u, 2u);
      if (want > st.d->grants) st.d->grants = want;
    }
    if (type == gb::wire::kDetach) return goIdle(st);
  }
}

void run(Stream& st) {
  DeviceData& d = *st.d;
  while (!st.stop) {
    readMessages(st);
    growRing(d);
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
      recycle(d, *front);
      if (r == VK_SUCCESS) process(st, std::move(front));
      else giveBack(d, *front);
      --d.toReceiver;
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

Stream* openStream(InstanceData& instance, VkPhysicalDevice physical) {
  const char* path = std::getenv(gb::wire::kSocketEnv);
  if (!path || !*path || std::strlen(path) >= sizeof(sockaddr_un::sun_path)) return nullptr;
  int s = socket(AF_UNIX, SOCK_SEQPACKET | SOCK_CLOEXEC, 0);
  sockaddr_un addr{};
  addr.sun_family = AF_UNIX;
  std::strcpy(addr.sun_path, path);
  if (s < 0 || connect(s, reinterpret_cast<sockaddr*>(&addr), sizeof(addr)) != 0) {
    if (s >= 0) close(s);
    return nullptr;  // nobody listens: the layer stays out of the way
  }
  VkPhysicalDeviceProperties props{};
  instance.properties(physical, &props);
  json hello = {{"type", gb::wire::kHello}, {"version", gb::wire::kVersion},   {"pid", getpid()},
                {"application", instance.application}, {"engine", instance.engine}, {"device", props.deviceName}};
  // The request comes at once from a receiver that listens; the application waits for it once, here,
  // so that command buffers it records right away (once, e.g. per swapchain image) copy too.
  std::string text;
  auto request = std::make_shared<Request>();
  if (!gb::wire::send(s, hello.dump()) ||
      gb::wire::receive(s, text, nullptr, 5000) != gb::wire::Received::Message || !parseRequest(text, *request)) {
    close(s);
    return nullptr;
  }
  auto* st = new Stream;
  st->socket = s;
  st->wake = eventfd(0, EFD_CLOEXEC | EFD_NONBLOCK);
  st->request = request;
  return st;
}

void closeStream(Stream* st) {
  close(st->socket);
  close(st->wake);
  delete st;
}

void startStream(DeviceData& d, Stream* st) {
  st->d = &d;
  d.stream = st;
  {
    std::lock_guard lock(d.requestLock);
    d.request = st->request;
  }
  d.boundBuffersAsked = st->request->boundBuffers.on;
  d.grantsUsed = 0;  // a paced receiver's first frame is granted at the connect
  d.grants = 1;
  d.streaming = true;
  st->thread = std::thread(run, std::ref(*st));
}

void stopStream(DeviceData& d) {
  Stream* st = d.stream;
  if (!st) return;
  // --capture-frame(s): a frame asked for, still on its way (its fence, the receiver's ack of the
  // one before), is sent before the device goes: an application may end right after a range's last frame.
  waitForCapture(d);
  st->stop = true;
  wakeUp(*st);
  st->thread.join();
  d.streaming = false;
  {
    std::lock_guard lock(d.frameLock);
    if (d.building) st->pending.push_back(std::move(d.building));
  }
  st->atReceiver.reset();
  st->waiting.reset();
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
  ++d.toReceiver;  // until the thread has sent or dropped it
  {
    std::lock_guard lock(st->lock);
    st->pending.push_back(std::move(f));
  }
  wakeUp(*st);
}

namespace {

json loadName(VkAttachmentLoadOp op) {
  switch (op) {
    case VK_ATTACHMENT_LOAD_OP_LOAD: return "load";
    case VK_ATTACHMENT_LOAD_OP_CLEAR: return "clear";
    case VK_ATTACHMENT_LOAD_OP_DONT_CARE: return "dont_care";
    default: return "none";
  }
}
json storeName(VkAttachmentStoreOp op) {
  return op == VK_ATTACHMENT_STORE_OP_STORE ? "store" : op == VK_ATTACHMENT_STORE_OP_DONT_CARE ? "dont_care" : "none";
}

// An attachment with the application's own ops per aspect (null: the format has no such aspect).
json attachmentJson(const PassReport::Attachment& a) {
  const bool main = a.depth || !a.stencil;  // a colour or depth aspect
  return {{"role", a.role}, {"image", a.image}, {"view", a.view}, {"image_id", a.imageId}, {"vk_format", a.format},
          {"format", a.storage}, {"width", a.width}, {"height", a.height}, {"samples", a.samples},
          {"written", a.written}, {"presented", a.presented},
          {"load", main ? loadName(a.ops.load) : json()}, {"store", main ? storeName(a.ops.store) : json()},
          {"stencil_load", a.stencil ? loadName(a.ops.stencilLoad) : json()},
          {"stencil_store", a.stencil ? storeName(a.ops.stencilStore) : json()},
          {"store_patched", a.ops.storePatched || a.ops.stencilStorePatched},
          {"stencil_store_patched", a.ops.stencilStorePatched}, {"why", a.why}};
}

}  // namespace

void streamPasses(DeviceData& d, const std::vector<PassReport>& passes, const std::vector<uint32_t>& presented,
                  uint64_t frame) {
  json list = json::array();
  for (const PassReport& p : passes) {
    json attachments = json::array();
    for (const PassReport::Attachment& a : p.attachments) attachments.push_back(attachmentJson(a));
    json storage = json::array();
    for (const PassReport::Storage& e : p.storageAfter) {
      const PassReport::Attachment& a = e.image;
      storage.push_back({{"image", a.image}, {"view", a.view}, {"image_id", a.imageId}, {"vk_format", a.format},
                         {"format", a.storage}, {"width", a.width}, {"height", a.height}, {"samples", a.samples},
                         {"set", e.set}, {"binding", e.binding}, {"labels", e.labels}, {"why", a.why}});
    }
    list.push_back({{"ordinal", p.ordinal}, {"dynamic", p.dynamic}, {"render_pass", p.renderPass}, {"labels", p.labels},
                    {"attachments", attachments}, {"reads", p.reads}, {"reads_after", p.readsAfter},
                    {"storage_after", storage}});
  }
  sendOnce(d, "passes",
           json{{"type", gb::wire::kPasses}, {"frame", frame}, {"passes", list}, {"presented", presented}}.dump());
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
