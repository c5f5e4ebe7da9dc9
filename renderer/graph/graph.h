// A small frame graph: passes declare which targets they read and write and how; the graph
// turns those declarations into Vulkan render passes (with subpasses and their dependencies),
// load/store ops, image layout transitions and pipeline barriers. Passes never place barriers.
#pragma once
#include <vulkan/vulkan.h>

#include <map>
#include <string>
#include <vector>

#include "renderer/core/frame_stats.h"
#include "renderer/graph/graph_compile.h"
#include "renderer/vk/context.h"
#include "renderer/vk/resources.h"

namespace gb {

void destroyGraphCache(GpuContext& ctx, GraphCache& cache);
// After targets are re-created: framebuffers and compiled groups name their images.
void clearFramebuffers(GpuContext& ctx, GraphCache& cache);

class FrameGraph {
 public:
  // Raster passes added between begin/endRenderPass share one Vulkan render pass; nextSubpass
  // starts its next subpass. Passes added outside one are compute/transfer passes.
  void beginRenderPass(std::string name);
  void nextSubpass();
  void endRenderPass();
  void addPass(std::string name, std::vector<Use> uses, PassFn execute, std::vector<BufferUse> buffers = {});
  void skipPass(std::string name, std::string reason);
  // Passes added between beginSide and endSide are recorded into a command buffer of their own,
  // before the others (record's `side`), so that another queue can run them beside the previous
  // frame. They must not touch what a pass added before them touches (asserted when recording).
  void beginSide();
  void endSide();
  bool hasSide() const;
  // The first pass of the first render-pass group outside the side part ("" if none).
  std::string rasterOutsideSide() const;

  // Builds render passes and barriers and records every pass, each in a debug label region named as in
  // stats() (RenderDoc's event browser), render-pass groups in one more region named as the group.
  // Timestamps (if a pool is given)
  // are written around each pass: query 2*i and 2*i+1 for the i-th pass in stats() order.
  // With `side`, it gets the side passes (and nothing else) and `cmd` the rest; without, `cmd` gets
  // every pass in order.
  void record(GpuContext& ctx, VkCommandBuffer cmd, GraphTargets& targets, GraphCache& cache,
              VkQueryPool timestamps, VkCommandBuffer side = VK_NULL_HANDLE);

  std::vector<PassStat>& stats() { return stats_; }
  uint32_t timestampCount() const { return uint32_t(stats_.size()) * 2; }

 private:
  std::vector<GraphPass> passes_;
  std::vector<GraphGroup> groups_;
  std::vector<PassStat> stats_;
  int openGroup_ = -1;
  bool openSide_ = false;
  std::map<VkBuffer, GraphBufferState> buffers_;  // buffer state while recording

  void bufferBarriers(const GraphPass& p, graph_sync::Barriers& out);
  void recordCompute(GpuContext& ctx, VkCommandBuffer cmd, GraphPass& p, GraphTargets& targets,
                     VkQueryPool timestamps);
  void recordGroup(GpuContext& ctx, VkCommandBuffer cmd, int group, GraphTargets& targets, GraphCache& cache,
                   VkQueryPool timestamps);
  void executeGroup(GpuContext& ctx, VkCommandBuffer cmd, const GraphGroup& group, const CompiledGroup& c,
                    GraphTargets& targets, VkQueryPool timestamps);
  bool usedAfter(Target t, size_t passIndex) const;
  void checkSideIndependent() const;
};

}  // namespace gb
