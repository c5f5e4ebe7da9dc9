// Following command buffers as the application records them: their lifetime, debug labels, and
// render passes (VkRenderPass and dynamic rendering) with their attachments, their load/store ops
// and where they are when the pass ends; at the end of each pass copy.cpp records the copies the
// request asks for (the sets bound and the frame's structure: structure.cpp).
#include <algorithm>

#include "app/layer/layer.h"

namespace gbl {

CmdState* cmdState(DeviceData& d, VkCommandBuffer cmd) {
  std::lock_guard lock(d.cmdLock);
  auto it = d.cmds.find(cmd);
  return it == d.cmds.end() ? nullptr : it->second.get();
}

namespace {

VKAPI_ATTR VkResult VKAPI_CALL AllocateCommandBuffers(VkDevice device, const VkCommandBufferAllocateInfo* info,
                                                      VkCommandBuffer* cmds) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.AllocateCommandBuffers(device, info, cmds);
  if (r == VK_SUCCESS) {
    std::lock_guard lock(d.cmdLock);
    for (uint32_t i = 0; i < info->commandBufferCount; ++i) {
      d.cmds[cmds[i]] = std::make_unique<CmdState>();
      d.cmds[cmds[i]]->pool = info->commandPool;
    }
  }
  return r;
}

VKAPI_ATTR void VKAPI_CALL FreeCommandBuffers(VkDevice device, VkCommandPool pool, uint32_t n, const VkCommandBuffer* cmds) {
  DeviceData& d = *deviceOf(device);
  d.vk.FreeCommandBuffers(device, pool, n, cmds);
  std::lock_guard lock(d.cmdLock);
  for (uint32_t i = 0; i < n; ++i) d.cmds.erase(cmds[i]);
}

VKAPI_ATTR VkResult VKAPI_CALL ResetCommandPool(VkDevice device, VkCommandPool pool, VkCommandPoolResetFlags flags) {
  DeviceData& d = *deviceOf(device);
  VkResult r = d.vk.ResetCommandPool(device, pool, flags);
  std::lock_guard lock(d.cmdLock);
  for (auto& [cmd, s] : d.cmds)
    if (s->pool == pool) s->reset();
  return r;
}

VKAPI_ATTR void VKAPI_CALL DestroyCommandPool(VkDevice device, VkCommandPool pool, const VkAllocationCallbacks* alloc) {
  DeviceData& d = *deviceOf(device);
  d.vk.DestroyCommandPool(device, pool, alloc);
  std::lock_guard lock(d.cmdLock);
  std::erase_if(d.cmds, [&](const auto& c) { return c.second->pool == pool; });
}

VKAPI_ATTR VkResult VKAPI_CALL BeginCommandBuffer(VkCommandBuffer cmd, const VkCommandBufferBeginInfo* info) {
  DeviceData& d = *deviceOf(cmd);
  if (CmdState* s = cmdState(d, cmd)) {
    s->reset();
    std::shared_ptr<const Request> req = currentRequest(d);
    // A command buffer submitted once copies only in the frames streamed (every N); one that may be
    // submitted again (recorded once, e.g. per swapchain image) copies whenever it runs.
    const bool reusable = !(info->flags & VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT);
    // --capture-frame N counts the frames read whole: none is left out for pace.
    s->paced = d.streaming && req && req->onlyFrame < 0 && !reusable &&
               (d.toReceiver >= (d.receiverBusy ? 1 : 2) || (req->paced && !grantLeft(d)));
    s->copies = d.streaming && req && !req->picks.empty() && (reusable || frameDue(*req, d.frame)) && !s->paced;
    s->skipped = d.streaming && req && !req->picks.empty() && !s->copies;
    s->reusable = reusable;
    s->suggest = req && req->suggest && !d.suggestSent;  // the report is of one frame: no tracking after it
    // The sets bound are followed only for what asks for them (a stream of attachments alone does not).
    // A pick by name may be a storage image compute writes: the compute sets say which (dispatch_copies.cpp).
    s->trackBinds = s->suggest || (s->copies && (req->boundBuffers.on || req->storagePicks ||
                                                 (req->liveCamera.on && !req->cameraPushConstants)));
    const bool bound = s->copies && req->boundBuffers.on;
    s->passBindsOf = s->suggest || (bound && !req->boundBuffers.pass.empty()) ? -1 : bound ? req->boundBuffers.passIndex : -2;
  }
  return d.vk.BeginCommandBuffer(cmd, info);
}

VKAPI_ATTR VkResult VKAPI_CALL EndCommandBuffer(VkCommandBuffer cmd) {
  DeviceData& d = *deviceOf(cmd);
  if (CmdState* s = cmdState(d, cmd); s && !s->pendingStorage.empty()) flushStorageCopies(d, cmd, *s);
  return d.vk.EndCommandBuffer(cmd);
}

VKAPI_ATTR VkResult VKAPI_CALL ResetCommandBuffer(VkCommandBuffer cmd, VkCommandBufferResetFlags flags) {
  DeviceData& d = *deviceOf(cmd);
  if (CmdState* s = cmdState(d, cmd)) s->reset();
  return d.vk.ResetCommandBuffer(cmd, flags);
}

VKAPI_ATTR void VKAPI_CALL CmdBeginDebugUtilsLabelEXT(VkCommandBuffer cmd, const VkDebugUtilsLabelEXT* label) {
  DeviceData& d = *deviceOf(cmd);
  if (CmdState* s = d.connected ? cmdState(d, cmd) : nullptr) s->labels.push_back(label && label->pLabelName ? label->pLabelName : "");
  d.vk.CmdBeginDebugUtilsLabelEXT(cmd, label);
}

VKAPI_ATTR void VKAPI_CALL CmdEndDebugUtilsLabelEXT(VkCommandBuffer cmd) {
  DeviceData& d = *deviceOf(cmd);
  if (CmdState* s = d.connected ? cmdState(d, cmd) : nullptr; s && !s->labels.empty()) s->labels.pop_back();
  d.vk.CmdEndDebugUtilsLabelEXT(cmd);
}

// ---- VkRenderPass

void beginRenderPass(DeviceData& d, VkCommandBuffer cmd, const VkRenderPassBeginInfo* info) {
  CmdState* s = cmdState(d, cmd);
  if (!s) return;
  s->open = OpenPass{};
  s->open.ordinal = s->passes++;
  s->open.labels = s->labels;
  s->inPass = true;
  beginPassBinds(*s);
  std::shared_lock lock(d.objects);
  auto rp = d.renderPasses.find(info->renderPass);
  auto fb = d.framebuffers.find(info->framebuffer);
  if (rp == d.renderPasses.end() || fb == d.framebuffers.end()) return;
  s->open.renderPass = rp->second.name;
  s->open.subpassColors = rp->second.subpassColors;
  s->open.subpassDepth = rp->second.subpassDepth;
  std::vector<VkImageView> views = fb->second.views;
  for (auto* n = static_cast<const VkBaseInStructure*>(info->pNext); n; n = n->pNext)
    if (n->sType == VK_STRUCTURE_TYPE_RENDER_PASS_ATTACHMENT_BEGIN_INFO) {  // an imageless framebuffer
      auto* a = reinterpret_cast<const VkRenderPassAttachmentBeginInfo*>(n);
      views.assign(a->pAttachments, a->pAttachments + a->attachmentCount);
    }
  const RenderPassInfo& r = rp->second;
  for (uint32_t a = 0; a < r.attachments.size() && a < views.size(); ++a) {
    auto v = d.views.find(views[a]);
    if (v == d.views.end()) continue;  // not an attachment image the layer follows
    PassAttachment pa;
    pa.image = v->second.image;
    pa.view = views[a];
    pa.attachment = int(a);
    auto c = std::find(r.colors.begin(), r.colors.end(), int(a));
    pa.color = c == r.colors.end() ? -1 : int(c - r.colors.begin());
    pa.depth = r.depth == int(a);
    pa.written = r.attachments[a].written;
    pa.ops = r.attachments[a].ops;
    pa.layout = r.attachments[a].finalLayout;
    pa.stencilLayout = r.attachments[a].stencilFinalLayout;
    s->open.attachments.push_back(pa);
  }
}

// Storage copies pending when a pass begins (s.open just made): before it, as its draws may write them.
void pendingBeforePass(DeviceData& d, VkCommandBuffer cmd) {
  if (CmdState* s = cmdState(d, cmd); s && !s->pendingStorage.empty()) storageBeforePass(d, cmd, *s);
}

void endPass(DeviceData& d, VkCommandBuffer cmd) {
  CmdState* s = cmdState(d, cmd);
  if (!s || !s->inPass) return;
  s->inPass = false;
  for (const std::string& l : s->labels)  // labels pushed inside the pass name it too
    if (std::find(s->open.labels.begin(), s->open.labels.end(), l) == s->open.labels.end()) s->open.labels.push_back(l);
  if (s->suggest) {
    s->reports.push_back(reportPass(d, s->open));
    s->reports.back().reads = passReads(d, *s);
  }
  if (s->copies) recordCopies(d, cmd, *s);
}

VKAPI_ATTR void VKAPI_CALL CmdBeginRenderPass(VkCommandBuffer cmd, const VkRenderPassBeginInfo* info, VkSubpassContents c) {
  DeviceData& d = *deviceOf(cmd);
  beginRenderPass(d, cmd, info);
  pendingBeforePass(d, cmd);
  d.vk.CmdBeginRenderPass(cmd, info, c);
}
VKAPI_ATTR void VKAPI_CALL CmdBeginRenderPass2(VkCommandBuffer cmd, const VkRenderPassBeginInfo* info,
                                               const VkSubpassBeginInfo* sub) {
  DeviceData& d = *deviceOf(cmd);
  beginRenderPass(d, cmd, info);
  pendingBeforePass(d, cmd);
  d.vk.CmdBeginRenderPass2(cmd, info, sub);
}
VKAPI_ATTR void VKAPI_CALL CmdBeginRenderPass2KHR(VkCommandBuffer cmd, const VkRenderPassBeginInfo* info,
                                                  const VkSubpassBeginInfo* sub) {
  DeviceData& d = *deviceOf(cmd);
  beginRenderPass(d, cmd, info);
  pendingBeforePass(d, cmd);
  d.vk.CmdBeginRenderPass2KHR(cmd, info, sub);
}
VKAPI_ATTR void VKAPI_CALL CmdEndRenderPass(VkCommandBuffer cmd) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdEndRenderPass(cmd);
  endPass(d, cmd);
}
VKAPI_ATTR void VKAPI_CALL CmdEndRenderPass2(VkCommandBuffer cmd, const VkSubpassEndInfo* info) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdEndRenderPass2(cmd, info);
  endPass(d, cmd);
}
VKAPI_ATTR void VKAPI_CALL CmdEndRenderPass2KHR(VkCommandBuffer cmd, const VkSubpassEndInfo* info) {
  DeviceData& d = *deviceOf(cmd);
  d.vk.CmdEndRenderPass2KHR(cmd, info);
  endPass(d, cmd);
}

// ---- dynamic rendering: the attachments are in the begin info; DONT_CARE stores are patched here.

bool readOnlyLayout(VkImageLayout l) {
  return l == VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL || l == VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_OPTIMAL ||
         l == VK_IMAGE_LAYOUT_STENCIL_READ_ONLY_OPTIMAL || l == VK_IMAGE_LAYOUT_READ_ONLY_OPTIMAL;
}

void beginRendering(DeviceData& d, VkCommandBuffer cmd, const VkRenderingInfo* info, VkRenderingInfo& patched,
                    std::vector<VkRenderingAttachmentInfo>& colors, VkRenderingAttachmentInfo& depth,
                    VkRenderingAttachmentInfo& stencil) {
  patched = *info;
  colors.assign(info->pColorAttachments, info->pColorAttachments + info->colorAttachmentCount);
  if (info->pDepthAttachment) depth = *info->pDepthAttachment, patched.pDepthAttachment = &depth;
  if (info->pStencilAttachment) stencil = *info->pStencilAttachment, patched.pStencilAttachment = &stencil;
  patched.pColorAttachments = colors.data();
  CmdState* s = cmdState(d, cmd);
  if (!s || (info->flags & VK_RENDERING_RESUMING_BIT)) return;  // a resumed pass goes on as it began
  s->open = OpenPass{};
  s->open.ordinal = s->passes++;
  s->open.labels = s->labels;
  s->open.dynamic = true;
  s->open.suspending = info->flags & VK_RENDERING_SUSPENDING_BIT;
  s->inPass = true;
  beginPassBinds(*s);
  std::shared_lock lock(d.objects);
  // Depth and stencil are separate attachments here, each with its own ops; an aspect the pass does
  // not attach is neither loaded nor stored (NONE).
  auto add = [&](VkRenderingAttachmentInfo& a, int color, bool isDepth, bool isStencil) {
    auto v = d.views.find(a.imageView);
    if (!a.imageView || v == d.views.end()) return;
    const bool written = a.storeOp != VK_ATTACHMENT_STORE_OP_NONE && !readOnlyLayout(a.imageLayout);
    const bool patch = written && a.storeOp == VK_ATTACHMENT_STORE_OP_DONT_CARE;
    auto setOps = [&](AttachmentOps& ops) {
      if (isStencil)
        ops.stencilLoad = a.loadOp, ops.stencilStore = a.storeOp, ops.stencilStorePatched = patch;
      else
        ops.load = a.loadOp, ops.store = a.storeOp, ops.storePatched = patch;
    };
    if (patch) a.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    for (PassAttachment& pa : s->open.attachments)
      if (pa.view == a.imageView) {  // the stencil of the depth attachment's view
        pa.stencilLayout = a.imageLayout;
        pa.written |= written;
        return setOps(pa.ops);
      }
    PassAttachment pa;
    pa.image = v->second.image;
    pa.view = a.imageView;
    pa.attachment = color >= 0 ? color : int(colors.size());  // dynamic rendering: colours, then depth
    pa.color = color;
    pa.depth = isDepth || isStencil;
    pa.written = written;
    pa.ops.load = pa.ops.stencilLoad = VK_ATTACHMENT_LOAD_OP_NONE_EXT;
    pa.ops.store = pa.ops.stencilStore = VK_ATTACHMENT_STORE_OP_NONE;
    setOps(pa.ops);
    pa.layout = pa.stencilLayout = a.imageLayout;
    s->open.attachments.push_back(pa);
  };
  for (uint32_t i = 0; i < colors.size(); ++i) add(colors[i], int(i), false, false);
  if (patched.pDepthAttachment) add(depth, -1, true, false);
  if (patched.pStencilAttachment) add(stencil, -1, false, true);
}

void cmdBeginRendering(PFN_vkCmdBeginRendering next, VkCommandBuffer cmd, const VkRenderingInfo* info) {
  DeviceData& d = *deviceOf(cmd);
  VkRenderingInfo patched;
  std::vector<VkRenderingAttachmentInfo> colors;
  VkRenderingAttachmentInfo depth, stencil;
  beginRendering(d, cmd, info, patched, colors, depth, stencil);
  if (!(info->flags & VK_RENDERING_RESUMING_BIT)) pendingBeforePass(d, cmd);
  next(cmd, &patched);
}
VKAPI_ATTR void VKAPI_CALL CmdBeginRendering(VkCommandBuffer cmd, const VkRenderingInfo* info) {
  cmdBeginRendering(deviceOf(cmd)->vk.CmdBeginRendering, cmd, info);
}
VKAPI_ATTR void VKAPI_CALL CmdBeginRenderingKHR(VkCommandBuffer cmd, const VkRenderingInfo* info) {
  cmdBeginRendering(deviceOf(cmd)->vk.CmdBeginRenderingKHR, cmd, info);
}

void cmdEndRendering(PFN_vkCmdEndRendering next, VkCommandBuffer cmd) {
  DeviceData& d = *deviceOf(cmd);
  next(cmd);
  CmdState* s = cmdState(d, cmd);
  if (s && !s->open.suspending) endPass(d, cmd);  // a suspended pass ends when it is resumed and ended
}
VKAPI_ATTR void VKAPI_CALL CmdEndRendering(VkCommandBuffer cmd) { cmdEndRendering(deviceOf(cmd)->vk.CmdEndRendering, cmd); }
VKAPI_ATTR void VKAPI_CALL CmdEndRenderingKHR(VkCommandBuffer cmd) {
  cmdEndRendering(deviceOf(cmd)->vk.CmdEndRenderingKHR, cmd);
}

}  // namespace

std::vector<Hook> recordHooks() {
  return {GBL_HOOK(AllocateCommandBuffers), GBL_HOOK(FreeCommandBuffers),     GBL_HOOK(ResetCommandPool),
          GBL_HOOK(DestroyCommandPool),     GBL_HOOK(BeginCommandBuffer),     GBL_HOOK(ResetCommandBuffer),     GBL_HOOK(EndCommandBuffer),
          GBL_HOOK(CmdBeginDebugUtilsLabelEXT), GBL_HOOK(CmdEndDebugUtilsLabelEXT),
          GBL_HOOK(CmdBeginRenderPass),     GBL_HOOK(CmdBeginRenderPass2),    GBL_HOOK(CmdBeginRenderPass2KHR),
          GBL_HOOK(CmdEndRenderPass),       GBL_HOOK(CmdEndRenderPass2),      GBL_HOOK(CmdEndRenderPass2KHR),
          GBL_HOOK(CmdBeginRendering),      GBL_HOOK(CmdBeginRenderingKHR),   GBL_HOOK(CmdEndRendering),
          GBL_HOOK(CmdEndRenderingKHR)};
}

}  // namespace gbl
