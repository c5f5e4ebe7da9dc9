// Frame slots (see frame_slots.h): per-slot resources, recording and submitting into the current
// slot, retiring a slot's frame, and the frames-in-flight API (finishFrames, renderBurst).
//
// What keeps frames in flight apart: everything the CPU writes for a frame (frame data, draws,
// the CPU path's lights and counts, new light descriptions) lives in the frame's slot, and so
// does everything the CPU reads after it (queries, light and cluster counts); the other slot's
// frame may still read or write its own. Buffers only the GPU touches (cluster lists, light setup
// scratch, fairy bits, the light descriptions) and the targets are shared: a frame recorded while
// another is in flight starts with a full memory barrier after everything submitted before it,
// and each target's first barrier comes from the state the previous frame's recording left it in
// (GraphTarget), as for frames waited for.
#include "renderer/frame/frame_slots.h"

#include <algorithm>

#include "renderer/frame/frame.h"
#include "renderer/gpu/cluster_buffers.h"
#include "renderer/gpu/gpu_lights.h"
#include "renderer/vk/check.h"

namespace gb {

using Clock = std::chrono::steady_clock;

static double msBetween(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double, std::milli>(b - a).count();
}

// Set 0 of one slot: frame data, draws, lights, visible list, light counts, visible positions.
static void writeSceneSet(GpuContext& ctx, const FrameSlot& s, const Buffer& materials) {
  const VkDescriptorBufferInfo bufs[] = {{s.frameBuffer.buffer, 0, VK_WHOLE_SIZE},   {s.drawBuffer.buffer, 0, VK_WHOLE_SIZE},
                                         {materials.buffer, 0, VK_WHOLE_SIZE},       {s.lightBuffer.buffer, 0, VK_WHOLE_SIZE},
                                         {s.visibleBuffer.buffer, 0, VK_WHOLE_SIZE}, {s.lightCountBuffer.buffer, 0, VK_WHOLE_SIZE},
                                         {s.visiblePositionBuffer.buffer, 0, VK_WHOLE_SIZE}};
  std::vector<VkWriteDescriptorSet> writes;
  for (uint32_t b = 0; b < uint32_t(std::size(bufs)); ++b) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstSet = s.sceneSet;
    w.dstBinding = b;
    w.descriptorCount = 1;
    w.descriptorType = b == gpu::kBindingFrame ? VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &bufs[b];
    writes.push_back(w);
  }
  vkUpdateDescriptorSets(ctx.device, uint32_t(writes.size()), writes.data(), 0, nullptr);
}

void createFrameSlots(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  VkDescriptorPoolSize sizes[] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, kFrameSlots},
                                  {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 6 * kFrameSlots}};
  VkDescriptorPoolCreateInfo dpci{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  dpci.maxSets = kFrameSlots;
  dpci.poolSizeCount = 2;
  dpci.pPoolSizes = sizes;
  VK_CHECK(vkCreateDescriptorPool(ctx.device, &dpci, nullptr, &r.descriptorPool));
  const size_t instances = std::max<size_t>(r.scene->instances.size(), 1);
  const size_t maxLights = std::max<size_t>(r.scene->lights.size(), 65536);  // --lights range: never grown
  for (FrameSlot& s : r.slots) {
    // Named as in shaders/common.glsl ("frame" is the uniform buffer with the camera matrices:
    // RenderDoc import finds it by that name), the same in every slot.
    s.frameBuffer = createBuffer(ctx, sizeof(gpu::FrameData), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT, MemoryUse::Upload, "frame");
    s.drawBuffer = createBuffer(ctx, instances * sizeof(gpu::DrawData), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                MemoryUse::Upload, "draws");
    s.lightBuffer = createBuffer(ctx, maxLights * sizeof(gpu::PointLight), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                 MemoryUse::Upload, "lights");
    s.visibleBuffer = createBuffer(ctx, maxLights * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                   MemoryUse::Upload, "visible_lights");
    s.visiblePositionBuffer = createBuffer(ctx, maxLights * sizeof(glm::vec4), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                           MemoryUse::Upload, "visible_positions");
    s.lightCountBuffer = createBuffer(ctx, sizeof(gpu::LightCounts),
                                      VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT,
                                      MemoryUse::Upload, "light_counts");
    VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
    ai.descriptorPool = r.descriptorPool;
    ai.descriptorSetCount = 1;
    ai.pSetLayouts = &r.sceneSetLayout;
    VK_CHECK(vkAllocateDescriptorSets(ctx.device, &ai, &s.sceneSet));
    setName(ctx, uint64_t(s.sceneSet), VK_OBJECT_TYPE_DESCRIPTOR_SET, "set0.scene");
    writeSceneSet(ctx, s, r.materialBuffer);
    VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    cai.commandPool = ctx.commandPool;
    cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    cai.commandBufferCount = 1;
    VK_CHECK(vkAllocateCommandBuffers(ctx.device, &cai, &s.cmd));
    setName(ctx, uint64_t(s.cmd), VK_OBJECT_TYPE_COMMAND_BUFFER, "frame");
    VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(ctx.device, &fci, nullptr, &s.fence));
    if (r.overlapAllowed) {  // frames that overlap (side_queue.h)
      VK_CHECK(vkAllocateCommandBuffers(ctx.device, &cai, &s.sideCmd));
      setName(ctx, uint64_t(s.sideCmd), VK_OBJECT_TYPE_COMMAND_BUFFER, "frame (visibility)");
      VkCommandBufferAllocateInfo compute = cai;
      compute.commandPool = ctx.computePool;
      VK_CHECK(vkAllocateCommandBuffers(ctx.device, &compute, &s.computeCmd));
      setName(ctx, uint64_t(s.computeCmd), VK_OBJECT_TYPE_COMMAND_BUFFER, "frame (compute)");
      VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
      VK_CHECK(vkCreateSemaphore(ctx.device, &sci, nullptr, &s.sideDone));
      setName(ctx, uint64_t(s.sideDone), VK_OBJECT_TYPE_SEMAPHORE, "visibility done");
    }
  }
  if (r.overlapAllowed) {
    VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    VkSemaphoreCreateInfo sci{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
    sci.pNext = &type;
    VK_CHECK(vkCreateSemaphore(ctx.device, &sci, nullptr, &r.frameTimeline));
    setName(ctx, uint64_t(r.frameTimeline), VK_OBJECT_TYPE_SEMAPHORE, "frames");
    r.framesSubmitted = 0;
  }
}

void destroyFrameSlots(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  for (FrameSlot& s : r.slots) {
    for (Buffer* b : {&s.frameBuffer, &s.drawBuffer, &s.lightBuffer, &s.visibleBuffer, &s.lightCountBuffer, &s.visiblePositionBuffer,
                      &s.lightDescStaging, &s.clusterHeader, &s.gridCells, &s.gridLights})
      if (b->buffer) destroyBuffer(ctx, *b);
    for (VkQueryPool q : {s.timestampPool, s.occlusionPool})
      if (q) vkDestroyQueryPool(ctx.device, q, nullptr);
    for (VkCommandBuffer c : {s.cmd, s.sideCmd})
      if (c) vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &c);
    if (s.computeCmd) vkFreeCommandBuffers(ctx.device, ctx.computePool, 1, &s.computeCmd);
    if (s.fence) vkDestroyFence(ctx.device, s.fence, nullptr);
    if (s.sideDone) vkDestroySemaphore(ctx.device, s.sideDone, nullptr);
    s = FrameSlot{};
  }
  if (r.descriptorPool) vkDestroyDescriptorPool(ctx.device, r.descriptorPool, nullptr);
  r.descriptorPool = VK_NULL_HANDLE;
  if (r.frameTimeline) vkDestroySemaphore(ctx.device, r.frameTimeline, nullptr);
  r.frameTimeline = VK_NULL_HANDLE;
}

bool framesInFlight(const Renderer& r) {
  return std::any_of(r.slots.begin(), r.slots.end(), [](const FrameSlot& s) { return s.pending; });
}

void nextFrameSlot(Renderer& r) {
  r.slot = (r.slot + 1) % kFrameSlots;
  FrameSlot& s = frameSlot(r);
  if (s.pending) r.retired.push_back(retireFrame(r, s));
}

void retireFrames(Renderer& r) {
  for (uint32_t k = 1; k <= kFrameSlots; ++k) {  // oldest first: the slot after the current one
    FrameSlot& s = r.slots[(r.slot + k) % kFrameSlots];
    if (s.pending) r.retired.push_back(retireFrame(r, s));
  }
}

uint64_t queryResult(GpuContext& ctx, VkQueryPool pool, uint32_t query) {
  uint64_t v = 0;
  VK_CHECK(vkGetQueryPoolResults(ctx.device, pool, query, 1, sizeof(v), &v, sizeof(v),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return v;
}

// The passes' GPU times from the slot's timestamps (query 2i and 2i + 1 around the i-th pass).
// "Before" is the gap after the pass that ran before it: in time, not list order (a side part
// runs before the main part's first passes).
static void passTimes(GpuContext& ctx, const FrameSlot& s, FrameStats& st) {
  st.gpuMs = 0.0;
  if (!ctx.features.timestamps) return;
  const double period = ctx.properties.limits.timestampPeriod * 1e-6;
  std::vector<std::pair<double, size_t>> starts;  // (start, pass)
  for (size_t i = 0; i < st.passes.size(); ++i) {
    if (st.passes[i].skipped) continue;
    const double t0 = double(queryResult(ctx, s.timestampPool, uint32_t(2 * i))) * period;
    const double t1 = double(queryResult(ctx, s.timestampPool, uint32_t(2 * i + 1))) * period;
    st.passes[i].ms = t1 - t0;
    starts.push_back({t0, i});
  }
  std::stable_sort(starts.begin(), starts.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  double first = 1e300, last = -1e300, end = -1.0;
  for (const auto& [t0, i] : starts) {
    const double t1 = t0 + st.passes[i].ms;
    st.passes[i].beforeMs = end < 0.0 ? 0.0 : t0 - end;
    end = t1;
    first = std::min(first, t0);
    last = std::max(last, t1);
  }
  if (last > first) st.gpuMs = last - first, st.gpuEndMs = last;
}

FrameStats retireFrame(Renderer& r, FrameSlot& s) {
  GB_ASSERT(s.pending);
  GpuContext& ctx = *r.ctx;
  VK_CHECK(vkWaitForFences(ctx.device, 1, &s.fence, VK_TRUE, UINT64_MAX));
  s.pending = false;
  FrameStats st = std::move(s.stats);
  st.frameMs = msBetween(s.start, Clock::now());
  if (s.skyQuery) {
    // Non-zero exactly when some sample passed (a non-precise query may overcount). Slots retire
    // in submission order, so this is the newest count of a finished frame.
    r.skyPixels = queryResult(ctx, s.occlusionPool, 0);
    r.skyKey = s.skyKey;
    st.skyPixels = int64_t(r.skyPixels);
  }
  passTimes(ctx, s, st);
  if (s.gpuLightCounts) readGpuLightCounts(s, st);
  if (s.clusterCounts) st.clusters = collectClusterStats(r, s);
  return st;
}

static VkQueryPool createQueryPool(GpuContext& ctx, VkQueryType type, uint32_t count,
                                   VkQueryPipelineStatisticFlags statistics = 0) {
  VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qci.queryType = type;
  qci.queryCount = count;
  qci.pipelineStatistics = statistics;
  VkQueryPool pool;
  VK_CHECK(vkCreateQueryPool(ctx.device, &qci, nullptr, &pool));
  return pool;
}

void resetQueries(Renderer& r, const FrameGraph& graph, const FrameRequest& request) {
  GpuContext& ctx = *r.ctx;
  FrameSlot& s = frameSlot(r);
  GB_ASSERT(!s.pending);
  if (r.skyQueryActive) {
    if (!s.occlusionPool) s.occlusionPool = createQueryPool(ctx, VK_QUERY_TYPE_OCCLUSION, 1);
    vkResetQueryPool(ctx.device, s.occlusionPool, 0, 1);
  }
  const uint32_t queries = std::max(graph.timestampCount(), 2u);
  if (!s.timestampPool || s.timestampCapacity < queries) {
    if (s.timestampPool) vkDestroyQueryPool(ctx.device, s.timestampPool, nullptr);
    s.timestampCapacity = std::max(queries, 64u);
    s.timestampPool = createQueryPool(ctx, VK_QUERY_TYPE_TIMESTAMP, s.timestampCapacity);
  }
  vkResetQueryPool(ctx.device, s.timestampPool, 0, s.timestampCapacity);
  r.statisticsActive = request.cullingStats && ctx.features.pipelineStatistics;
  if (r.statisticsActive) {
    if (!r.statisticsPool)
      r.statisticsPool = createQueryPool(ctx, VK_QUERY_TYPE_PIPELINE_STATISTICS, 1,
                                         VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT);
    vkResetQueryPool(ctx.device, r.statisticsPool, 0, 1);
  }
}

// Everything submitted before (the other slot's frame may still run) against everything this
// command buffer does: shared buffers are written and read again each frame.
static void afterEarlierFrames(VkCommandBuffer cmd) {
  VkMemoryBarrier2 mb{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  mb.srcStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  mb.srcAccessMask = VK_ACCESS_2_MEMORY_WRITE_BIT;
  mb.dstStageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  mb.dstAccessMask = VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT;
  VkDependencyInfo di{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  di.memoryBarrierCount = 1;
  di.pMemoryBarriers = &mb;
  vkCmdPipelineBarrier2(cmd, &di);
}

static void beginCommands(VkCommandBuffer cmd, bool othersInFlight) {
  VK_CHECK(vkResetCommandBuffer(cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &bi));
  if (othersInFlight) afterEarlierFrames(cmd);
}

// A frame that overlaps (Renderer::overlap) submits its side part (the visibility pass) to the
// graphics queue and the rest to the compute queue, which waits for the side part. The side part
// waits for nothing of the frame in flight: it writes only this slot's own images (kSlotTargets),
// whose last frame was retired, and the barrier after earlier frames orders it after the graphics
// queue's work before it. Every frame's last submission waits for the previous frame's on the
// timeline (whichever queue that went to) and signals its own.
std::chrono::steady_clock::time_point recordAndSubmit(Renderer& r, FrameGraph& graph) {
  GpuContext& ctx = *r.ctx;
  FrameSlot& s = frameSlot(r);
  const bool othersInFlight = framesInFlight(r);  // this slot's own frame was retired
  const bool side = r.overlap;
  GB_ASSERT(!side || (s.sideCmd && r.parked[0].image.image && graph.hasSide()));
  VkCommandBuffer main = side ? s.computeCmd : s.cmd;
  beginCommands(main, othersInFlight);
  if (side) beginCommands(s.sideCmd, othersInFlight);
  graph.record(ctx, main, r.targets, r.graphCache, ctx.features.timestamps ? s.timestampPool : VK_NULL_HANDLE,
               side ? s.sideCmd : VK_NULL_HANDLE);
  VK_CHECK(vkEndCommandBuffer(main));
  if (side) VK_CHECK(vkEndCommandBuffer(s.sideCmd));

  std::vector<VkSemaphore> waits;
  std::vector<VkPipelineStageFlags> waitStages;
  std::vector<uint64_t> waitValues;
  if (side) waits.push_back(s.sideDone), waitValues.push_back(0);
  if (r.frameTimeline) waits.push_back(r.frameTimeline), waitValues.push_back(r.framesSubmitted);
  waitStages.assign(waits.size(), VK_PIPELINE_STAGE_ALL_COMMANDS_BIT);
  const uint64_t signalValue = r.framesSubmitted + 1;
  VkTimelineSemaphoreSubmitInfo timeline{VK_STRUCTURE_TYPE_TIMELINE_SEMAPHORE_SUBMIT_INFO};
  timeline.waitSemaphoreValueCount = uint32_t(waitValues.size());
  timeline.pWaitSemaphoreValues = waitValues.data();
  timeline.signalSemaphoreValueCount = 1;
  timeline.pSignalSemaphoreValues = &signalValue;
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &main;
  si.waitSemaphoreCount = uint32_t(waits.size());
  si.pWaitSemaphores = waits.data();
  si.pWaitDstStageMask = waitStages.data();
  if (r.frameTimeline) {
    si.pNext = &timeline;
    si.signalSemaphoreCount = 1;
    si.pSignalSemaphores = &r.frameTimeline;
  }
  VK_CHECK(vkResetFences(ctx.device, 1, &s.fence));
  const Clock::time_point submitted = Clock::now();
  if (side) {
    VkSubmitInfo ssi{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    ssi.commandBufferCount = 1;
    ssi.pCommandBuffers = &s.sideCmd;
    ssi.signalSemaphoreCount = 1;
    ssi.pSignalSemaphores = &s.sideDone;
    VK_CHECK(vkQueueSubmit(ctx.queue, 1, &ssi, VK_NULL_HANDLE));
  }
  VK_CHECK(vkQueueSubmit(side ? ctx.computeQueue : ctx.queue, 1, &si, s.fence));
  if (r.frameTimeline) r.framesSubmitted = signalValue;
  s.pending = true;
  return submitted;
}

std::vector<FrameStats> finishFrames(Renderer& r) {
  retireFrames(r);
  return std::exchange(r.retired, {});
}

FrameBurst renderBurst(Renderer& r, const RenderOptions& options, int frames) {
  GB_ASSERT(frames >= 2);
  FrameBurst burst;
  burst.inFlight = int(kFrameSlots);
  finishFrames(r);  // frames before the burst are not its own
  submitFrame(r, options);
  burst.first = finishFrames(r).at(0);  // targets, pipelines, the light upload; not counted
  const Clock::time_point start = Clock::now();
  Clock::time_point last = start;
  for (int i = 1; i < frames; ++i) {
    submitFrame(r, options);
    const Clock::time_point now = Clock::now();
    if (i > 1) burst.intervalMs.push_back(msBetween(last, now));
    last = now;
  }
  burst.frames = finishFrames(r);
  const Clock::time_point end = Clock::now();
  burst.intervalMs.push_back(msBetween(last, end));
  burst.msPerFrame = msBetween(start, end) / double(frames - 1);
  const FrameStats &a = burst.frames.front(), &b = burst.frames.back();
  if (burst.frames.size() >= 2 && a.gpuEndMs >= 0.0 && b.gpuEndMs > a.gpuEndMs)
    burst.steadyMs = (b.gpuEndMs - a.gpuEndMs) / double(burst.frames.size() - 1);
  GB_ASSERT(burst.frames.size() == size_t(frames - 1));
  return burst;
}

}  // namespace gb
