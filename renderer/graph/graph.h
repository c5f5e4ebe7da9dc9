// A small frame graph: passes declare which targets they read and write and how; the graph
// turns those declarations into Vulkan render passes (with subpasses and their dependencies),
// load/store ops, image layout transitions and pipeline barriers. Passes never place barriers.
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "renderer/core/frame_stats.h"
#include "renderer/core/targets.h"
#include "renderer/vk/context.h"
#include "renderer/vk/resources.h"

namespace gb {

enum class Access : uint8_t {
  ColorWrite,             // colour attachment, written
  ColorBlend,             // colour attachment, read-modify-write (blending)
  DepthStencilWrite,      // depth/stencil attachment, both written
  DepthTestStencilWrite,  // depth tested (not written), stencil written; depth may be read too
  DepthStencilRead,       // depth/stencil attachment, read only
  InputAttachment,        // subpass input (single-pass path)
  SampledFragment,        // texture read in a fragment shader
  SampledCompute,         // texture read in a compute shader
  StorageFragment,        // storage image read/written in a fragment shader (atomics)
  StorageCompute,         // storage image read/written in a compute shader
  TransferSrc,
  TransferDst,
};

struct Use {
  Target target;
  Access access;
  bool clear = false;  // first use in its render pass clears to clearValue
  VkClearValue clearValue{};
};

// A target as the graph sees it: its image and the state the last recorded use left it in.
struct GraphTarget {
  Image image;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = 0;
  bool keep = false;  // contents must survive past the frame (read-back, reuse next frame)
};
using GraphTargets = std::array<GraphTarget, kTargetCount>;

struct PassContext {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkRenderPass renderPass = VK_NULL_HANDLE;  // null for compute/transfer passes
  uint32_t subpass = 0;
  uint32_t colorAttachments = 0;  // colour attachments of this subpass (pipelines need one blend state each)
  std::string compatKey;          // render-pass compatibility class + subpass: key for pipeline caches
  VkExtent2D extent{};
  std::array<VkImageLayout, kTargetCount> layouts{};  // each target's layout during this pass
};
using PassFn = std::function<void(PassContext&)>;


// Vulkan objects derived from declarations, reused across frames with the same shape.
struct GraphCache {
  std::map<std::string, VkRenderPass> renderPasses;
  std::map<std::string, VkFramebuffer> framebuffers;
};
void destroyGraphCache(GpuContext& ctx, GraphCache& cache);
void clearFramebuffers(GpuContext& ctx, GraphCache& cache);  // after targets are re-created

class FrameGraph {
 public:
  // Raster passes added between begin/endRenderPass share one Vulkan render pass; nextSubpass
  // starts its next subpass. Passes added outside one are compute/transfer passes.
  void beginRenderPass(std::string name);
  void nextSubpass();
  void endRenderPass();
  void addPass(std::string name, std::vector<Use> uses, PassFn execute);
  void skipPass(std::string name, std::string reason);

  // Builds render passes and barriers and records every pass. Timestamps (if a pool is given)
  // are written around each pass: query 2*i and 2*i+1 for the i-th pass in stats() order.
  void record(GpuContext& ctx, VkCommandBuffer cmd, GraphTargets& targets, GraphCache& cache,
              VkQueryPool timestamps);

  std::vector<PassStat>& stats() { return stats_; }
  uint32_t timestampCount() const { return uint32_t(stats_.size()) * 2; }

 private:
  struct PassNode {
    std::string name;
    std::vector<Use> uses;
    PassFn execute;
    int renderPass = -1;  // index into groups_, -1 for compute/transfer
    uint32_t subpass = 0;
    int stat = 0;         // index into stats_
  };
  struct Group {
    std::string name;
    uint32_t subpasses = 1;
    std::vector<int> passes;
  };
  std::vector<PassNode> passes_;
  std::vector<Group> groups_;
  std::vector<PassStat> stats_;
  int openGroup_ = -1;

  void recordGroup(GpuContext& ctx, VkCommandBuffer cmd, int group, GraphTargets& targets, GraphCache& cache,
                   VkQueryPool timestamps);
  bool usedAfter(Target t, size_t passIndex) const;
};

}  // namespace gb
