// FrameGraph: passes and their declarations in frame order; recording (compute/transfer passes with
// their barriers, render-pass groups compiled once per shape by graph_compile.cpp, then executed).
#include "renderer/graph/graph.h"

#include <algorithm>

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
  cache.compatClasses.clear();
}

void clearFramebuffers(GpuContext& ctx, GraphCache& cache) {
  for (auto& [k, fb] : cache.framebuffers) vkDestroyFramebuffer(ctx.device, fb, nullptr);
  cache.framebuffers.clear();
  cache.groups.clear();
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

void FrameGraph::beginSide() {
  GB_ASSERT(!openSide_ && openGroup_ < 0);
  openSide_ = true;
}

void FrameGraph::endSide() {
  GB_ASSERT(openSide_ && openGroup_ < 0);
  openSide_ = false;
}

bool FrameGraph::hasSide() const {
  return std::any_of(passes_.begin(), passes_.end(), [](const GraphPass& p) { return p.side; });
}

std::string FrameGraph::rasterOutsideSide() const {
  for (const GraphGroup& g : groups_)
    if (!g.passes.empty() && !passes_[size_t(g.passes[0])].side) return passes_[size_t(g.passes[0])].name;
  return "";
}

void FrameGraph::addPass(std::string name, std::vector<Use> uses, PassFn execute, std::vector<BufferUse> buffers) {
  GraphPass node;
  node.side = openSide_;
  node.name = name;
  node.uses = std::move(uses);
  node.buffers = std::move(buffers);
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

// Side passes run first (another queue may start them while the previous frame's main part runs):
// that is the frame's order only if no pass before them touches what they touch.
void FrameGraph::checkSideIndependent() const {
  for (size_t i = 0; i < passes_.size(); ++i) {
    if (!passes_[i].side) continue;
    for (size_t j = 0; j < i; ++j) {
      if (passes_[j].side) continue;
      for (const Use& a : passes_[i].uses)
        for (const Use& b : passes_[j].uses) GB_ASSERT(a.target != b.target);
      for (const BufferUse& a : passes_[i].buffers)
        for (const BufferUse& b : passes_[j].buffers) GB_ASSERT(a.buffer != b.buffer);
    }
  }
  for (const GraphGroup& g : groups_)
    for (int pi : g.passes) GB_ASSERT(passes_[size_t(pi)].side == passes_[size_t(g.passes[0])].side);
}

void FrameGraph::record(GpuContext& ctx, VkCommandBuffer cmd, GraphTargets& targets, GraphCache& cache,
                        VkQueryPool timestamps, VkCommandBuffer side) {
  GB_ASSERT(openGroup_ < 0 && !openSide_);
  GB_ASSERT(!side || hasSide());
  if (side) checkSideIndependent();
  buffers_.clear();
  std::vector<bool> groupDone(groups_.size(), false);
  for (bool sidePart : {true, false}) {
    if (sidePart && !side) continue;
    VkCommandBuffer into = sidePart ? side : cmd;
    for (GraphPass& p : passes_) {
      if (side && p.side != sidePart) continue;
      if (p.renderPass < 0) {
        recordCompute(ctx, into, p, targets, timestamps);
      } else if (!groupDone[p.renderPass]) {
        recordGroup(ctx, into, p.renderPass, targets, cache, timestamps);
        groupDone[p.renderPass] = true;
      }
    }
  }
  // Buffers written this frame may be read by the CPU after the fence (counters, read-backs):
  // make the writes visible to the host.
  bool written = false;
  for (const auto& [buffer, state] : buffers_)
    written |= (state.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT)) != 0;
  if (written) hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_MEMORY_WRITE_BIT);
}

// A compute or transfer pass: a barrier into each use that needs one, then the pass.
// A pass's uses of one buffer (say indirect arguments and a storage write) count as one use.
void FrameGraph::bufferBarriers(const GraphPass& p, Barriers& out) {
  std::map<VkBuffer, AccessInfo> combined;
  for (const BufferUse& b : p.buffers) {
    GB_ASSERT(b.buffer);
    const AccessInfo a = bufferAccessInfo(b.access);
    auto [it, fresh] = combined.try_emplace(b.buffer, a);
    if (!fresh) {
      it->second.stage |= a.stage;
      it->second.access |= a.access;
      it->second.write |= a.write;
    }
  }
  for (const auto& [buffer, to] : combined) bufferUse(out, buffer, buffers_[buffer], to);
}

void FrameGraph::recordCompute(GpuContext& ctx, VkCommandBuffer cmd, GraphPass& p, GraphTargets& targets,
                               VkQueryPool timestamps) {
  LabelScope label(ctx, cmd, p.name.c_str());
  Barriers barriers;
  for (const Use& u : p.uses) {
    GraphTarget& t = targets[size_t(u.target)];
    GB_ASSERT(t.image.image);
    AccessInfo to = accessInfo(u.access, t.image.desc.format);
    const bool barrier = needsBarrier(t, to);
    if (barrier) imageBarrier(barriers.images, t, u.clear ? VK_IMAGE_LAYOUT_UNDEFINED : t.layout, to);
    afterUse(t, barrier, to.layout, to.stage, to.access);
  }
  bufferBarriers(p, barriers);
  flushBarriers(cmd, barriers);
  timestamp(cmd, timestamps, 2 * p.stat, false);
  PassContext pc;
  pc.cmd = cmd;
  for (size_t ti = 0; ti < kTargetCount; ++ti) pc.layouts[ti] = targets[ti].layout;
  if (p.execute) p.execute(pc);
  timestamp(cmd, timestamps, 2 * p.stat + 1, true);
}

// A render-pass group: compiled when its shape differs from the last frame's, then executed.
void FrameGraph::recordGroup(GpuContext& ctx, VkCommandBuffer cmd, int g, GraphTargets& targets, GraphCache& cache,
                             VkQueryPool timestamps) {
  const GraphGroup& group = groups_[g];
  int lastPass = 0;
  for (int pi : group.passes) lastPass = std::max(lastPass, pi);
  GroupShape shape = groupShape(group, passes_, targets, [&](Target t) { return usedAfter(t, size_t(lastPass)); });
  std::vector<CompiledGroup>& compiled = cache.groups[group.name];
  auto it = std::find_if(compiled.begin(), compiled.end(), [&](const CompiledGroup& c) { return c.shape == shape; });
  if (it == compiled.end()) {
    constexpr size_t kKept = 2;  // a group's shapes while targets alternate between two frame slots
    if (compiled.size() == kKept) compiled.pop_back();
    compiled.insert(compiled.begin(), compileGroup(ctx, group, passes_, targets, shape, cache));
    cache.compilations++;
  } else {
    if (it != compiled.begin()) std::rotate(compiled.begin(), it, it + 1);  // newest first
    cache.reuses++;
  }
  executeGroup(ctx, cmd, group, compiled.front(), targets, timestamps);
}

// Barriers into the render pass, the targets' new state, and every pass of every subpass.
void FrameGraph::executeGroup(GpuContext& ctx, VkCommandBuffer cmd, const GraphGroup& group, const CompiledGroup& c,
                              GraphTargets& targets, VkQueryPool timestamps) {
  LabelScope groupLabel(ctx, cmd, group.name.c_str());
  Barriers barriers;
  for (const CompiledGroup::TargetStep& s : c.steps) {
    GraphTarget& t = targets[size_t(s.target)];
    if (s.barrier) imageBarrier(barriers.images, t, s.discard ? VK_IMAGE_LAYOUT_UNDEFINED : t.layout, s.into);
    afterUse(t, s.afterBarrier, s.afterLayout, s.afterStage, s.afterAccess);
  }
  // Buffers the group's passes read (light lists, indirect arguments): barriers before the
  // render pass begins (a render pass's own dependencies cover only its attachments).
  for (int pi : group.passes) bufferBarriers(passes_[pi], barriers);
  flushBarriers(cmd, barriers);
  VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
  bi.renderPass = c.renderPass;
  bi.framebuffer = c.framebuffer;
  bi.renderArea = {{0, 0}, c.extent};
  bi.clearValueCount = uint32_t(c.clears.size());
  bi.pClearValues = c.clears.data();
  vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
  for (uint32_t si = 0; si < uint32_t(c.subpasses.size()); ++si) {
    if (si > 0) vkCmdNextSubpass(cmd, VK_SUBPASS_CONTENTS_INLINE);
    const CompiledGroup::Subpass& sub = c.subpasses[si];
    for (int pi : group.passes) {
      GraphPass& p = passes_[pi];
      if (p.subpass != si) continue;
      LabelScope label(ctx, cmd, p.name.c_str());
      timestamp(cmd, timestamps, 2 * p.stat, false);
      PassContext pc;
      pc.cmd = cmd;
      pc.renderPass = c.renderPass;
      pc.subpass = si;
      pc.colorAttachments = sub.colorAttachments;
      pc.compatClass = sub.compatClass;
      pc.extent = c.extent;
      for (size_t ti = 0; ti < kTargetCount; ++ti) pc.layouts[ti] = sub.used[ti] ? sub.layouts[ti] : targets[ti].layout;
      if (p.execute) p.execute(pc);
      timestamp(cmd, timestamps, 2 * p.stat + 1, true);
    }
  }
  vkCmdEndRenderPass(cmd);
}

}  // namespace gb
