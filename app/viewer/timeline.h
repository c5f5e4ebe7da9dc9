// What the viewer's timeline goes over (docs/temporal.md "Viewer timeline"): frames by index, each
// with its number and time. A sequence (sequence.cpp: its frames loaded through a bounded cache) and
// an attached stream's kept frames (live_timeline.cpp: attach --history K) both implement it; the
// strip (views/ui/timeline_panel.cpp), the probe's track and the probe following it are written once
// over it (timeline.cpp).
#pragma once
#include <cstdint>
#include <memory>
#include <optional>
#include <string>

#include <glm/glm.hpp>

#include "renderer/core/snapshot.h"
#include "views/ui/viewer_model.h"

namespace gb {

struct Viewer;

class TimelineFrames {
 public:
  virtual ~TimelineFrames() = default;
  virtual size_t count() const = 0;
  virtual int64_t number(size_t i) const = 0;                  // the frame's number (SEQ@N; the application's frame)
  virtual std::optional<double> time(size_t i) const = 0;      // seconds, where known
  virtual std::optional<glm::dvec2> jitter(size_t) const { return std::nullopt; }  // pixels; none: not known
  // Frame i (shared: a cache may drop it while a caller still reads it); null with `error`.
  virtual std::shared_ptr<const FrameSnapshot> frame(size_t i, std::string& error) = 0;
  virtual size_t inMemory() const = 0;  // frames held now (the strip says it)
};

// The strip's frames: every frame's number and time, `shown` the one on screen.
void fillTimelineFrames(ViewerModel::TimelineUi& t, const TimelineFrames& frames, size_t shown);
// After frame i came on screen: the probe moved to where its track puts the point there (else the
// same pixel, with a note).
void followTimelineProbe(Viewer& v, size_t i);
// After a probe of the frame shown: the point followed through the other frames (model.track), the
// values of the view last used; logged as `track` with the frames' numbers.
void trackTimelineProbe(Viewer& v, TimelineFrames& frames);

}  // namespace gb
