// Compiling a render-pass group, phase by phase: collect uses per subpass -> assign layouts ->
// attachments, load/store ops and the barriers into the pass -> subpasses and dependencies ->
// render pass and framebuffer (cached by typed keys).
#include "renderer/graph/graph_compile.h"

#include <algorithm>
#include <cstring>

#include "renderer/graph/graph.h"
#include "renderer/vk/check.h"

namespace gb {

using namespace graph_sync;

namespace {

// How a target is used in one subpass.
struct SubUse {
  bool used = false, color = false, depth = false, input = false, clear = false;
  Access depthAccess = Access::DepthStencilRead;
  VkPipelineStageFlags2 stage = 0;
  VkAccessFlags2 access = 0;
  bool write = false;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkClearValue clearValue{};
};
using SubUses = std::vector<std::array<SubUse, kTargetCount>>;

// Phase 1: every declared use, merged per subpass and target; colour attachments in the order
// their passes first declare them.
void collectUses(const GraphGroup& group, const std::vector<GraphPass>& passes, const GraphTargets& targets,
                 SubUses& sub, std::vector<std::vector<Target>>& colorOrder) {
  for (int pi : group.passes) {
    const GraphPass& p = passes[size_t(pi)];
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
}

// Phase 2: the layout of each target in each subpass.
void assignLayouts(SubUses& sub, const GraphTargets& targets) {
  for (auto& subpass : sub)
    for (size_t ti = 0; ti < kTargetCount; ++ti) {
      SubUse& s = subpass[ti];
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
}

// The attachment index of each target (-1: not an attachment): every target used as colour,
// depth or input attachment in some subpass.
std::array<int, kTargetCount> attachmentIndices(const SubUses& sub) {
  std::array<int, kTargetCount> index;
  index.fill(-1);
  int n = 0;
  for (size_t ti = 0; ti < kTargetCount; ++ti)
    for (const auto& subpass : sub)
      if (subpass[ti].color || subpass[ti].depth || subpass[ti].input) {
        index[ti] = n++;
        break;
      }
  return index;
}

// Phase 3 for one attachment: load/store ops. Aspects the render pass never writes are not
// stored at all (STORE_OP_NONE): a store would be a write racing with this pass's own reads.
// `storeStage`/`storeAccess`: the store happens after the last use, later barriers wait for it.
RenderPassKey::Attachment attachmentOps(const SubUses& sub, size_t ti, uint32_t first, uint32_t last,
                                        const GraphTarget& t, bool store, VkPipelineStageFlags2& storeStage,
                                        VkAccessFlags2& storeAccess) {
  bool colorOrDepthWritten = false, stencilWritten = false;
  for (uint32_t si = first; si <= last; ++si) {
    const SubUse& su = sub[si][ti];
    colorOrDepthWritten |= su.color || (su.depth && su.depthAccess == Access::DepthStencilWrite);
    stencilWritten |= su.depth && su.depthAccess != Access::DepthStencilRead;
  }
  const VkFormat format = t.image.desc.format;
  RenderPassKey::Attachment a{};
  a.format = format;
  a.load = sub[first][ti].clear ? VK_ATTACHMENT_LOAD_OP_CLEAR
                                : (t.layout == VK_IMAGE_LAYOUT_UNDEFINED ? VK_ATTACHMENT_LOAD_OP_DONT_CARE
                                                                         : VK_ATTACHMENT_LOAD_OP_LOAD);
  auto storeOp = [&](bool written) {
    return !written ? VK_ATTACHMENT_STORE_OP_NONE : (store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE);
  };
  a.store = storeOp(colorOrDepthWritten);
  a.stencilStore = hasStencil(format) ? storeOp(stencilWritten) : VK_ATTACHMENT_STORE_OP_DONT_CARE;
  a.initial = sub[first][ti].layout;
  a.final = sub[last][ti].layout;
  if (colorOrDepthWritten || stencilWritten) {
    bool depth = isDepthFormat(format);
    storeStage = depth ? VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT : VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
    storeAccess = depth ? VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT;
  }
  return a;
}

// Phase 3: per used target, the barrier into the render pass and the state after it; the
// attachments with their ops, clear values and views.
void attachmentsAndBarriers(const SubUses& sub, const std::array<int, kTargetCount>& attachment,
                            const GraphTargets& targets, const GroupShape& shape, CompiledGroup& c,
                            RenderPassKey& rpKey, std::vector<VkImageView>& views) {
  const uint32_t nsub = uint32_t(sub.size());
  for (size_t ti = 0; ti < kTargetCount; ++ti) {
    uint32_t first = nsub, last = 0;
    for (uint32_t si = 0; si < nsub; ++si)
      if (sub[si][ti].used) {
        first = std::min(first, si);
        last = si;
      }
    if (first == nsub) continue;
    const GraphTarget& t = targets[ti];
    const SubUse& f = sub[first][ti];
    const SubUse& l = sub[last][ti];
    // Non-attachments keep one layout for the whole render pass.
    if (attachment[ti] < 0)
      for (uint32_t si = first; si <= last; ++si) GB_ASSERT(!sub[si][ti].used || sub[si][ti].layout == f.layout);
    CompiledGroup::TargetStep step;
    step.target = Target(ti);
    step.discard = f.clear || t.layout == VK_IMAGE_LAYOUT_UNDEFINED;
    step.into = {f.layout, 0, 0, false};
    for (uint32_t si = first; si <= last; ++si)
      if (attachment[ti] < 0 || si == first) {
        step.into.stage |= sub[si][ti].stage;
        step.into.access |= sub[si][ti].access;
      }
    step.into.write = f.write;
    // An attachment loaded (not cleared, contents kept) is read by its load op.
    if (attachment[ti] >= 0 && !step.discard)
      step.into.access |= isDepthFormat(t.image.desc.format) ? VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT
                                                             : VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT;
    step.barrier = needsBarrier(t, step.into);
    VkPipelineStageFlags2 storeStage = 0;
    VkAccessFlags2 storeAccess = 0;
    if (attachment[ti] >= 0) {
      const bool store = t.keep || shape.targets[ti].usedAfter;
      rpKey.attachments.push_back(attachmentOps(sub, ti, first, last, t, store, storeStage, storeAccess));
      c.clears.push_back(f.clearValue);
      views.push_back(t.image.view);
      if (c.extent.width == 0) c.extent = {t.image.desc.width, t.image.desc.height};
      GB_ASSERT(c.extent.width == t.image.desc.width && c.extent.height == t.image.desc.height);
    }
    step.afterBarrier = step.barrier || storeStage;
    step.afterLayout = l.layout;
    step.afterStage = l.stage | storeStage;
    step.afterAccess = l.access | storeAccess;
    c.steps.push_back(step);
  }
}

// Phase 4: subpass references and the dependencies between consecutive uses of each target.
void subpassesAndDependencies(GpuContext& ctx, const SubUses& sub, const std::vector<std::vector<Target>>& colorOrder,
                              const std::array<int, kTargetCount>& attachment, RenderPassKey& key) {
  const uint32_t nsub = uint32_t(sub.size());
  std::map<std::pair<uint32_t, uint32_t>, RenderPassKey::Dependency> deps;
  for (uint32_t si = 0; si < nsub; ++si) {
    RenderPassKey::Subpass sp{};
    sp.depth = VK_ATTACHMENT_UNUSED;
    sp.depthLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    for (Target t : colorOrder[si]) sp.color.push_back(uint32_t(attachment[size_t(t)]));
    for (size_t ti = 0; ti < kTargetCount; ++ti) {
      const SubUse& s = sub[si][ti];
      if (s.depth) {
        sp.depth = uint32_t(attachment[ti]);
        sp.depthLayout = s.layout;
      }
      if (s.input) {
        sp.input.push_back(uint32_t(attachment[ti]));
        sp.inputLayouts.push_back(s.layout);
      }
      if (!s.used || si == 0) continue;
      int prev = -1;
      for (int sj = int(si) - 1; sj >= 0 && prev < 0; --sj)
        if (sub[sj][ti].used) prev = sj;
      if (prev < 0) continue;
      const SubUse& p = sub[prev][ti];
      if (!p.write && !s.write && p.layout == s.layout) continue;
      auto [it, fresh] = deps.try_emplace({uint32_t(prev), si}, RenderPassKey::Dependency{});
      RenderPassKey::Dependency& d = it->second;
      if (fresh) {
        d.src = uint32_t(prev);
        d.dst = si;
        d.flags = VK_DEPENDENCY_BY_REGION_BIT;
      }
      d.srcStages |= legacyStages(p.stage);
      d.srcAccess |= legacyAccess(p.access);
      d.dstStages |= legacyStages(s.stage);
      d.dstAccess |= legacyAccess(s.access);
      bool framebufferLocal = (s.color || s.depth || s.input) && (p.color || p.depth || p.input);
      if (!framebufferLocal) d.flags = 0;
    }
    if (ctx.features.rasterOrderAttachmentAccess && !sp.input.empty())
      sp.flags |= VK_SUBPASS_DESCRIPTION_RASTERIZATION_ORDER_ATTACHMENT_COLOR_ACCESS_BIT_EXT;
    key.subpasses.push_back(sp);
  }
  for (auto& [k, d] : deps) key.dependencies.push_back(d);
}

VkRenderPass createRenderPass(GpuContext& ctx, const RenderPassKey& key, const std::string& name) {
  std::vector<VkAttachmentDescription2> descs;
  for (const RenderPassKey::Attachment& a : key.attachments) {
    VkAttachmentDescription2 d{VK_STRUCTURE_TYPE_ATTACHMENT_DESCRIPTION_2};
    d.format = a.format;
    d.samples = VK_SAMPLE_COUNT_1_BIT;
    d.loadOp = a.load;
    d.storeOp = a.store;
    d.stencilLoadOp = hasStencil(a.format) ? a.load : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    d.stencilStoreOp = a.stencilStore;
    d.initialLayout = a.initial;
    d.finalLayout = a.final;
    descs.push_back(d);
  }
  const size_t nsub = key.subpasses.size();
  std::vector<std::vector<VkAttachmentReference2>> colorRefs(nsub), inputRefs(nsub);
  std::vector<VkAttachmentReference2> depthRefs(nsub, {VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2});
  std::vector<VkSubpassDescription2> subpasses(nsub, {VK_STRUCTURE_TYPE_SUBPASS_DESCRIPTION_2});
  for (size_t si = 0; si < nsub; ++si) {
    const RenderPassKey::Subpass& sp = key.subpasses[si];
    for (uint32_t a : sp.color)
      colorRefs[si].push_back({VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, a,
                               VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_IMAGE_ASPECT_COLOR_BIT});
    for (size_t k = 0; k < sp.input.size(); ++k) {
      VkFormat f = key.attachments[sp.input[k]].format;
      inputRefs[si].push_back({VK_STRUCTURE_TYPE_ATTACHMENT_REFERENCE_2, nullptr, sp.input[k], sp.inputLayouts[k],
                               VkImageAspectFlags(isDepthFormat(f) ? VK_IMAGE_ASPECT_DEPTH_BIT : VK_IMAGE_ASPECT_COLOR_BIT)});
    }
    depthRefs[si].attachment = sp.depth;
    if (sp.depth != VK_ATTACHMENT_UNUSED) {
      depthRefs[si].layout = sp.depthLayout;
      depthRefs[si].aspectMask = aspectsOf(key.attachments[sp.depth].format);
    }
    VkSubpassDescription2& sd = subpasses[si];
    sd.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sd.flags = sp.flags;
    sd.colorAttachmentCount = uint32_t(colorRefs[si].size());
    sd.pColorAttachments = colorRefs[si].data();
    sd.inputAttachmentCount = uint32_t(inputRefs[si].size());
    sd.pInputAttachments = inputRefs[si].data();
    sd.pDepthStencilAttachment = sp.depth == VK_ATTACHMENT_UNUSED ? nullptr : &depthRefs[si];
  }
  std::vector<VkSubpassDependency2> deps;
  for (const RenderPassKey::Dependency& d : key.dependencies) {
    VkSubpassDependency2 v{VK_STRUCTURE_TYPE_SUBPASS_DEPENDENCY_2};
    v.srcSubpass = d.src;
    v.dstSubpass = d.dst;
    v.srcStageMask = d.srcStages;
    v.dstStageMask = d.dstStages;
    v.srcAccessMask = d.srcAccess;
    v.dstAccessMask = d.dstAccess;
    v.dependencyFlags = d.flags;
    deps.push_back(v);
  }
  VkRenderPassCreateInfo2 ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO_2};
  ci.attachmentCount = uint32_t(descs.size());
  ci.pAttachments = descs.data();
  ci.subpassCount = uint32_t(nsub);
  ci.pSubpasses = subpasses.data();
  ci.dependencyCount = uint32_t(deps.size());
  ci.pDependencies = deps.data();
  VkRenderPass rp;
  VK_CHECK(vkCreateRenderPass2(ctx.device, &ci, nullptr, &rp));
  setName(ctx, uint64_t(rp), VK_OBJECT_TYPE_RENDER_PASS, name.c_str());
  return rp;
}

// Phase 5: the render pass, its compatibility class and the framebuffer, from the cache.
void renderPassAndFramebuffer(GpuContext& ctx, const RenderPassKey& key, const std::string& name,
                              const std::vector<VkImageView>& views, GraphCache& cache, CompiledGroup& c) {
  VkRenderPass& rp = cache.renderPasses[key];
  if (!rp) rp = createRenderPass(ctx, key, name);
  c.renderPass = rp;
  RenderPassKey compat = key.compatibility();
  auto [cls, fresh] = cache.compatClasses.try_emplace(compat, uint32_t(cache.compatClasses.size()));
  for (uint32_t si = 0; si < uint32_t(key.subpasses.size()); ++si) {
    CompiledGroup::Subpass& s = c.subpasses[si];
    s.colorAttachments = uint32_t(key.subpasses[si].color.size());
    s.compatClass = cls->second;
  }
  VkFramebuffer& fb = cache.framebuffers[FramebufferKey{rp, c.extent.width, c.extent.height, views}];
  if (!fb) {
    VkFramebufferCreateInfo fci{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
    fci.renderPass = rp;
    fci.attachmentCount = uint32_t(views.size());
    fci.pAttachments = views.data();
    fci.width = c.extent.width;
    fci.height = c.extent.height;
    fci.layers = 1;
    VK_CHECK(vkCreateFramebuffer(ctx.device, &fci, nullptr, &fb));
    setName(ctx, uint64_t(fb), VK_OBJECT_TYPE_FRAMEBUFFER, name.c_str());
  }
  c.framebuffer = fb;
}

}  // namespace

RenderPassKey RenderPassKey::compatibility() const {
  RenderPassKey k;
  for (const Attachment& a : attachments)
    k.attachments.push_back({a.format, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_DONT_CARE,
                             VK_ATTACHMENT_STORE_OP_DONT_CARE, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_UNDEFINED});
  k.subpasses = subpasses;
  for (Subpass& s : k.subpasses) {
    s.depthLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    s.inputLayouts.clear();
  }
  // Render passes of more than one subpass are compatible only with identical dependencies:
  // pipelines cached per class must not be reused across frames whose options change them.
  if (subpasses.size() > 1) k.dependencies = dependencies;
  return k;
}

GroupShape groupShape(const GraphGroup& group, const std::vector<GraphPass>& passes, const GraphTargets& targets,
                      const std::function<bool(Target)>& usedAfter) {
  GroupShape shape;
  shape.subpasses = group.subpasses;
  for (int pi : group.passes) {
    const GraphPass& p = passes[size_t(pi)];
    for (const Use& u : p.uses) {
      GroupShape::UseKey k;
      k.subpass = p.subpass;
      k.target = u.target;
      k.access = u.access;
      k.clear = u.clear;
      std::memcpy(k.clearBits.data(), &u.clearValue, sizeof(k.clearBits));
      shape.uses.push_back(k);
      const GraphTarget& t = targets[size_t(u.target)];
      shape.targets[size_t(u.target)] = {t.image.image, t.image.view, t.image.desc.format, t.image.desc.width,
                                         t.image.desc.height, t.layout, t.stage, t.access, t.keep, usedAfter(u.target)};
    }
  }
  return shape;
}

CompiledGroup compileGroup(GpuContext& ctx, const GraphGroup& group, const std::vector<GraphPass>& passes,
                           const GraphTargets& targets, const GroupShape& shape, GraphCache& cache) {
  const uint32_t nsub = group.subpasses;
  SubUses sub(nsub);
  std::vector<std::vector<Target>> colorOrder(nsub);
  collectUses(group, passes, targets, sub, colorOrder);
  assignLayouts(sub, targets);
  const std::array<int, kTargetCount> attachment = attachmentIndices(sub);
  CompiledGroup c;
  c.shape = shape;
  c.subpasses.resize(nsub);
  for (uint32_t si = 0; si < nsub; ++si)
    for (size_t ti = 0; ti < kTargetCount; ++ti) {
      c.subpasses[si].used[ti] = sub[si][ti].used;
      c.subpasses[si].layouts[ti] = sub[si][ti].layout;
    }
  RenderPassKey key;
  std::vector<VkImageView> views;
  attachmentsAndBarriers(sub, attachment, targets, shape, c, key, views);
  subpassesAndDependencies(ctx, sub, colorOrder, attachment, key);
  renderPassAndFramebuffer(ctx, key, group.name, views, cache, c);
  return c;
}

}  // namespace gb
