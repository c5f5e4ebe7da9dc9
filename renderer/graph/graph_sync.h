// Frame graph synchronisation (renderer/graph_sync.cpp): declared use -> layout, stages, access;
// the barrier rules. Internal to the frame graph.
#pragma once
#include <vector>

#include "renderer/graph/graph_types.h"

namespace gb::graph_sync {

struct AccessInfo {
  VkImageLayout layout;
  VkPipelineStageFlags2 stage;
  VkAccessFlags2 access;
  bool write;
};

bool isColorAttachment(Access a);
bool isDepthAttachment(Access a);
AccessInfo accessInfo(Access a, VkFormat format);

// Render-pass dependencies take the original 32-bit masks: map the synchronization2 bits we use.
VkPipelineStageFlags legacyStages(VkPipelineStageFlags2 s);
VkAccessFlags legacyAccess(VkAccessFlags2 a);

void imageBarrier(std::vector<VkImageMemoryBarrier2>& out, const GraphTarget& t, VkImageLayout from,
                  const AccessInfo& to);
// Barriers collected for one point of the command buffer (images and buffers), then flushed.
struct Barriers {
  std::vector<VkImageMemoryBarrier2> images;
  std::vector<VkBufferMemoryBarrier2> buffers;
};
void flushBarriers(VkCommandBuffer cmd, Barriers& barriers);
// A buffer use: a barrier after the buffer's earlier uses in this frame when one is needed
// (read after write, write after read or write), then the buffer's new state.
AccessInfo bufferAccessInfo(BufferAccess a);
void bufferUse(Barriers& out, VkBuffer buffer, GraphBufferState& state, const AccessInfo& to);

// Whether a use needs a barrier after the target's last uses (see graph_sync.cpp).
bool needsBarrier(const GraphTarget& t, const AccessInfo& to);
// After a use: a read after reads without a barrier joins them (a later writer waits for all).
void afterUse(GraphTarget& t, bool barrier, VkImageLayout layout, VkPipelineStageFlags2 stage, VkAccessFlags2 access);

}  // namespace gb::graph_sync
