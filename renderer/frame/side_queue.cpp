// Frames that overlap (side_queue.h): the device-wide decision, the per-frame one, and the targets
// with an image per frame slot.
#include "renderer/frame/side_queue.h"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <utility>

namespace gb {

void decideOverlapAllowed(Renderer& r) {
  const GpuContext& ctx = *r.ctx;
  const char* v = std::getenv("GBLENS_OVERLAP");
  const std::string mode = v && *v ? v : "auto";
  const bool asyncCompute = ctx.computeQueue != ctx.queue;
  if (mode != "auto" && mode != "on" && mode != "off") {
    std::fprintf(stderr, "gblens: GBLENS_OVERLAP=%s: auto, on or off (the visibility pass beside the previous frame)\n",
                 v);
    std::exit(2);
  }
  r.overlapAllowed = false;
  if (mode == "off")
    r.overlapAllowedReason = "GBLENS_OVERLAP=off";
  else if (!ctx.features.timelineSemaphore)
    r.overlapAllowedReason = "the device lacks timeline semaphores";
  else if (mode == "on")
    r.overlapAllowed = true, r.overlapAllowedReason = asyncCompute
                                 ? "GBLENS_OVERLAP=on: the compute part on the compute queue, beside the next visibility pass"
                                 : "GBLENS_OVERLAP=on: no compute-only queue family, the two parts submitted apart to the one queue";
  else if (ctx.isCpu)
    r.overlapAllowedReason = "auto: a CPU device runs one part at a time";
  else if (!asyncCompute)
    r.overlapAllowedReason = "auto: the device has no compute-only queue family";
  else
    r.overlapAllowed = true, r.overlapAllowedReason = "auto: a GPU device with a compute queue: the compute part runs there, "
                                                       "beside the next frame's visibility pass";
}

bool overlapFrame(const Renderer& r, std::string& reason) {
  if (!r.overlapAllowed) return reason = r.overlapAllowedReason, false;
  if (!r.visibility) return reason = "the G-buffer pass shades materials: only a visibility pass overlaps", false;
  GB_ASSERT(r.method != Method::Forward);
  reason = r.overlapAllowedReason;
  return true;
}

bool overlapRecorded(Renderer& r, const FrameGraph& graph) {
  if (!r.overlap) return false;
  const std::string raster = graph.rasterOutsideSide();
  if (raster.empty()) return true;
  r.overlap = false;
  r.overlapReason = "the compute part has a raster pass (" + raster + "), which the compute queue cannot run";
  return false;
}

void useSlotTargets(Renderer& r) {
  if (!r.parked[0].image.image || r.targetsSlot == r.slot) return;
  static_assert(kFrameSlots == 2, "one parked image per slot target");
  for (size_t i = 0; i < kSlotTargets.size(); ++i) std::swap(r.targets[size_t(kSlotTargets[i])], r.parked[i]);
  r.targetsSlot = r.slot;
}

}  // namespace gb
