// The state of a sequence's temporal views (app/viewer/temporal_views.cpp: the views, their images,
// the hover; temporal_work.cpp: the motion check and flicker workers): private to app/viewer.
#pragma once
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <string>

#include "app/viewer/viewer.h"
#include "views/analysis/temporal.h"

namespace gb {

// The workers (futures, progress), the last results and their maps as decoded view images.
struct TemporalWork {
  struct MotionResult {
    MotionPair pair;
    size_t index = 0;  // the frame shown it is of (the pair index - 1 -> index)
    bool cancelled = false;
    std::string error;
  };
  std::future<MotionResult> motionJob;
  std::shared_ptr<WorkProgress> motionProgress;
  std::chrono::steady_clock::time_point motionStart;
  int wanted = -1;                  // the frame the motion views should be of (the frame shown)
  std::optional<MotionResult> motion;  // the last result kept (of `wanted` when current)
  CpuImage motionError, motionClass;   // its maps as decoded view images
  struct FlickerResult {
    FlickerReport report;
    size_t index = 0;  // the reference frame
    std::string error;
  };
  std::future<FlickerResult> flickerJob;
  std::shared_ptr<WorkProgress> flickerProgress;  // frames done
  std::chrono::steady_clock::time_point flickerStart;
  std::optional<FlickerResult> flicker;
  ViewDef flickerOf;                    // the view it was run on
  CpuImage flickerStddev, flickerMaxStep;
};

// The class map's values (motion.h MotionPair::classMap) as the legend and the hover name them.
extern const std::vector<std::string> kMotionClassNames;

// An f32 map of `n` channels as a decoded view image (RGBA32F; NaN: the empty texel, nothing there).
CpuImage decodedFloats(const CpuImage& map, uint32_t n, const std::string& name);
CpuImage decodedClasses(const CpuImage& map);  // the u32 class map as the id view's image
// A result came: the images uploaded again; `newViews` (flicker's first maps) rebuild the view list.
void refreshTemporalViews(Viewer& v, bool newViews);

}  // namespace gb
