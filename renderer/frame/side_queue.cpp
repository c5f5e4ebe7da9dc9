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
  if (mode == "off") {
    r.overlapAllowed = false;
    r.overlapAllowedReason = "GBLENS_OVERLAP=off";
  } else if (mode == "on") {
    r.overlapAllowed = true;
    r.overlapAllowedReason = ctx.sideQueue != ctx.queue
                                 ? "GBLENS_OVERLAP=on: the visibility pass on a second queue, beside the previous frame"
                                 : "GBLENS_OVERLAP=on: the visibility pass submitted apart, on the device's one queue";
  } else if (mode == "auto") {
    r.overlapAllowed = !ctx.isCpu && ctx.sideQueue != ctx.queue;
    r.overlapAllowedReason = ctx.isCpu ? "auto: a CPU device runs one part at a time"
                             : r.overlapAllowed ? "auto: a GPU device with a second queue: the visibility pass runs "
                                                  "there, beside the previous frame"
                                                : "auto: the device's graphics family has one queue";
  } else {
    std::fprintf(stderr, "gblens: GBLENS_OVERLAP=%s: auto, on or off (the visibility pass beside the previous frame)\n",
                 v);
    std::exit(2);
  }
}

bool overlapFrame(const Renderer& r, std::string& reason) {
  if (!r.overlapAllowed) return reason = r.overlapAllowedReason, false;
  if (!r.visibility) return reason = "the G-buffer pass shades materials: only a visibility pass overlaps", false;
  GB_ASSERT(r.method != Method::Forward);
  reason = r.overlapAllowedReason;
  return true;
}

void useSlotTargets(Renderer& r) {
  if (!r.parked[0].image.image || r.targetsSlot == r.slot) return;
  static_assert(kFrameSlots == 2, "one parked image per slot target");
  for (size_t i = 0; i < kSlotTargets.size(); ++i) std::swap(r.targets[size_t(kSlotTargets[i])], r.parked[i]);
  r.targetsSlot = r.slot;
}

}  // namespace gb
