// The timeline's work common to a sequence and an attached stream's kept frames (timeline.h).
#include "app/viewer/timeline.h"

#include "app/viewer/viewer.h"
#include "views/analysis/probe_track.h"

namespace gb {

void fillTimelineFrames(ViewerModel::TimelineUi& t, const TimelineFrames& frames, size_t shown) {
  t.on = true;
  t.numbers.clear(), t.times.clear();
  for (size_t i = 0; i < frames.count(); ++i) t.numbers.push_back(frames.number(i)), t.times.push_back(frames.time(i));
  t.shown = int(shown);
  t.cached = frames.inMemory();
}

void followTimelineProbe(Viewer& v, size_t i) {
  ViewerModel& m = v.model;
  if (!m.probePixel) return;
  const bool followed = m.track && i < m.track->texels.size() && m.track->texels[i];
  probeCapturePixel(v, followed ? *m.track->texels[i] : *m.probePixel);
  m.probeNote = followed || !m.track ? ""
                                     : "the probed point is not followed into this frame (" +
                                           (i < m.track->first ? m.track->stopBefore : m.track->stopAfter) + "): the same pixel";
}

void trackTimelineProbe(Viewer& v, TimelineFrames& frames) {
  ViewerModel& m = v.model;
  if (!m.probePixel || m.views.empty()) return;
  // The values plotted: the view last used (clicked in), else the first that decodes a quantity.
  int k = m.edited >= 0 && size_t(m.edited) < m.views.size() ? m.edited : 0;
  if (m.views[size_t(k)].quantity < 0)
    for (size_t j = 0; j < m.views.size(); ++j)
      if (m.views[j].quantity >= 0) {
        k = int(j);
        break;
      }
  const size_t shown = size_t(m.timeline.shown);
  const TrackFrames get = [&v, &frames, shown](size_t i) -> std::shared_ptr<const FrameSnapshot> {
    if (i == shown) return std::shared_ptr<const FrameSnapshot>(std::shared_ptr<void>(), &v.captureA.frame);  // not owned
    std::string error;
    return frames.frame(i, error);
  };
  const TrackJitters jitters = [&frames](size_t i) { return i < frames.count() ? frames.jitter(i) : std::nullopt; };
  m.track = trackProbe(frames.count(), get, shown, *m.probePixel, m.views[size_t(k)], jitters);
  m.timeline.cached = frames.inMemory();
  m.probeNote.clear();
  nlohmann::json j = trackJson(*m.track);
  j["event"] = "track";
  j["frames"] = m.timeline.numbers;
  logLine(v.eventLog, j);
}

}  // namespace gb
