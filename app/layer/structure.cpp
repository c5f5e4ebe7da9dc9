// The frame's structure for --suggest and the sets a pass binds: descriptor sets bound per bind point
// (followed only where something asks: --suggest until its report is sent, bound_buffers,
// camera.live, a pick that may be a storage image: dispatch_copies.cpp), the sets a pass's draws see
// and the images they may read through them, and what is read between passes (compute dispatches,
// copy/blit/resolve sources) or copied into a swapchain image; image ids; push constants for
// bound_buffers and camera.live; the --suggest report of a pass. The draw, dispatch, copy and
// push-constant hooks are handed out only to a device whose request asks for them
// (structureHooks): a plain stream never calls them.
#include <algorithm>
#include <cstring>

#include "app/layer/layer.h"

namespace gbl {

uint32_t imageId(DeviceData& d, VkImage image) {
  std::lock_guard lock(d.idLock);
  auto [it, added] = d.imageIds.try_emplace(image, 0);
  if (added) it->second = ++d.nextImageId;
  return it->second;
}

void forgetImageId(DeviceData& d, VkImage image) {
  std::lock_guard lock(d.idLock);
  d.imageIds.erase(image);  // a later image with this handle is another image
}

bool passMatches(const PassPick& p, const OpenPass& pass) {
  if (p.passIndex >= 0 && p.passIndex != pass.ordinal) return false;
  return p.pass.empty() || p.pass == pass.renderPass ||
         std::find(pass.labels.begin(), pass.labels.end(), p.pass) != pass.labels.end();
}

void beginPassBinds(CmdState& s) {
  s.passBinds.clear();
  s.keepPassBinds = s.passBindsOf == -1 || s.passBindsOf == s.open.ordinal;
  for (BoundSet& b : s.graphicsSets) b.fresh = true;  // bound before the pass began: seen by its first draw
}

namespace {

void addOnce(std::vector<uint32_t>& ids, uint32_t id) {
  if (std::find(ids.begin(), ids.end(), id) == ids.end()) ids.push_back(id);
}

// The ids of the followed images (attachments, swapchains) the image descriptors of these sets view.
void readsOf(DeviceData& d, const std::vector<BindEvent>& binds, std::vector<uint32_t>& ids) {
  std::shared_lock lock(d.objects);
  std::vector<BoundDescriptor> all;
  for (const BindEvent& b : binds) boundDescriptors(d, b.number, b.set, all);
  for (const BoundDescriptor& desc : all) {
    if (!imageDescriptor(desc.type) || !desc.view) continue;
    auto v = d.views.find(desc.view);
    if (v != d.views.end() && d.images.count(v->second.image)) addOnce(ids, imageId(d, v->second.image));
  }
}

// A recording's state while --suggest still follows the frame, else null (the fast way out).
CmdState* following(DeviceData& d, VkCommandBuffer cmd) {
  if (d.suggestSent) return nullptr;
  CmdState* s = cmdState(d, cmd);
  return s && s->suggest ? s : nullptr;
}

// Read between passes: after the last pass this recording ended (or before its first).
void readAfter(CmdState& s, uint32_t id) {
  if (s.inPass) return;  // (a copy or dispatch cannot be inside a render pass)
  addOnce(s.reports.empty() ? s.leadingReads : s.reports.back().readsAfter, id);
}

// An image copy, blit or resolve: its source is read; a swapchain destination presents it.
void imageCopy(DeviceData& d, VkCommandBuffer cmd, VkImage src, VkImage dst) {
  CmdState* s = following(d, cmd);
  if (!s) return;
  bool followed = false, intoSwapchain = false;
  {
    std::shared_lock lock(d.objects);
    followed = d.images.count(src) > 0;
    auto out = d.images.find(dst);
    intoSwapchain = out != d.images.end() && out->second.swapchain;
  }
  if (!followed) return;
  const uint32_t id = imageId(d, src);
  readAfter(*s, id);
  if (intoSwapchain) addOnce(s->intoSwapchain, id);
}

// A followed image as the report shows it (the caller holds d.objects).
PassReport::Attachment describeImage(DeviceData& d, VkImage image, const ImageInfo& info, const ViewInfo* view) {
  PassReport::Attachment e;
  e.image = info.name;
  e.view = view ? view->name : "";
  const uint32_t mip = view ? view->mip : 0;
  e.width = std::max(1u, info.extent.width >> mip);
  e.height = std::max(1u, info.extent.height >> mip);
  e.samples = uint32_t(info.samples);
  e.format = formatName(info.format);
  e.storage = formatInfo(info.format).storage;
  e.depth = formatInfo(info.format).depth;
  e.stencil = formatInfo(info.format).stencil;
  e.presented = info.swapchain != VK_NULL_HANDLE;
  e.imageId = imageId(d, image);
  e.why = refusal(d, info, "");
  return e;
}

// The storage images a dispatch binds, each once between two passes, where it binds them.
void noteStorage(DeviceData& d, CmdState& s, const std::vector<BindEvent>& binds) {
  std::vector<PassReport::Storage>& list = s.reports.empty() ? s.leadingStorage : s.reports.back().storageAfter;
  std::shared_lock lock(d.objects);
  std::vector<BoundDescriptor> all;
  for (const BindEvent& b : binds) boundDescriptors(d, b.number, b.set, all);
  for (const BoundDescriptor& desc : all) {
    if (desc.type != VK_DESCRIPTOR_TYPE_STORAGE_IMAGE || !desc.view) continue;
    auto v = d.views.find(desc.view);
    auto img = v == d.views.end() ? d.images.end() : d.images.find(v->second.image);
    if (img == d.images.end()) continue;
    PassReport::Storage e{describeImage(d, img->first, img->second, &v->second), desc.set, desc.binding, s.labels};
    e.image.role = "storage";
    addStorageOnce(list, e);
  }
}

void dispatched(DeviceData& d, VkCommandBuffer cmd) {
  if (CmdState* c = cmdState(d, cmd); c && c->copies && c->trackBinds) dispatchCopies(d, cmd, *c);
  CmdState* s = following(d, cmd);
  if (!s) return;
  std::vector<BindEvent> binds;
  for (uint32_t n = 0; n < s->computeSets.size(); ++n)
    if (s->computeSets[n].bound()) binds.push_back({n, s->computeSets[n]});
  std::vector<uint32_t> ids;
  readsOf(d, binds, ids);
  for (uint32_t id : ids) readAfter(*s, id);
  noteStorage(d, *s, binds);
}

// The camera's buffer by its debug name: the last one of that name bound before the pass ends
// (the caller holds d.objects).
void noteCamera(DeviceData& d, CmdState& s, const std::string& name, const std::vector<BoundDescriptor>& bound) {
  for (const BoundDescriptor& desc : bound) {
    auto info = desc.buffer ? d.buffers.find(desc.buffer) : d.buffers.end();
    if (info != d.buffers.end() && info->second.name == name) s.cameraBuffer = desc.buffer;
  }
}

// The camera's debug name when this recording copies and the request names one, else "".
std::string cameraName(DeviceData& d, const CmdState& s) {
  std::shared_ptr<const Request> req = s.copies ? currentRequest(d) : nullptr;
  return req ? req->cameraBuffer : std::string();
}

VKAPI_ATTR void VKAPI_CALL CmdBindDescriptorSets(VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipelineLayout layout,
                                                 uint32_t first, uint32_t count, const VkDescriptorSet* sets,
                                                 uint32_t dynamicCount, const uint32_t* dynamicOffsets) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdBindDescriptorSets(cmd, point, layout, first, count, sets, dynamicCount, dynamicOffsets);
  CmdState* s = cmdState(d, cmd);
  if (!s) return;
  if (const std::string camera = cameraName(d, *s); !camera.empty()) {
    std::vector<BoundDescriptor> all;
    std::shared_lock lock(d.objects);
    for (uint32_t i = 0; i < count; ++i) boundDescriptors(d, first + i, BoundSet{sets[i], {}, nullptr}, all);
    noteCamera(d, *s, camera, all);
  }
  if (!s->trackBinds || (point != VK_PIPELINE_BIND_POINT_GRAPHICS && point != VK_PIPELINE_BIND_POINT_COMPUTE)) return;
  std::vector<BoundSet> bound = splitDynamicOffsets(d, count, sets, dynamicCount, dynamicOffsets);
  std::vector<BoundSet>& table = point == VK_PIPELINE_BIND_POINT_GRAPHICS ? s->graphicsSets : s->computeSets;
  if (table.size() < first + count) table.resize(first + count);
  for (uint32_t i = 0; i < count; ++i) {
    table[first + i] = std::move(bound[i]);
    table[first + i].fresh = true;
  }
}

// Push descriptors: the set number's pushed descriptors, bindings pushed again replaced.
void pushDescriptors(DeviceData& d, VkCommandBuffer cmd, VkPipelineBindPoint point, uint32_t set,
                     std::vector<BoundDescriptor> descs) {
  CmdState* s = cmdState(d, cmd);
  if (const std::string camera = s ? cameraName(d, *s) : ""; !camera.empty()) {
    std::shared_lock lock(d.objects);
    noteCamera(d, *s, camera, descs);
  }
  if (!s || !s->trackBinds || (point != VK_PIPELINE_BIND_POINT_GRAPHICS && point != VK_PIPELINE_BIND_POINT_COMPUTE)) return;
  std::vector<BoundSet>& table = point == VK_PIPELINE_BIND_POINT_GRAPHICS ? s->graphicsSets : s->computeSets;
  if (table.size() <= set) table.resize(set + 1);
  if (table[set].pushed)
    for (const BoundDescriptor& old : *table[set].pushed)
      if (std::none_of(descs.begin(), descs.end(), [&](const BoundDescriptor& b) { return b.binding == old.binding && b.index == old.index; }))
        descs.push_back(old);
  BoundSet bound;
  bound.pushed = std::make_shared<const std::vector<BoundDescriptor>>(std::move(descs));
  bound.fresh = true;
  table[set] = std::move(bound);
}

VKAPI_ATTR void VKAPI_CALL CmdPushDescriptorSetKHR(VkCommandBuffer cmd, VkPipelineBindPoint point, VkPipelineLayout layout,
                                                   uint32_t set, uint32_t count, const VkWriteDescriptorSet* writes) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdPushDescriptorSetKHR(cmd, point, layout, set, count, writes);
  pushDescriptors(d, cmd, point, set, pushedDescriptors(count, writes));
}

VKAPI_ATTR void VKAPI_CALL CmdPushDescriptorSetWithTemplateKHR(VkCommandBuffer cmd, VkDescriptorUpdateTemplate t,
                                                               VkPipelineLayout layout, uint32_t set, const void* data) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdPushDescriptorSetWithTemplateKHR(cmd, t, layout, set, data);
  // The template says its bind point (VkDescriptorUpdateTemplateCreateInfo::pipelineBindPoint).
  VkPipelineBindPoint point = VK_PIPELINE_BIND_POINT_MAX_ENUM;
  {
    std::shared_lock lock(d.objects);
    auto it = d.templates.find(t);
    if (it != d.templates.end()) point = it->second.bindPoint;
  }
  pushDescriptors(d, cmd, point, set, pushedDescriptors(d, t, data));
}

// Push constants the graphics stages see, for bound_buffers and camera.live (streamed recordings only).
VKAPI_ATTR void VKAPI_CALL CmdPushConstants(VkCommandBuffer cmd, VkPipelineLayout layout, VkShaderStageFlags stages,
                                            uint32_t offset, uint32_t size, const void* values) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdPushConstants(cmd, layout, stages, offset, size, values);
  if (!(stages & VK_SHADER_STAGE_ALL_GRAPHICS) || uint64_t(offset) + size > 4096) return;
  CmdState* s = cmdState(d, cmd);
  if (!s || !s->copies) return;
  if (s->push.bytes.size() < offset + size) s->push.bytes.resize(offset + size);
  std::memcpy(s->push.bytes.data() + offset, values, size);
  s->push.lo = std::min(s->push.lo, offset);
  s->push.hi = std::max(s->push.hi, offset + size);
}

// A draw of the open pass: the graphics sets bound since its last draw are what it reads.
void drawn(DeviceData& d, VkCommandBuffer cmd) {
  if (d.suggestSent && !d.boundBuffersAsked) return;
  CmdState* s = cmdState(d, cmd);
  if (!s || !s->inPass || !s->keepPassBinds) return;
  for (uint32_t n = 0; n < s->graphicsSets.size(); ++n)
    if (BoundSet& b = s->graphicsSets[n]; b.fresh && b.bound()) {
      s->passBinds.push_back({n, b});
      b.fresh = false;
    }
}

#define GBL_DRAW(name, params, args)                       \
  VKAPI_ATTR void VKAPI_CALL name params {                 \
    DeviceData& d = *deviceOf(cmd);                        \
    d.vk.name args;                                        \
    drawn(d, cmd);                                         \
  }
GBL_DRAW(CmdDraw, (VkCommandBuffer cmd, uint32_t a, uint32_t b, uint32_t c, uint32_t e), (cmd, a, b, c, e))
GBL_DRAW(CmdDrawIndexed, (VkCommandBuffer cmd, uint32_t a, uint32_t b, uint32_t c, int32_t v, uint32_t e), (cmd, a, b, c, v, e))
GBL_DRAW(CmdDrawIndirect, (VkCommandBuffer cmd, VkBuffer b, VkDeviceSize o, uint32_t n, uint32_t s), (cmd, b, o, n, s))
GBL_DRAW(CmdDrawIndexedIndirect, (VkCommandBuffer cmd, VkBuffer b, VkDeviceSize o, uint32_t n, uint32_t s), (cmd, b, o, n, s))
GBL_DRAW(CmdDrawIndirectCount, (VkCommandBuffer cmd, VkBuffer b, VkDeviceSize o, VkBuffer c, VkDeviceSize co, uint32_t n, uint32_t s),
         (cmd, b, o, c, co, n, s))
GBL_DRAW(CmdDrawIndirectCountKHR, (VkCommandBuffer cmd, VkBuffer b, VkDeviceSize o, VkBuffer c, VkDeviceSize co, uint32_t n, uint32_t s),
         (cmd, b, o, c, co, n, s))
GBL_DRAW(CmdDrawIndexedIndirectCount,
         (VkCommandBuffer cmd, VkBuffer b, VkDeviceSize o, VkBuffer c, VkDeviceSize co, uint32_t n, uint32_t s), (cmd, b, o, c, co, n, s))
GBL_DRAW(CmdDrawIndexedIndirectCountKHR,
         (VkCommandBuffer cmd, VkBuffer b, VkDeviceSize o, VkBuffer c, VkDeviceSize co, uint32_t n, uint32_t s), (cmd, b, o, c, co, n, s))
GBL_DRAW(CmdDrawMeshTasksEXT, (VkCommandBuffer cmd, uint32_t x, uint32_t y, uint32_t z), (cmd, x, y, z))
GBL_DRAW(CmdDrawMeshTasksIndirectEXT, (VkCommandBuffer cmd, VkBuffer b, VkDeviceSize o, uint32_t n, uint32_t s), (cmd, b, o, n, s))
#undef GBL_DRAW

VKAPI_ATTR void VKAPI_CALL CmdDispatch(VkCommandBuffer cmd, uint32_t x, uint32_t y, uint32_t z) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdDispatch(cmd, x, y, z);
  dispatched(d, cmd);
}
VKAPI_ATTR void VKAPI_CALL CmdDispatchIndirect(VkCommandBuffer cmd, VkBuffer buffer, VkDeviceSize offset) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdDispatchIndirect(cmd, buffer, offset);
  dispatched(d, cmd);
}
VKAPI_ATTR void VKAPI_CALL CmdDispatchBase(VkCommandBuffer cmd, uint32_t bx, uint32_t by, uint32_t bz, uint32_t x, uint32_t y,
                                           uint32_t z) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdDispatchBase(cmd, bx, by, bz, x, y, z);
  dispatched(d, cmd);
}
VKAPI_ATTR void VKAPI_CALL CmdDispatchBaseKHR(VkCommandBuffer cmd, uint32_t bx, uint32_t by, uint32_t bz, uint32_t x,
                                              uint32_t y, uint32_t z) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdDispatchBaseKHR(cmd, bx, by, bz, x, y, z);
  dispatched(d, cmd);
}

VKAPI_ATTR void VKAPI_CALL CmdCopyImage(VkCommandBuffer cmd, VkImage src, VkImageLayout srcLayout, VkImage dst,
                                        VkImageLayout dstLayout, uint32_t n, const VkImageCopy* regions) {
  DeviceData& d = *deviceOf(cmd);
  flushBeforeWrite(cmd);
  d.vk.CmdCopyImage(cmd, src, srcLayout, dst, dstLayout, n, regions);
  imageCopy(d, cmd, src, dst);
}
VKAPI_ATTR void VKAPI_CALL CmdBlitImage(VkCommandBuffer cmd, VkImage src, VkImageLayout srcLayout, VkImage dst,
                                        VkImageLayout dstLayout, uint32_t n, const VkImageBlit* regions, VkFilter filter) {
  DeviceData& d = *deviceOf(cmd);
  flushBeforeWrite(cmd);
  d.vk.CmdBlitImage(cmd, src, srcLayout, dst, dstLayout, n, regions, filter);
  imageCopy(d, cmd, src, dst);
}
VKAPI_ATTR void VKAPI_CALL CmdResolveImage(VkCommandBuffer cmd, VkImage src, VkImageLayout srcLayout, VkImage dst,
                                           VkImageLayout dstLayout, uint32_t n, const VkImageResolve* regions) {
  DeviceData& d = *deviceOf(cmd);
  flushBeforeWrite(cmd);
  d.vk.CmdResolveImage(cmd, src, srcLayout, dst, dstLayout, n, regions);
  imageCopy(d, cmd, src, dst);
}
VKAPI_ATTR void VKAPI_CALL CmdCopyImageToBuffer(VkCommandBuffer cmd, VkImage src, VkImageLayout layout, VkBuffer dst,
                                                uint32_t n, const VkBufferImageCopy* regions) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdCopyImageToBuffer(cmd, src, layout, dst, n, regions);
  imageCopy(d, cmd, src, VK_NULL_HANDLE);
}

// The Vulkan 1.3 / KHR forms: the same, their images in an info struct.
#define GBL_COPY2(name, Info, dstImage)                                          \
  VKAPI_ATTR void VKAPI_CALL name(VkCommandBuffer cmd, const Info* info) {       \
    DeviceData& d = *deviceOf(cmd);                                              \
    flushBeforeWrite(cmd);                                                       \
    d.vk.name(cmd, info);                                                        \
    imageCopy(d, cmd, info->srcImage, dstImage);                                 \
  }
GBL_COPY2(CmdCopyImage2, VkCopyImageInfo2, info->dstImage)
GBL_COPY2(CmdCopyImage2KHR, VkCopyImageInfo2, info->dstImage)
GBL_COPY2(CmdBlitImage2, VkBlitImageInfo2, info->dstImage)
GBL_COPY2(CmdBlitImage2KHR, VkBlitImageInfo2, info->dstImage)
GBL_COPY2(CmdResolveImage2, VkResolveImageInfo2, info->dstImage)
GBL_COPY2(CmdResolveImage2KHR, VkResolveImageInfo2, info->dstImage)
GBL_COPY2(CmdCopyImageToBuffer2, VkCopyImageToBufferInfo2, VK_NULL_HANDLE)
GBL_COPY2(CmdCopyImageToBuffer2KHR, VkCopyImageToBufferInfo2, VK_NULL_HANDLE)
#undef GBL_COPY2

}  // namespace

std::vector<uint32_t> passReads(DeviceData& d, const CmdState& s) {
  std::vector<uint32_t> ids;
  readsOf(d, s.passBinds, ids);
  return ids;
}

std::vector<Hook> bindHooks() {
  return {GBL_HOOK(CmdBindDescriptorSets), GBL_HOOK(CmdPushDescriptorSetKHR), GBL_HOOK(CmdPushDescriptorSetWithTemplateKHR)};
}

std::vector<Hook> structureHooks(const Request& req) {
  std::vector<Hook> hooks;
  // --suggest follows dispatches and image copies; a pick that may be a storage image needs the
  // dispatches (copies after them) and every command that may write an image (the pending copies
  // go first).
  if (req.suggest || req.storagePicks)
    hooks = {GBL_HOOK(CmdDispatch),      GBL_HOOK(CmdDispatchIndirect),   GBL_HOOK(CmdDispatchBase),
             GBL_HOOK(CmdDispatchBaseKHR), GBL_HOOK(CmdCopyImage),        GBL_HOOK(CmdCopyImage2),
             GBL_HOOK(CmdCopyImage2KHR), GBL_HOOK(CmdBlitImage),          GBL_HOOK(CmdBlitImage2),
             GBL_HOOK(CmdBlitImage2KHR), GBL_HOOK(CmdResolveImage),       GBL_HOOK(CmdResolveImage2),
             GBL_HOOK(CmdResolveImage2KHR), GBL_HOOK(CmdCopyImageToBuffer), GBL_HOOK(CmdCopyImageToBuffer2),
             GBL_HOOK(CmdCopyImageToBuffer2KHR)};
  if (req.storagePicks) {
    const std::vector<Hook> writers = storageWriterHooks();
    hooks.insert(hooks.end(), writers.begin(), writers.end());
  }
  if (req.suggest || req.boundBuffers.on)
    for (const Hook& h : {GBL_HOOK(CmdDraw), GBL_HOOK(CmdDrawIndexed), GBL_HOOK(CmdDrawIndirect), GBL_HOOK(CmdDrawIndexedIndirect),
                          GBL_HOOK(CmdDrawIndirectCount), GBL_HOOK(CmdDrawIndirectCountKHR), GBL_HOOK(CmdDrawIndexedIndirectCount),
                          GBL_HOOK(CmdDrawIndexedIndirectCountKHR), GBL_HOOK(CmdDrawMeshTasksEXT), GBL_HOOK(CmdDrawMeshTasksIndirectEXT)})
      hooks.push_back(h);
  if (req.boundBuffers.on || (req.liveCamera.on && req.cameraPushConstants)) hooks.push_back(GBL_HOOK(CmdPushConstants));
  return hooks;
}

void addStorageOnce(std::vector<PassReport::Storage>& list, const PassReport::Storage& e) {
  if (std::none_of(list.begin(), list.end(), [&](const PassReport::Storage& b) { return b.image.imageId == e.image.imageId; }))
    list.push_back(e);
}

PassReport reportPass(DeviceData& d, const OpenPass& pass) {
  PassReport r;
  r.ordinal = pass.ordinal;
  r.dynamic = pass.dynamic;
  r.renderPass = pass.renderPass;
  r.labels = pass.labels;
  std::shared_lock lock(d.objects);
  for (const PassAttachment& a : pass.attachments) {
    auto img = d.images.find(a.image);
    auto view = d.views.find(a.view);
    if (img == d.images.end()) continue;
    PassReport::Attachment e = describeImage(d, a.image, img->second, view == d.views.end() ? nullptr : &view->second);
    e.role = a.color >= 0 ? "color " + std::to_string(a.color) : a.depth ? "depth" : "other";
    e.written = a.written;
    e.ops = a.ops;
    r.attachments.push_back(e);
  }
  return r;
}

}  // namespace gbl
