// The renderer: a scene on the GPU, the frame's targets, and renderFrame(), which builds the
// frame graph (frame.cpp), records it, submits, waits, and reads back what was asked for; or
// submitFrame(), which leaves the frame in flight (frame slots, frame_slots.h).
#pragma once
#include <functional>
#include <vector>

#include "renderer/gpu/renderer_state.h"

namespace gb {

// Uploads the scene; the Renderer keeps a pointer to it (the scene must outlive the renderer;
// lights may change between frames).
void initRenderer(Renderer& r, GpuContext& ctx, const Scene& scene);
void destroyRenderer(Renderer& r);

// Renders one frame with these options and waits for it. Targets are re-created when the size
// or a format changes. Frames still in flight are finished first (their stats wait for finishFrames).
const FrameStats& renderFrame(Renderer& r, const RenderOptions& options, const FrameRequest& request = {});

// Frames in flight: records and submits one frame and returns without waiting for it, so the
// CPU records the next frame while the GPU runs this one. Waits only for the frame that last
// used this frame's slot (kFrameSlots in flight at most). Nothing is read back (coverage frames
// are for read-backs: renderFrame). Its FrameStats come from finishFrames.
void submitFrame(Renderer& r, const RenderOptions& options);
// Waits for every frame in flight; the FrameStats of every frame retired since the last call
// (renderFrame's own excepted), complete (GPU times, light and cluster counts), oldest first.
std::vector<FrameStats> finishFrames(Renderer& r);
// A burst of `frames` frames of these options in flight (at least 2; FrameBurst says what is
// timed), for the bench and gblens render --stats.
FrameBurst renderBurst(Renderer& r, const RenderOptions& options, int frames);
// One more frame with the coverage counters on and the eye depth kept, for its culling counts
// (FrameStats::culling): the counters' atomics would slow frames that are being timed.
const FrameStats& renderCountingFrame(Renderer& r, const RenderOptions& options, FrameRequest request = {});

// Runs a small graph over this frame's targets after renderFrame (the viewer's region read-back
// and view ranges): `build` adds passes, then the `handOff` targets are left readable by fragment
// shaders again. Barriers come from the passes' declarations, as in the frame. Submits and waits.
// No frame may be in flight (finishFrames).
void runAfterFrame(Renderer& r, const std::function<void(FrameGraph&)>& build, const std::vector<Target>& handOff);

}  // namespace gb
