// FrameGraph: declarations -> render passes, subpass dependencies, load/store ops and barriers.
#include "renderer/graph/graph.h"

#include <algorithm>
#include <sstream>

#include "renderer/graph/graph_sync.h"
#include "renderer/vk/check.h"

namespace gb {

namespace {

void timestamp(VkCommandBuffer cmd, VkQueryPool pool, uint32_t query, bool end) {
  if (pool)
    vkCmdWriteTimestamp2(cmd, end ? VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT : VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT, pool,
                         query);
}

}  // namespace

using namespace graph_sync;

void destroyGraphCache(GpuContext& ctx, GraphCache& cache) {
  clearFramebuffers(ctx, cache);
  for (auto& [k, rp] : cache.renderPasses) vkDestroyRenderPass(ctx.device, rp, nullptr);
  cache.renderPasses.clear();
}

void clearFramebuffers(GpuContext& ctx, GraphCache& cache) {
  for (auto& [k, fb] : cache.framebuffers) vkDestroyFramebuffer(ctx.device, fb, nullptr);
  cache.framebuffers.clear();
}

void FrameGraph::beginRenderPass(std::string name) {
  GB_ASSERT(openGroup_ < 0);
  groups_.push_back({std::move(name), 1, {}});
  openGroup_ = int(groups_.size()) - 1;
}

void FrameGraph::nextSubpass() {
  GB_ASSERT(openGroup_ >= 0);
  groups_[openGroup_].subpasses++;
}

void FrameGraph::endRenderPass() {
  GB_ASSERT(openGroup_ >= 0);
  openGroup_ = -1;
}

void FrameGraph::addPass(std::string name, std::vector<Use> uses, PassFn execute) {
  PassNode node;
  node.name = name;
  node.uses = std::move(uses);
  node.execute = std::move(execute);
  node.renderPass = openGroup_;
  if (openGroup_ >= 0) {
    node.subpass = groups_[openGroup_].subpasses - 1;
    groups_[openGroup_].passes.push_back(int(passes_.size()));
  }
  node.stat = int(stats_.size());
  stats_.push_back({std::move(name), false, "", 0.0});
  passes_.push_back(std::move(node));
}

void FrameGraph::skipPass(std::string name, std::string reason) {
  stats_.push_back({std::move(name), true, std::move(reason), 0.0});
}

bool FrameGraph::usedAfter(Target t, size_t passIndex) const {
  for (size_t i = passIndex + 1; i < passes_.size(); ++i)
    for (const Use& u : passes_[i].uses)
      if (u.target == t) return true;
  return false;
}

void FrameGraph::record(GpuContext& ctx, VkCommandBuffer cmd, GraphTargets& targets, GraphCache& cache,
                        VkQueryPool timestamps) {
  GB_ASSERT(openGroup_ < 0);
  std::vector<VkImageMemoryBarrier2> barriers;
  std::vector<bool> groupDone(groups_.size(), false);
  for (size_t i = 0; i < passes_.size(); ++i) {
    PassNode& p = passes_[i];
    if (p.renderPass >= 0) {
      if (!groupDone[p.renderPass]) recordGroup(ctx, cmd, p.renderPass, targets, cache, timestamps);
      groupDone[p.renderPass] = true;
      continue;
    }
    for (const Use& u : p.uses) {
      GraphTarget& t = targets[size_t(u.target)];
      GB_ASSERT(t.image.image);
      AccessInfo to = accessInfo(u.access, t.image.desc.format);
      const bool barrier = needsBarrier(t, to);
      if (barrier) imageBarrier(barriers, t, u.clear ? VK_IMAGE_LAYOUT_UNDEFINED : t.layout, to);
      afterUse(t, barrier, to.layout, to.stage, to.access);
    }
    flushBarriers(cmd, barriers);
    timestamp(cmd, timestamps, 2 * p.stat, false);
    PassContext pc;
    pc.cmd = cmd;
    for (size_t ti = 0; ti < kTargetCount; ++ti) pc.layouts[ti] = targets[ti].layout;
    if (p.execute) p.execute(pc);
    timestamp(cmd, timestamps, 2 * p.stat + 1, true);
  }
}

void FrameGraph::recordGroup(GpuContext& ctx, VkCommandBuffer cmd, int g, GraphTargets& targets, GraphCache& cache,
                             VkQueryPool timestamps) {
  const Group& group = groups_[g];
  const uint32_t nsub = group.subpasses;

  // Per target, per subpass: how it is used there.
  struct SubUse {
    bool used = false, color = false, depth = false, input = false, clear = false;
    int colorOrder = -1;  // position of first declaration among colour attachments
    Access depthAccess = Access::DepthStencilRead;
    VkPipelineStageFlags2 stage = 0;
    VkAccessFlags2 access = 0;
    bool write = false;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkClearValue clearValue{};
  };
  std::vector<std::array<SubUse, kTargetCount>> sub(nsub);
  std::vector<std::vector<Target>> colorOrder(nsub);
  int lastPass = 0;
  for (int pi : group.passes) {
    const PassNode& p = passes_[pi];
    lastPass = std::max(lastPass, pi);
    for (const Use& u : p.uses) {
      SubUse& s = sub[p.subpass][size_t(u.target)];
      const GraphTarget& t = targets[size_t(u.target)];
      GB_ASSERT(t.image.image);
      AccessInfo info = accessInfo(u.access, t.image.desc.format);
      s.used = true;
      s.stage |= info.stage;
      s.access |= info.access;
      s.write |= info.write;
      if (u.clear && !s.clear) {
        s.clear = true;
        s.clearValue = u.clearValue;
      }
      if (isColorAttachment(u.access) && !s.color) {
        s.color = true;
        colorOrder[p.subpass].push_back(u.target);
      }
      if (isDepthAttachment(u.access)) {
        // The strongest depth use in the subpass decides its layout.
        auto rank = [](Access a) { return a == Access::DepthStencilWrite ? 2 : a == Access::DepthTestStencilWrite ? 1 : 0; };
        if (!s.depth || rank(u.access) > rank(s.depthAccess)) s.depthAccess = u.access;
        s.depth = true;
      }
      if (u.access == Access::InputAttachment) s.input = true;
    }
  }
  // Layout of each target in each subpass.
  for (uint32_t si = 0; si < nsub; ++si)
    for (size_t ti = 0; ti < kTargetCount; ++ti) {
      SubUse& s = sub[si][ti];
      if (!s.used) continue;
      VkFormat f = targets[ti].image.desc.format;
      GB_ASSERT(!(s.color && (s.input || s.depth)));  // a feedback loop: not supported
      if (s.depth)
        s.layout = accessInfo(s.depthAccess, f).layout;  // input/sampled reads share the attachment's layout
      else if (s.color)
        s.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      else if (s.input)
        s.layout = accessInfo(Access::InputAttachment, f).layout;
      else if (s.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT))
        s.layout = VK_IMAGE_LAYOUT_GENERAL;
      else
        s.layout = accessInfo(Access::SampledFragment, f).layout;
    }

  // Attachments: every target used as colour, depth or input attachment in some subpass.
  std::vector<Target> attachments;
  std::array<int, kTargetCount> attachmentIndex;
  attachmentIndex.fill(-1);
  for (size_t ti = 0; ti < kTargetCount; ++ti)
    for (uint32_t si = 0; si < nsub; ++si)
      if (sub[si][ti].color || sub[si][ti].depth || sub[si][ti].input) {
        attachmentIndex[ti] = int(attachments.size());
        attachments.push_back(Target(ti));
        break;
      }

  std::vector<VkAttachmentDescription2> descs;
  std::vector<VkClearValue> clears;
  std::vector<VkImageView> views;
  std::vector<VkImageMemoryBarrier2> barriers;
  std::ostringstream key, compat;
  VkExtent2D extent{0, 0};
  std::array<VkPipelineStageFlags2, kTargetCount> storeStage{};
  std::array<VkAccessFlags2, kTargetCount> storeAccess{};
  for (size_t ti = 0; ti < kTargetCount; ++ti) {
    uint32_t first = nsub, last = 0;
    for (uint32_t si = 0; si < nsub; ++si)
      if (sub[si][ti].used) {
        first = std::min(first, si);
        last = si;
      }
    if (first == nsub) continue;
    GraphTarget& t = targets[ti];
    const SubUse& f = sub[first][ti];
    const SubUse& l = sub[last][ti];
    // Non-attachments keep one layout for the whole render pass.
    if (attachmentIndex[ti] < 0)
      for (uint32_t si = first; si <= last; ++si) GB_ASSERT(!sub[si][ti].used || sub[si][ti].layout == f.layout);
    bool discard = f.clear || t.layout == VK_IMAGE_LAYOUT_UNDEFINED;
    AccessInfo into{f.layout, 0, 0, false};
    for (uint32_t si = first; si <= last; ++si)
      if (attachmentIndex[ti] < 0 || si == first) {
        into.stage |= sub[si][ti].stage;
        into.access |= sub[si][ti].access;
      }
    into.write = f.write;
    const bool barrier = needsBarrier(t, into);
    if (barrier) imageBarrier(barriers, t, discard ? VK_IMAGE_LAYOUT_UNDEFINED : t.layout, into);

    if (attachmentIndex[ti] >= 0) {
      bool store = t.keep || usedAfter(Target(ti), size_t(lastPass));
      // Aspects the render pass never writes are not stored at all (STORE_OP_NONE): a store
      // would be a write racing with this pass's own reads of them.
      bool colorOrDepthWritten = false, stencilWritten = false;
      for (uint32_t si = first; si <= last; ++si) {
        const SubUse& su = sub[si][ti];
        colorOrDepthWritten |= su.color || (su.depth && su.depthAccess == Access::DepthStencilWrite);
        stencilWritten |= su.depth && su.depthAccess != Access::DepthStencilRead;
      }
      VkAttachmentDescription2 d{VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2};
      d.format = t.image.desc.format;
      d.samples = VK_SAMPLE_COUNT_1_BIT;
      d.loadOp = f.clear ? VK_ATTACHMENT_LOAD_OP_CLEAR
                         : (t.layout == VK_IMAGE_LAYOUT_UNDEFINED ? VK_ATTACHMENT_LOAD_OP_DONT_CARE
                                                                  : VK_ATTACHMENT_LOAD_OP_LOAD);
      auto storeOp = [&](bool written) {
        return !written ? VK_ATTACHMENT_STORE_OP_NONE
                        : (store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE);
      };
      d.storeOp = storeOp(colorOrDepthWritten);
      d.stencilLoadOp = hasStencil(d.format) ? d.loadOp : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
      d.stencilStoreOp = hasStencil(d.format) ? storeOp(stencilWritten) : VK_ATTACHMENT_STORE_OP_DONT_CARE;
      // The store happens after the last use: later barriers must wait for it.
      if (colorOrDepthWritten || stencilWritten) {
        bool depth = isDepthFormat(d.format);
        storeStage[ti] = depth ? VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT : VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
        storeAccess[ti] = depth ? VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
      }
      d.initialLayout = f.layout;
      d.finalLayout = l.layout;
      descs.push_back(d);
      clears.push_back(f.clearValue);
      views.push_back(t.image.view);
      key << targetName(Target(ti)) << ':' << d.format << ':' << d.loadOp << d.storeOp << d.stencilStoreOp << ':' << d.initialLayout
          << '>' << d.finalLayout << ';';
      compat << d.format << ';';
      if (extent.width == 0) extent = {t.image.desc.width, t.image.desc.height};
      GB_ASSERT(extent.width == t.image.desc.width && extent.height == t.image.desc.height);
    }
    afterUse(t, barrier || storeStage[ti], l.layout, l.stage | storeStage[ti], l.access | storeAccess[ti]);
  }
  flushBarriers(cmd, barriers);

  // Subpasses and the dependencies between consecutive uses of each target.
  std::vector<std::vector<VkAttachmentReference2>> colorRefs(nsub), inputRefs(nsub);
  std::vector<VkAttachmentReference2> depthRefs(nsub, {VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2});
  std::vector<VkSubpassDescription2> subpasses(nsub, {VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_2});
  std::map<std::pair<uint32_t, uint32_t>, VkSubpassDependency2> deps;
  for (uint32_t si = 0; si < nsub; ++si) {
    for (Target t : colorOrder[si]) {
      VkAttachmentReference2 r{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2};
      r.attachment = uint32_t(attachmentIndex[size_t(t)]);
      r.layout = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
      r.aspectMask = VK_IMAGE_ASPECT_COLOR_BIT;
      colorRefs[si].push_back(r);
    }
    depthRefs[si].attachment = VK_ATTACHMENT_UNUSED;
    for (size_t ti = 0; ti < kTargetCount; ++ti) {
      const SubUse& s = sub[si][ti];
      if (s.depth) {
        depthRefs[si].attachment = uint32_t(attachmentIndex[ti]);
        depthRefs[si].layout = s.layout;
        depthRefs[si].aspectMask = aspectsOf(targets[ti].image.desc.format);
      }
      if (s.input) {
        VkAttachmentReference2 r{VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2};
        r.attachment = uint32_t(attachmentIndex[ti]);
        r.layout = s.layout;
        r.aspectMask = isDepthFormat(targets[ti].image.desc.format) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT;
        inputRefs[si].push_back(r);
      }
      if (!s.used || si == 0) continue;
      int prev = -1;
      for (int sj = int(si) - 1; sj >= 0; --sj)
        if (sub[sj][ti].used) {
          prev = sj;
          break;
        }
      if (prev < 0) continue;
      const SubUse& p = sub[prev][ti];
      if (!p.write && !s.write && p.layout == s.layout) continue;
      auto [it, fresh] = deps.try_emplace({uint32_t(prev), si}, VkSubpassDependency2{VK_STRUCTURE_TYPE_SUBPASS_DEPENDENCY_2});
      VkSubpassDependency2& d = it->second;
      if (fresh) {
        d.srcSubpass = uint32_t(prev);
        d.dstSubpass = si;
        d.dependencyFlags = VK_DEPENDENCY_BY_REGION_BIT;
      }
      d.srcStageMask |= legacyStages(p.stage);
      d.srcAccessMask |= legacyAccess(p.access);
      d.dstStageMask |= legacyStages(s.stage);
      d.dstAccessMask |= legacyAccess(s.access);
      bool framebufferLocal = (s.color || s.depth || s.input) && (p.color || p.depth || p.input);
      if (!framebufferLocal) d.dependencyFlags = 0;
    }
    VkSubpassDescription2& sd = subpasses[si];
    sd.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sd.colorAttachmentCount = uint32_t(colorRefs[si].size());
    sd.pColorAttachments = colorRefs[si].data();
    sd.inputAttachmentCount = uint32_t(inputRefs[si].size());
    sd.pInputAttachments = inputRefs[si].data();
    sd.pDepthStencilAttachment = depthRefs[si].attachment == VK_ATTACHMENT_UNUSED ? nullptr : &depthRefs[si];
    if (ctx.features.rasterOrderAttachmentAccess && !inputRefs[si].empty())
      sd.flags |= VK_SUBPASS_DESCRIPTION_RASTERIZATION_ORDER_ATTACHMENT_COLOR_ACCESS_BIT_EXT;
    key << "|s" << si << ':' << sd.colorAttachmentCount << ':' << sd.inputAttachmentCount << ':'
        << depthRefs[si].attachment << ':' << depthRefs[si].layout;
    compat << "|s" << si << ':';
    for (auto& r : colorRefs[si]) compat << r.attachment << ',';
    compat << 'i';
    for (auto& r : inputRefs[si]) compat << r.attachment << ',';
    compat << 'd' << depthRefs[si].attachment << 'f' << sd.flags;
  }
  std::vector<VkSubpassDependency2> depList;
  for (auto& [k, d] : deps) {
    depList.push_back(d);
    std::ostringstream dep;
    dep << "|d" << d.srcSubpass << '>' << d.dstSubpass << ':' << d.srcStageMask << ':' << d.dstStageMask << ':'
        << d.srcAccessMask << ':' << d.dstAccessMask << ':' << d.dependencyFlags;
    key << dep.str();
    // Render passes of more than one subpass are compatible only with identical dependencies
    // (Vulkan spec, "Render Pass Compatibility"): pipelines cached per compatibility class must
    // not be reused across frames whose options change the dependencies.
    if (nsub > 1) compat << dep.str();
  }

  VkRenderPass& rp = cache.renderPasses[key.str()];
  if (!rp) {
    VkRenderPassCreateInfo2 ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO_2};
    ci.attachmentCount = uint32_t(descs.size());
    ci.pAttachments = descs.data();
    ci.subpassCount = nsub;
    ci.pSubpasses = subpasses.data();
    ci.dependencyCount = uint32_t(depList.size());
    ci.pDependencies = depList.data();
    VK_CHECK(vkCreateRenderPass2(ctx.device, &ci, nullptr, &rp));
    setName(ctx, uint64_t(rp), VK_OBJECT_TYPE_RENDER_PASS, group.name.c_str());
  }
  std::ostringstream fbKey;
  fbKey << key.str() << '#' << extent.width << 'x' << extent.height;
  for (VkImageView v : views) fbKey << ':' << uint64_t(v);
  VkFramebuffer& fb = cache.framebuffers[fbKey.str()];
  if (!fb) {
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = rp;
    fci.attachmentCount = uint32_t(views.size());
    fci.pAttachments = views.data();
    fci.width = extent.width;
    fci.height = extent.height;
    fci.layers = 1;
    VK_CHECK(vkCreateFramebuffer(ctx.device, &fci, nullptr, &fb));
  }

  VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  bi.renderPass = rp;
  bi.framebuffer = fb;
  bi.renderArea = {{0, 0}, extent};
  bi.clearValueCount = uint32_t(clears.size());
  bi.pClearValues = clears.data();
  vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
  for (uint32_t si = 0; si < nsub; ++si) {
    if (si > 0) vkCmdNextSubpass(cmd, VK_SUBPASS_CONTENTS_INLINE);
    for (int pi : group.passes) {
      PassNode& p = passes_[pi];
      if (p.subpass != si) continue;
      timestamp(cmd, timestamps, 2 * p.stat, false);
      PassContext pc;
      pc.cmd = cmd;
      pc.renderPass = rp;
      pc.subpass = si;
      pc.colorAttachments = uint32_t(colorRefs[si].size());
      pc.compatKey = compat.str() + "#" + std::to_string(si);
      pc.extent = extent;
      for (size_t ti = 0; ti < kTargetCount; ++ti) pc.layouts[ti] = sub[si][ti].used ? sub[si][ti].layout : targets[ti].layout;
      if (p.execute) p.execute(pc);
      timestamp(cmd, timestamps, 2 * p.stat + 1, true);
    }
  }
  vkCmdEndRenderPass(cmd);
}

}  // namespace gb
