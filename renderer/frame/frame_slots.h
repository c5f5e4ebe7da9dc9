// Frame slots, for frames in flight (renderer/frame/frame_slots.cpp): what each slot owns (command
// buffer, fence, set 0 and its host-written buffers, queries, copies of the GPU's counts), how a
// frame is recorded into the current slot and submitted, and how a slot's frame is retired.
#pragma once
#include "renderer/frame/renderer.h"

namespace gb {

// Each slot's command buffer, fence, set-0 buffers and set 0 (after createDescriptors).
void createFrameSlots(Renderer& r);
void destroyFrameSlots(Renderer& r);

// Whether some slot holds a frame not yet retired.
bool framesInFlight(const Renderer& r);
// Makes the next slot current; the frame still in it is retired first (into r.retired).
void nextFrameSlot(Renderer& r);
// Retires every frame in flight, oldest first, into r.retired.
void retireFrames(Renderer& r);
// Waits for the slot's frame and completes its FrameStats: GPU pass times, the sky count (the
// skybox decision of later frames), the light counts of light setup on the GPU, cluster counts.
FrameStats retireFrame(Renderer& r, FrameSlot& s);

// The current slot's queries for the passes of `graph` (created or grown on first use, reset),
// and the pipeline-statistics query of a culling frame.
void resetQueries(Renderer& r, const FrameGraph& graph, const FrameRequest& request);
// Records `graph` into the current slot's command buffer and submits it, without waiting; the
// time just before the submission (FrameStats::cpuMs ends there).
std::chrono::steady_clock::time_point recordAndSubmit(Renderer& r, FrameGraph& graph);
uint64_t queryResult(GpuContext& ctx, VkQueryPool pool, uint32_t query);

}  // namespace gb
