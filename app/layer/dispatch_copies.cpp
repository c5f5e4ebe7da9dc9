// G-buffers written by compute (visibility-buffer and compute-deferred engines): a storage image a
// pick names (or binds at the set and binding a pick gives) is copied after the last of a run of
// dispatches that bind it, before the next command that could write it again: a dispatch binding it
// supersedes the pending copy; a render pass writing it as an attachment copies it at its end
// instead; another render pass, a clear, a copy or blit into an image, a barrier discarding it,
// secondary command buffers and the recording's end flush it; a barrier moving it to another layout
// keeps it pending there. The frame holds what the last such dispatch left (docs/attach.md "Targets
// written by compute"); the copies and barriers are copy.cpp's.
#include <algorithm>
#include <chrono>

#include "app/layer/layer.h"

namespace gbl {

namespace {

// The views of the images (or views) a pick names: found once per recording, so that a dispatch
// compares its storage descriptors with a handful of views, not with every view the device has
// (the caller holds d.objects).
void findNamedViews(DeviceData& d, const Request& req, CmdState& s) {
  s.namedViewsFound = true;
  s.namedViews.clear();
  auto named = [&](const std::string& name) {
    return !name.empty() && std::any_of(req.picks.begin(), req.picks.end(), [&](const Pick& p) { return p.name == name; });
  };
  for (const auto& [view, info] : d.views) {
    auto image = d.images.find(info.image);
    if (image != d.images.end() && (image->second.usage & VK_IMAGE_USAGE_STORAGE_BIT) &&
        (named(info.name) || named(image->second.name)))
      s.namedViews.push_back(view);
  }
}

bool bindingPicked(const Request& req, uint32_t set, uint32_t binding) {
  return std::any_of(req.picks.begin(), req.picks.end(), [&](const Pick& p) {
    return p.storageSet == int(set) && p.storageBinding == int(binding);
  });
}

// The storage images the compute sets bound now hold that a pick names, or binds at a set and
// binding a pick gives (the caller holds d.objects).
std::vector<PassAttachment> boundPickedStorage(DeviceData& d, const Request& req, CmdState& s) {
  std::vector<PassAttachment> out;
  std::vector<BoundDescriptor> bound;
  for (uint32_t n = 0; n < s.computeSets.size(); ++n)
    if (s.computeSets[n].bound()) boundDescriptors(d, n, s.computeSets[n], bound);
  for (const BoundDescriptor& b : bound) {
    if (b.type != VK_DESCRIPTOR_TYPE_STORAGE_IMAGE || !b.view || !d.views.count(b.view)) continue;
    const bool atBinding = bindingPicked(req, b.set, b.binding);
    if (!atBinding && std::find(s.namedViews.begin(), s.namedViews.end(), b.view) == s.namedViews.end()) continue;
    if (std::any_of(out.begin(), out.end(), [&](const PassAttachment& a) { return a.view == b.view; })) continue;
    PassAttachment a;
    a.image = d.views.at(b.view).image;
    a.view = b.view;
    a.written = a.storage = true;
    a.layout = a.stencilLayout = VK_IMAGE_LAYOUT_GENERAL;  // where storage images are accessed
    if (atBinding) a.storageSet = int(b.set), a.storageBinding = int(b.binding);
    out.push_back(a);
  }
  return out;
}

}  // namespace

void dispatchCopies(DeviceData& d, VkCommandBuffer, CmdState& s) {
  std::shared_ptr<const Request> req = currentRequest(d);
  if (!req || !req->storagePicks) return;
  const auto start = std::chrono::steady_clock::now();
  std::shared_lock lock(d.objects);
  if (!s.namedViewsFound) findNamedViews(d, *req, s);
  const bool bindings = std::any_of(req->picks.begin(), req->picks.end(), [](const Pick& p) { return p.storageSet >= 0; });
  if (s.namedViews.empty() && !bindings) return;
  for (PassAttachment& a : boundPickedStorage(d, *req, s)) {
    std::erase_if(s.pendingStorage, [&](const PendingStorage& p) { return p.attachment.view == a.view; });
    s.pendingStorage.push_back({a, s.labels});
  }
  const uint64_t ns = uint64_t(std::chrono::duration_cast<std::chrono::nanoseconds>(std::chrono::steady_clock::now() - start).count());
  d.hookNs += ns;
  if (ns > 1000000) GBL_LOG("a dispatch's storage images took %.2f ms to look up", double(ns) * 1e-6);
}

void flushStorageCopies(DeviceData& d, VkCommandBuffer cmd, CmdState& s) {
  std::vector<PendingStorage> pending;
  pending.swap(s.pendingStorage);
  while (!pending.empty() && s.copies) {  // one "pass" per run of the same labels (the target's pass name)
    OpenPass pass;
    pass.ordinal = -1;
    pass.labels = pending.front().labels;
    for (auto it = pending.begin(); it != pending.end();)
      if (it->labels == pass.labels) {
        pass.attachments.push_back(it->attachment);
        it = pending.erase(it);
      } else {
        ++it;
      }
    recordPassCopies(d, cmd, s, pass);
  }
}

void storageBeforePass(DeviceData& d, VkCommandBuffer cmd, CmdState& s) {
  std::shared_ptr<const Request> req = currentRequest(d);
  std::erase_if(s.pendingStorage, [&](const PendingStorage& p) {
    auto a = std::find_if(s.open.attachments.begin(), s.open.attachments.end(),
                          [&](const PassAttachment& x) { return x.image == p.attachment.image && x.written; });
    // A pick by set and binding is no render pass's: only the dispatch's copy serves it.
    if (a == s.open.attachments.end() || !req || p.attachment.storageSet >= 0) return false;
    // The pass's end copies it only for picks that follow the image through every pass; a pick
    // naming the dispatch's pass wants what the dispatch left.
    std::string name, viewName;
    {
      std::shared_lock lock(d.objects);
      if (auto i = d.images.find(p.attachment.image); i != d.images.end()) name = i->second.name;
      if (auto v = d.views.find(p.attachment.view); v != d.views.end()) viewName = v->second.name;
    }
    return std::none_of(req->picks.begin(), req->picks.end(), [&](const Pick& k) {
      return (k.name == name || k.name == viewName) && (!k.pass.empty() || k.passIndex >= 0);
    });
  });
  if (!s.pendingStorage.empty()) flushStorageCopies(d, cmd, s);
}

namespace {

// Commands that may write an image: the pending storage copies go first.
void beforeWrite(VkCommandBuffer cmd) {
  DeviceData& d = *deviceOf(cmd);
  if (CmdState* s = cmdState(d, cmd); s && !s->pendingStorage.empty()) flushStorageCopies(d, cmd, *s);
}

VKAPI_ATTR void VKAPI_CALL CmdClearColorImage(VkCommandBuffer cmd, VkImage image, VkImageLayout layout, const VkClearColorValue* c,
                                              uint32_t n, const VkImageSubresourceRange* ranges) {
  beforeWrite(cmd);
  deviceOf(cmd)->vk.CmdClearColorImage(cmd, image, layout, c, n, ranges);
}
VKAPI_ATTR void VKAPI_CALL CmdClearDepthStencilImage(VkCommandBuffer cmd, VkImage image, VkImageLayout layout,
                                                     const VkClearDepthStencilValue* c, uint32_t n,
                                                     const VkImageSubresourceRange* ranges) {
  beforeWrite(cmd);
  deviceOf(cmd)->vk.CmdClearDepthStencilImage(cmd, image, layout, c, n, ranges);
}
VKAPI_ATTR void VKAPI_CALL CmdCopyBufferToImage(VkCommandBuffer cmd, VkBuffer src, VkImage dst, VkImageLayout layout, uint32_t n,
                                                const VkBufferImageCopy* regions) {
  beforeWrite(cmd);
  deviceOf(cmd)->vk.CmdCopyBufferToImage(cmd, src, dst, layout, n, regions);
}
VKAPI_ATTR void VKAPI_CALL CmdCopyBufferToImage2(VkCommandBuffer cmd, const VkCopyBufferToImageInfo2* info) {
  beforeWrite(cmd);
  deviceOf(cmd)->vk.CmdCopyBufferToImage2(cmd, info);
}
VKAPI_ATTR void VKAPI_CALL CmdCopyBufferToImage2KHR(VkCommandBuffer cmd, const VkCopyBufferToImageInfo2* info) {
  beforeWrite(cmd);
  deviceOf(cmd)->vk.CmdCopyBufferToImage2KHR(cmd, info);
}
// A barrier over a pending image: one that discards it (from UNDEFINED) copies it first; one that
// moves it to another layout keeps it pending there (a render pass that then writes it as an
// attachment copies it itself: the compute clear before a raster G-buffer is never copied).
void throughBarriers(VkCommandBuffer cmd, uint32_t n, const VkImage* images, const VkImageLayout* from, const VkImageLayout* to,
                     size_t stride) {
  DeviceData& d = *deviceOf(cmd);
  CmdState* s = cmdState(d, cmd);
  if (!s || s->pendingStorage.empty()) return;
  auto at = [&](const void* base, uint32_t i) { return static_cast<const char*>(base) + stride * i; };
  bool discarded = false;
  for (uint32_t i = 0; i < n && !discarded; ++i) {
    const VkImage image = *reinterpret_cast<const VkImage*>(at(images, i));
    const VkImageLayout oldLayout = *reinterpret_cast<const VkImageLayout*>(at(from, i));
    for (const PendingStorage& p : s->pendingStorage)
      discarded |= p.attachment.image == image && (oldLayout == VK_IMAGE_LAYOUT_UNDEFINED || oldLayout == VK_IMAGE_LAYOUT_PREINITIALIZED);
  }
  if (discarded) return flushStorageCopies(d, cmd, *s);
  for (uint32_t i = 0; i < n; ++i) {
    const VkImage image = *reinterpret_cast<const VkImage*>(at(images, i));
    const VkImageLayout newLayout = *reinterpret_cast<const VkImageLayout*>(at(to, i));
    for (PendingStorage& p : s->pendingStorage)
      if (p.attachment.image == image) p.attachment.layout = p.attachment.stencilLayout = newLayout;
  }
}
void throughBarriers(VkCommandBuffer cmd, uint32_t n, const VkImageMemoryBarrier* b) {
  if (n) throughBarriers(cmd, n, &b->image, &b->oldLayout, &b->newLayout, sizeof(*b));
}
void throughBarriers(VkCommandBuffer cmd, uint32_t count, const VkDependencyInfo* infos) {
  for (uint32_t k = 0; k < count; ++k)
    if (const VkDependencyInfo& i = infos[k]; i.imageMemoryBarrierCount)
      throughBarriers(cmd, i.imageMemoryBarrierCount, &i.pImageMemoryBarriers->image, &i.pImageMemoryBarriers->oldLayout,
                      &i.pImageMemoryBarriers->newLayout, sizeof(VkImageMemoryBarrier2));
}

VKAPI_ATTR void VKAPI_CALL CmdPipelineBarrier(VkCommandBuffer cmd, VkPipelineStageFlags src, VkPipelineStageFlags dst,
                                              VkDependencyFlags flags, uint32_t nm, const VkMemoryBarrier* m, uint32_t nb,
                                              const VkBufferMemoryBarrier* b, uint32_t ni, const VkImageMemoryBarrier* i) {
  throughBarriers(cmd, ni, i);
  deviceOf(cmd)->vk.CmdPipelineBarrier(cmd, src, dst, flags, nm, m, nb, b, ni, i);
}
VKAPI_ATTR void VKAPI_CALL CmdPipelineBarrier2(VkCommandBuffer cmd, const VkDependencyInfo* info) {
  throughBarriers(cmd, 1, info);
  deviceOf(cmd)->vk.CmdPipelineBarrier2(cmd, info);
}
VKAPI_ATTR void VKAPI_CALL CmdPipelineBarrier2KHR(VkCommandBuffer cmd, const VkDependencyInfo* info) {
  throughBarriers(cmd, 1, info);
  deviceOf(cmd)->vk.CmdPipelineBarrier2KHR(cmd, info);
}
VKAPI_ATTR void VKAPI_CALL CmdWaitEvents(VkCommandBuffer cmd, uint32_t n, const VkEvent* events, VkPipelineStageFlags src,
                                         VkPipelineStageFlags dst, uint32_t nm, const VkMemoryBarrier* m, uint32_t nb,
                                         const VkBufferMemoryBarrier* b, uint32_t ni, const VkImageMemoryBarrier* i) {
  throughBarriers(cmd, ni, i);
  deviceOf(cmd)->vk.CmdWaitEvents(cmd, n, events, src, dst, nm, m, nb, b, ni, i);
}
VKAPI_ATTR void VKAPI_CALL CmdWaitEvents2(VkCommandBuffer cmd, uint32_t n, const VkEvent* events, const VkDependencyInfo* infos) {
  throughBarriers(cmd, n, infos);
  deviceOf(cmd)->vk.CmdWaitEvents2(cmd, n, events, infos);
}
VKAPI_ATTR void VKAPI_CALL CmdWaitEvents2KHR(VkCommandBuffer cmd, uint32_t n, const VkEvent* events, const VkDependencyInfo* infos) {
  throughBarriers(cmd, n, infos);
  deviceOf(cmd)->vk.CmdWaitEvents2KHR(cmd, n, events, infos);
}
VKAPI_ATTR void VKAPI_CALL CmdExecuteCommands(VkCommandBuffer cmd, uint32_t n, const VkCommandBuffer* cmds) {
  beforeWrite(cmd);
  deviceOf(cmd)->vk.CmdExecuteCommands(cmd, n, cmds);
}

}  // namespace

void flushBeforeWrite(VkCommandBuffer cmd) { beforeWrite(cmd); }

std::vector<Hook> storageWriterHooks() {
  return {GBL_HOOK(CmdClearColorImage), GBL_HOOK(CmdClearDepthStencilImage), GBL_HOOK(CmdCopyBufferToImage),
          GBL_HOOK(CmdCopyBufferToImage2), GBL_HOOK(CmdCopyBufferToImage2KHR), GBL_HOOK(CmdExecuteCommands),
          GBL_HOOK(CmdPipelineBarrier), GBL_HOOK(CmdPipelineBarrier2), GBL_HOOK(CmdPipelineBarrier2KHR),
          GBL_HOOK(CmdWaitEvents), GBL_HOOK(CmdWaitEvents2), GBL_HOOK(CmdWaitEvents2KHR)};
}

}  // namespace gbl
