// Frame graph synchronisation: how each declared use maps to a layout, stages and access, and
// when a use needs a barrier. Render-pass dependencies and pipeline barriers both come from here.
#include "renderer/graph/graph_sync.h"

#include "renderer/vk/check.h"

namespace gb::graph_sync {


bool isColorAttachment(Access a) { return a == Access::ColorWrite || a == Access::ColorBlend; }
bool isDepthAttachment(Access a) {
  return a == Access::DepthStencilWrite || a == Access::DepthTestStencilWrite || a == Access::DepthStencilRead;
}

AccessInfo accessInfo(Access a, VkFormat format) {
  const bool ds = isDepthFormat(format) && hasStencil(format);
  const VkImageLayout readLayout =
      ds ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  const VkPipelineStageFlags2 tests =
      VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT;
  switch (a) {
    case Access::ColorWrite:
      return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
              VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT, true};
    case Access::ColorBlend:
      return {VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
              VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT, true};
    case Access::DepthStencilWrite:
      return {VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, tests,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, true};
    case Access::DepthTestStencilWrite:
      return {VK_IMAGE_LAYOUT_DEPTH_READ_ONLY_STENCIL_ATTACHMENT_OPTIMAL, tests,
              VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT, true};
    case Access::DepthStencilRead:
      return {VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, tests, VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
              false};
    case Access::InputAttachment:
      return {readLayout, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_INPUT_ATTACHMENT_READ_BIT, false};
    case Access::SampledFragment:
      return {readLayout, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, false};
    case Access::SampledCompute:
      return {readLayout, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT, false};
    case Access::StorageFragment:
      return {VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
              VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true};
    case Access::StorageCompute:
      return {VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
              VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true};
    case Access::TransferSrc:
      return {VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
              false};
    case Access::TransferDst:
      return {VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT,
              VK_ACCESS_2_TRANSFER_WRITE_BIT, true};
  }
  GB_ASSERT(!"accessInfo");
  return {};
}

// Render-pass dependencies take the original 32-bit masks: map the synchronization2 bits we use.
VkPipelineStageFlags legacyStages(VkPipelineStageFlags2 s) {
  VkPipelineStageFlags out = VkPipelineStageFlags(s & 0xFFFFFFFFull);
  if (s & (VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT)) out |= VK_PIPELINE_STAGE_TRANSFER_BIT;
  return out;
}
VkAccessFlags legacyAccess(VkAccessFlags2 a) {
  VkAccessFlags out = VkAccessFlags(a & 0xFFFFFFFFull);
  if (a & (VK_ACCESS_2_SHADER_SAMPLED_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT)) out |= VK_ACCESS_SHADER_READ_BIT;
  if (a & VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT) out |= VK_ACCESS_SHADER_WRITE_BIT;
  return out;
}

void imageBarrier(std::vector<VkImageMemoryBarrier2>& out, const GraphTarget& t, VkImageLayout from,
                  const AccessInfo& to) {
  out.push_back(imageMemoryBarrier(t.image.image, {aspectsOf(t.image.desc.format), 0, VK_REMAINING_MIP_LEVELS, 0, 1},
                                   from, to.layout,
                                   t.stage == VK_PIPELINE_STAGE_2_NONE ? VK_PIPELINE_STAGE_2_TOP_OF_PIPE_BIT : t.stage,
                                   t.access, to.stage, to.access));
}

void flushBarriers(VkCommandBuffer cmd, Barriers& barriers) {
  if (barriers.images.empty() && barriers.buffers.empty()) return;
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = uint32_t(barriers.images.size());
  dep.pImageMemoryBarriers = barriers.images.data();
  dep.bufferMemoryBarrierCount = uint32_t(barriers.buffers.size());
  dep.pBufferMemoryBarriers = barriers.buffers.data();
  vkCmdPipelineBarrier2(cmd, &dep);
  barriers.images.clear();
  barriers.buffers.clear();
}

AccessInfo bufferAccessInfo(BufferAccess a) {
  const VkImageLayout none = VK_IMAGE_LAYOUT_UNDEFINED;
  switch (a) {
    case BufferAccess::TransferWrite:
      return {none, VK_PIPELINE_STAGE_2_CLEAR_BIT | VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, true};
    case BufferAccess::TransferRead:
      return {none, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT, false};
    case BufferAccess::ComputeRead:
      return {none, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, false};
    case BufferAccess::ComputeReadWrite:
      return {none, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
              VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, true};
    case BufferAccess::IndirectRead:
      return {none, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT, false};
    case BufferAccess::VertexRead:
      return {none, VK_PIPELINE_STAGE_2_VERTEX_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, false};
    case BufferAccess::FragmentRead:
      return {none, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT, false};
    case BufferAccess::HostRead:
      return {none, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT, false};
  }
  GB_ASSERT(!"bufferAccessInfo");
  return {};
}

void bufferUse(Barriers& out, VkBuffer buffer, GraphBufferState& state, const AccessInfo& to) {
  const bool lastWasWrite = (state.access & (VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT)) != 0;
  const bool used = state.stage != VK_PIPELINE_STAGE_2_NONE;
  // Nothing before it in this frame: the submission orders host writes before it.
  const bool barrier = used && (lastWasWrite || to.write || (to.stage & ~state.stage) != 0);
  if (barrier) {
    VkBufferMemoryBarrier2 b{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
    b.srcStageMask = state.stage;
    b.srcAccessMask = state.access;
    b.dstStageMask = to.stage;
    b.dstAccessMask = to.access;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.buffer = buffer;
    b.offset = 0;
    b.size = VK_WHOLE_SIZE;
    out.buffers.push_back(b);
  }
  if (barrier || !used) {
    state.stage = to.stage;
    state.access = to.access;
  } else {
    state.stage |= to.stage;
    state.access |= to.access;
  }
}

// Barrier into a use unless it is a read after a read in the same layout in stages the last
// barrier already reached (t.stage: the readers since then). A read in a new stage needs one:
// the barrier that transitioned the image (or made the last write visible) did not include it,
// and a barrier from the earlier readers' stages chains it on.
bool needsBarrier(const GraphTarget& t, const AccessInfo& to) {
  bool lastWasWrite = (t.access & (VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT |
                                   VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT)) != 0;
  return t.layout != to.layout || lastWasWrite || to.write || (to.stage & ~t.stage) != 0;
}

// After a use: a read after reads without a barrier joins them (a later writer waits for all).
void afterUse(GraphTarget& t, bool barrier, VkImageLayout layout, VkPipelineStageFlags2 stage, VkAccessFlags2 access) {
  if (barrier) {
    t.stage = stage;
    t.access = access;
  } else {
    t.stage |= stage;
    t.access |= access;
  }
  t.layout = layout;
}

}  // namespace gb::graph_sync
