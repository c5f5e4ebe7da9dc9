// Frames that overlap: a frame's visibility pass (the id's clear and the raster pass) goes into a
// side command buffer on a second queue, so it runs beside the previous frame's compute passes.
// On Hopper only 2 of 66 TPCs draw (docs/perf-gpu.md): the raster pass otherwise leaves the chip idle.
#pragma once
#include <string>

#include "renderer/frame/renderer.h"

namespace gb {

// Whether this renderer's frames may overlap: GBLENS_OVERLAP=auto (default: on a GPU device whose
// graphics family has a second queue), on (also on one queue: the same split, run in order; for
// tests), off. Any other value stops the program (an A/B run never times the default by mistake).
void decideOverlapAllowed(Renderer& r);
// Whether this frame (r.visibility, r.method set) overlaps, and why (FrameStats::overlapReason).
bool overlapFrame(const Renderer& r, std::string& reason);
// r.targets gets the current slot's images of kSlotTargets (a frame writes its own slot's depth and
// id, which no frame in flight reads); a no-op with one image each.
void useSlotTargets(Renderer& r);

}  // namespace gb
