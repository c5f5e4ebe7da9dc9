// Submissions and frames. The copies a submitted command buffer recorded join the frame being
// made; after the application's own submission an empty one signals a fence of the layer's when
// the GPU is done with it (the application's queue never waits for the layer). A frame ends at
// vkQueuePresentKHR, or, in an application without a swapchain, at each submission that holds a
// render pass; its copies then go to the stream thread (stream.cpp), and what the request named
// but the frame lacked is reported once.
#include <algorithm>
#include <chrono>

#include "app/layer/layer.h"
#include "views/live/live_wire.h"

namespace gbl {

namespace {

struct Submitted {
  bool pass = false, copies = false, skipped = false, paced = false;
  std::vector<Copy> multisampled;  // copies of multisampled attachments, to unpack after the submission
  std::vector<Copy> download;      // the staged ring without a queue of the layer's: every copy, brought to the host after it
};

void addOnce(std::vector<uint32_t>& ids, const std::vector<uint32_t>& more) {
  for (uint32_t id : more)
    if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
}

// --suggest: a recording's passes join the frame's; what it read before its first pass was read
// after the frame's pass before it (reads_after), and what it copied into a swapchain image counts
// as presented.
void gatherStructure(DeviceData& d, const CmdState& s) {
  if (!d.frameReports.empty()) {
    PassReport& before = d.frameReports.back();
    addOnce(before.readsAfter, s.leadingReads);
    for (const PassReport::Storage& e : s.leadingStorage)  // (none before the frame's first pass: no pass to name)
      addStorageOnce(before.storageAfter, e);
  }
  d.frameReports.insert(d.frameReports.end(), s.reports.begin(), s.reports.end());
  addOnce(d.framePresented, s.intoSwapchain);
}

// Gathers what the submitted command buffers recorded. Every buffer they copy into counts one more
// submission (a frame read from it while this count moves may be torn: the thread drops it).
Submitted gather(DeviceData& d, const std::vector<VkCommandBuffer>& cmds) {
  Submitted got;
  std::lock_guard lock(d.frameLock);
  for (VkCommandBuffer cb : cmds) {
    CmdState* s = cmdState(d, cb);
    if (!s) continue;
    got.pass |= s->passes > 0;
    got.skipped |= s->skipped && s->passes > 0;
    got.paced |= s->paced && s->passes > 0;
    if (s->suggest && !d.suggestSent) gatherStructure(d, *s);
    std::vector<RingBuffer*> counted;
    for (const Copy& c : s->copiesMade)
      if (std::find(counted.begin(), counted.end(), c.buffer.get()) == counted.end()) {
        counted.push_back(c.buffer.get());
        ++*c.buffer->submissions;
        GBL_LOG("frame %llu: submits a recording writing ring buffer %u (submission %llu)", (unsigned long long)d.frame.load(),
                c.buffer->id, (unsigned long long)c.buffer->submissions->load());
      }
    if (s->copiesMade.empty() || !d.streaming) continue;
    if (!d.building) d.building = std::make_unique<PendingFrame>();
    PendingFrame& f = *d.building;
    f.reusable |= s->reusable;
    // A later submission's copy of a target replaces an earlier one; its bound buffers replace all earlier ones.
    if (std::any_of(s->copiesMade.begin(), s->copiesMade.end(), [](const Copy& c) { return c.target == kBoundCopy; }))
      std::erase_if(f.copies, [](const Copy& e) { return e.target == kBoundCopy; });
    for (const Copy& c : s->copiesMade) {
      if (c.samples > 1) got.multisampled.push_back(c);
      if (d.staging && !stagedOwnQueue(d)) got.download.push_back(c);
      if (c.target != kBoundCopy) std::erase_if(f.copies, [&](const Copy& e) { return e.target == c.target; });
      f.copies.push_back(c);
      auto w = std::find_if(f.writes.begin(), f.writes.end(), [&](const auto& e) { return e.first == c.buffer; });
      if (w == f.writes.end()) {
        f.writes.push_back({c.buffer, c.buffer->submissions->load()});
        f.held.emplace_back(c.buffer);  // no new recording takes this buffer until the thread has read it
      } else {
        w->second = c.buffer->submissions->load();
      }
    }
    got.copies = true;
  }
  d.passesThisFrame |= got.pass;
  d.skippedThisFrame |= got.skipped;
  d.pacedThisFrame |= got.paced;
  return got;
}

void endFrame(DeviceData& d, const std::vector<uint32_t>& presentedNow = {}) {
  std::shared_ptr<const Request> req = currentRequest(d);
  std::unique_ptr<PendingFrame> f;
  std::vector<PassReport> reports;
  std::vector<uint32_t> presented;
  bool passes = false, suggest = false, skipped = false;
  uint64_t number = 0;
  {
    std::lock_guard lock(d.frameLock);
    number = d.frame++;
    const uint64_t now = gb::wire::monotonicNs();
    if (d.lastFrameEndNs) d.frameNsSum += now - d.lastFrameEndNs, ++d.frameIntervals;
    d.lastFrameEndNs = now;
    f = std::move(d.building);
    reports = std::move(d.frameReports);
    d.frameReports.clear();
    presented = presentedNow;
    addOnce(presented, d.framePresented);
    d.framePresented.clear();
    passes = d.passesThisFrame;
    d.passesThisFrame = false;
    skipped = d.skippedThisFrame;
    d.skippedThisFrame = false;
    if (d.pacedThisFrame && req && frameDue(*req, number) && !f)  // due, not taken
      ++(req->paced && !grantLeft(d) ? d.notAsked : d.droppedAtSource);
    d.pacedThisFrame = false;
    suggest = req && req->suggest && !d.suggestSent && !reports.empty();
    if (suggest) d.suggestSent = true;
    if (f) {
      ++d.copiedFrames;
      f->appFrame = number;
      f->endNs = now;
      // A frame one of whose recordings skipped its copies (every slot held, the ring being made)
      // would hold only some targets: never sent as if it were whole.
      f->due = req && frameDue(*req, number) && !f->broken && !skipped;
      if (f->due && req->paced) {  // one frame a grant; one recorded before the last grant went is not sent
        f->granted = grantLeft(d);
        if (f->granted) ++d.grantsUsed;
        else f->due = false, ++d.notAsked;
      }
      if (f->due) f->stream = ++d.streamed;
      if (f->due && req->onlyFrame >= 0) holdCapture(d);
    }
  }
  if (suggest) streamPasses(d, reports, presented, number);
  if (!req || !d.streaming || !passes || skipped) {  // a frame that did not copy says nothing of the targets
    if (f) streamFrame(d, std::move(f));
    return;
  }
  // What the request names and this frame lacks: once each (the receiver shows why a target is absent).
  bool any = false;
  for (size_t t = 0; t < req->picks.size(); ++t) {
    const Pick& p = req->picks[t];
    const bool got = f && std::any_of(f->copies.begin(), f->copies.end(), [&](const Copy& c) { return c.target == int(t); });
    any |= got;
    if (!got && p.explicitSource && !wasReported(d, "refused:" + p.targetName))  // a refusal said more
      report(d, "missing:" + p.targetName,
             "target \"" + p.targetName + "\": frame " + std::to_string(number) + " has no " +
                 (p.storageSet >= 0                                        ? "compute dispatch with "
                  : req->storagePicks && !p.name.empty() && p.passIndex < 0 ? "render pass or compute dispatch with "
                                                                           : "render pass with ") +
                 pickText(p));
  }
  if (any)
    d.framesWithoutMatch = 0;
  else if (++d.framesWithoutMatch == req->giveUp)
    streamNoMatch(d, d.framesWithoutMatch);
  if (f) streamFrame(d, std::move(f));
}

template <class Call>
VkResult submit(DeviceData& d, VkQueue queue, const std::vector<VkCommandBuffer>& cmds, Call&& call) {
  auto start = std::chrono::steady_clock::now();
  // Before gather counts this submission on the ring buffers frame N's copies may be in.
  if (std::any_of(cmds.begin(), cmds.end(), [&](VkCommandBuffer cb) {
        const CmdState* s = cmdState(d, cb);
        return s && !s->copiesMade.empty();
      }))
    waitForCapture(d);
  const Submitted got = gather(d, cmds);
  const auto before = std::chrono::steady_clock::now();
  VkResult r = call();
  d.hookNs += uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(before - start).count());
  start = std::chrono::steady_clock::now();  // the application's own submission is not the layer's time
  if (got.copies) {
    // The layer's fence, signalled once everything submitted so far on this queue is done.
    // Multisampled targets' samples are unpacked into the ring before it (samples.cpp).
    VkFence fence = r == VK_SUCCESS ? takeFence(d) : VK_NULL_HANDLE;
    if (fence && submitFence(d, queue, got.multisampled, got.download, fence) != VK_SUCCESS)
      returnFence(d, fence), fence = VK_NULL_HANDLE;
    std::lock_guard lock(d.frameLock);
    if (d.building && fence)
      d.building->fences.push_back(fence);
    else if (d.building)
      d.building->broken = true;  // no way to know when its copies are done: not streamed
    else if (fence)
      returnFence(d, fence);
  }
  bool frameEnds;
  {
    std::lock_guard lock(d.frameLock);
    frameEnds = !d.presents && got.pass;
  }
  if (frameEnds) endFrame(d);
  d.hookNs += uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count());
  return r;
}

VKAPI_ATTR VkResult VKAPI_CALL QueueSubmit(VkQueue queue, uint32_t n, const VkSubmitInfo* submits, VkFence fence) {
  DeviceData& d = *deviceOf(queue);
  std::vector<VkCommandBuffer> cmds;
  for (uint32_t i = 0; i < n; ++i)
    cmds.insert(cmds.end(), submits[i].pCommandBuffers, submits[i].pCommandBuffers + submits[i].commandBufferCount);
  return submit(d, queue, cmds, [&] { return d.vk.QueueSubmit(queue, n, submits, fence); });
}

VkResult queueSubmit2(PFN_vkQueueSubmit2 next, VkQueue queue, uint32_t n, const VkSubmitInfo2* submits, VkFence fence) {
  DeviceData& d = *deviceOf(queue);
  std::vector<VkCommandBuffer> cmds;
  for (uint32_t i = 0; i < n; ++i)
    for (uint32_t k = 0; k < submits[i].commandBufferInfoCount; ++k)
      cmds.push_back(submits[i].pCommandBufferInfos[k].commandBuffer);
  return submit(d, queue, cmds, [&] { return next(queue, n, submits, fence); });
}
VKAPI_ATTR VkResult VKAPI_CALL QueueSubmit2(VkQueue queue, uint32_t n, const VkSubmitInfo2* submits, VkFence fence) {
  return queueSubmit2(deviceOf(queue)->vk.QueueSubmit2, queue, n, submits, fence);
}
VKAPI_ATTR VkResult VKAPI_CALL QueueSubmit2KHR(VkQueue queue, uint32_t n, const VkSubmitInfo2* submits, VkFence fence) {
  return queueSubmit2(deviceOf(queue)->vk.QueueSubmit2KHR, queue, n, submits, fence);
}

VKAPI_ATTR VkResult VKAPI_CALL QueuePresentKHR(VkQueue queue, const VkPresentInfoKHR* info) {
  DeviceData& d = *deviceOf(queue);
  VkResult r = d.vk.QueuePresentKHR(queue, info);
  std::vector<uint32_t> presented;  // --suggest: the swapchain images this present shows
  if (!d.suggestSent) {
    std::shared_ptr<const Request> req = currentRequest(d);
    if (req && req->suggest) {
      std::vector<VkImage> images;
      {
        std::shared_lock lock(d.objects);
        for (uint32_t i = 0; i < info->swapchainCount; ++i) {
          auto it = d.swapchainImages.find(info->pSwapchains[i]);
          if (it != d.swapchainImages.end() && info->pImageIndices[i] < it->second.size())
            images.push_back(it->second[info->pImageIndices[i]]);
        }
      }
      for (VkImage image : images) addOnce(presented, {imageId(d, image)});
    }
  }
  endFrame(d, presented);
  return r;
}

}  // namespace

// --capture-frame N (and each frame N of --capture-frames A..B): a submission that copies after
// frame N ended (a reusable recording writing the ring buffers frame N's copies are in; frame N+1's
// own copies, in a range) waits until the receiver has read frame N; at most 20 s (a receiver that
// never answers), then it is said and the application goes on.
void waitForCapture(DeviceData& d) {
  std::unique_lock lock(d.captureLock);
  if (!d.captureHeld) return;
  if (!d.captureRead.wait_for(lock, std::chrono::seconds(20), [&] { return !d.captureHeld; })) {
    d.captureHeld = false;
    lock.unlock();
    report(d, "capture-wait", "the receiver did not read a frame --capture-frame(s) names within 20 s: the application goes on");
  }
}

void holdCapture(DeviceData& d) {
  std::lock_guard lock(d.captureLock);
  d.captureHeld = true;
}

void releaseCapture(DeviceData& d) {
  {
    std::lock_guard lock(d.captureLock);
    d.captureHeld = false;
  }
  d.captureRead.notify_all();
}

std::vector<Hook> submitHooks() {
  return {GBL_HOOK(QueueSubmit), GBL_HOOK(QueueSubmit2), GBL_HOOK(QueueSubmit2KHR), GBL_HOOK(QueuePresentKHR)};
}

}  // namespace gbl
