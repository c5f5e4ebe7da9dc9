// A render-pass group of the frame graph, compiled: from its passes' declared uses and the state
// its targets arrive in, the layout of every target in every subpass, the attachments with their
// load/store ops, the barriers into the render pass, the subpass dependencies, and the cached
// render pass and framebuffer. A group whose shape (declarations + arriving state) is the same as
// in the last frame is not compiled again: only its execution is recorded (FrameGraph::record).
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "renderer/core/targets.h"
#include "renderer/graph/graph_sync.h"

namespace gb {

// What a group's compilation depends on: equal shapes compile to the same render pass, barriers
// and layouts.
struct GroupShape {
  struct UseKey {
    uint32_t subpass = 0;
    Target target{};
    Access access{};
    bool clear = false;
    std::array<uint32_t, 4> clearBits{};
    bool operator==(const UseKey&) const = default;
  };
  struct TargetKey {
    VkImage image = VK_NULL_HANDLE;
    VkImageView view = VK_NULL_HANDLE;
    VkFormat format = VK_FORMAT_UNDEFINED;
    uint32_t width = 0, height = 0;
    VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 stage = 0;
    VkAccessFlags2 access = 0;
    bool keep = false, usedAfter = false;
    bool operator==(const TargetKey&) const = default;
  };
  uint32_t subpasses = 1;
  std::vector<UseKey> uses;
  std::array<TargetKey, kTargetCount> targets{};  // the targets the group uses (others left zero)
  bool operator==(const GroupShape&) const = default;
};

// The compiled group: everything recording it needs but the passes' own commands.
struct CompiledGroup {
  GroupShape shape;
  // Per used target, in target order: the barrier into the render pass (when `barrier`), and the
  // state the group leaves it in (graph_sync::afterUse).
  struct TargetStep {
    Target target{};
    graph_sync::AccessInfo into{};
    bool discard = false, barrier = false;
    bool afterBarrier = false;
    VkImageLayout afterLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    VkPipelineStageFlags2 afterStage = 0;
    VkAccessFlags2 afterAccess = 0;
  };
  std::vector<TargetStep> steps;
  struct Subpass {
    uint32_t colorAttachments = 0;
    uint32_t compatClass = 0;  // render-pass compatibility class of this subpass (pipeline caches)
    std::array<bool, kTargetCount> used{};
    std::array<VkImageLayout, kTargetCount> layouts{};  // of the used targets during the subpass
  };
  std::vector<Subpass> subpasses;
  VkRenderPass renderPass = VK_NULL_HANDLE;
  VkFramebuffer framebuffer = VK_NULL_HANDLE;
  VkExtent2D extent{};
  std::vector<VkClearValue> clears;
};

// Typed keys of the Vulkan objects derived from declarations.
struct RenderPassKey {
  struct Attachment {
    VkFormat format;
    VkAttachmentLoadOp load;
    VkAttachmentStoreOp store, stencilStore;
    VkImageLayout initial, final;
    auto operator<=>(const Attachment&) const = default;
  };
  struct Subpass {
    std::vector<uint32_t> color, input;
    std::vector<VkImageLayout> inputLayouts;
    uint32_t depth;
    VkImageLayout depthLayout;
    VkSubpassDescriptionFlags flags;
    auto operator<=>(const Subpass&) const = default;
  };
  struct Dependency {
    uint32_t src, dst;
    VkPipelineStageFlags srcStages, dstStages;
    VkAccessFlags srcAccess, dstAccess;
    VkDependencyFlags flags;
    auto operator<=>(const Dependency&) const = default;
  };
  std::vector<Attachment> attachments;
  std::vector<Subpass> subpasses;
  std::vector<Dependency> dependencies;
  auto operator<=>(const RenderPassKey&) const = default;
  // Render passes are compatible when formats, subpass references and (with more than one
  // subpass) dependencies match (Vulkan spec, "Render Pass Compatibility"): load/store ops and
  // layouts do not matter.
  RenderPassKey compatibility() const;
};
struct FramebufferKey {
  VkRenderPass renderPass;
  uint32_t width, height;
  std::vector<VkImageView> views;
  auto operator<=>(const FramebufferKey&) const = default;
};

// Vulkan objects derived from declarations, reused across frames with the same shape.
struct GraphCache {
  std::map<RenderPassKey, VkRenderPass> renderPasses;
  std::map<RenderPassKey, uint32_t> compatClasses;  // compatibility() -> class index
  std::map<FramebufferKey, VkFramebuffer> framebuffers;
  // By group name: its last compilations, newest first (two while targets alternate between frame
  // slots, renderer/frame/frame_slots.h: the same group names the images of either slot).
  std::map<std::string, std::vector<CompiledGroup>> groups;
  uint64_t compilations = 0, reuses = 0;         // group compilations and reuses since creation
};

// A pass as the graph holds it.
struct PassContext;
using PassFn = std::function<void(PassContext&)>;
struct GraphPass {
  std::string name;
  std::vector<Use> uses;
  std::vector<BufferUse> buffers;
  PassFn execute;
  int renderPass = -1;  // index of its group, -1 for compute/transfer
  uint32_t subpass = 0;
  int stat = 0;         // index into the graph's pass statistics
  bool side = false;    // recorded into the side command buffer (FrameGraph::beginSide)
};
struct GraphGroup {
  std::string name;
  uint32_t subpasses = 1;
  std::vector<int> passes;
};

// The shape of `group` given the targets' current state; `usedAfter` says whether a target is
// read by a later pass of the frame.
GroupShape groupShape(const GraphGroup& group, const std::vector<GraphPass>& passes, const GraphTargets& targets,
                      const std::function<bool(Target)>& usedAfter);
// Compiles a group of this shape (render pass and framebuffer from the cache, created on first use).
CompiledGroup compileGroup(GpuContext& ctx, const GraphGroup& group, const std::vector<GraphPass>& passes,
                           const GraphTargets& targets, const GroupShape& shape, GraphCache& cache);

}  // namespace gb
