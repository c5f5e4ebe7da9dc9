// Frames that overlap: a frame's visibility pass (the id's clear and the raster pass) is its side
// part, on the graphics queue; the rest, all compute, goes to a compute-only queue, so the next
// frame's visibility pass runs beside it. On Hopper only 2 TPCs draw (docs/perf-gpu.md): the raster
// pass otherwise leaves the chip idle.
#pragma once
#include <string>

#include "renderer/frame/renderer.h"

namespace gb {

// Whether this renderer's frames may overlap: GBLENS_OVERLAP=auto (default: on a GPU device with a
// compute-only queue family, GpuContext::computeQueue), on (also on one queue: the same split, run in
// order; for tests), off. Any other value stops the program (an A/B run never times the default by
// mistake). Needs timeline semaphores.
void decideOverlapAllowed(Renderer& r);
// Whether this frame (r.visibility, r.method set) may overlap, and why (FrameStats::overlapReason):
// buildFrame then puts its visibility pass in the graph's side part.
bool overlapFrame(const Renderer& r, std::string& reason);
// Whether the built frame does: not when its compute part has a raster pass (a shadow map drawn,
// deferred lighting, a raster tone map), which a compute-only queue cannot run (r.overlap and its
// reason updated; the graph then records every pass in order, on the graphics queue).
bool overlapRecorded(Renderer& r, const FrameGraph& graph);
// r.targets gets the current slot's images of kSlotTargets (a frame writes its own slot's depth and
// id, which no frame in flight reads); a no-op with one image each.
void useSlotTargets(Renderer& r);

}  // namespace gb
