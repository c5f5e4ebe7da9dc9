// The timeline on an attached stream's kept frames (gblens attach --history K, docs/attach.md): the
// strip of a sequence (views/ui/timeline_panel.cpp) over LiveReceiver::history(). While the stream
// runs the strip sits on the newest frame and holds only the kept frames' numbers; frozen (Space, or
// a step or the slider, which freeze it), the viewer holds the kept frames as they were (shared with
// the session's history once the receiver has stopped taking frames: at most K frames' texels, plus
// the copy shown) and shows any of them as a streamed frame is shown; the probe follows its point through them
// (no jitter known: none). Running again drops them and the track; the next frame taken is the newest.
#include <algorithm>

#include "app/viewer/timeline.h"
#include "app/viewer/viewer.h"

namespace gb {

struct LiveHistoryFrames : TimelineFrames {
  std::vector<HistoryFrame> kept;  // oldest first
  size_t count() const override { return kept.size(); }
  int64_t number(size_t i) const override { return int64_t(kept[i].appFrame); }
  std::optional<double> time(size_t i) const override {  // seconds before the newest kept frame's end
    return double(int64_t(kept[i].endNs) - int64_t(kept.back().endNs)) * 1e-9;  // 0 for the newest
  }
  std::shared_ptr<const FrameSnapshot> frame(size_t i, std::string&) override { return kept[i].frame; }
  size_t inMemory() const override { return kept.size(); }
};

namespace {

LiveHistoryFrames keptFrames(Viewer& v) {
  LiveHistoryFrames f;
  f.kept = v.receiver->history();
  return f;
}

size_t indexOf(const LiveHistoryFrames& f, uint64_t appFrame) {
  for (size_t i = 0; i < f.kept.size(); ++i)
    if (f.kept[i].appFrame == appFrame) return i;
  return f.kept.empty() ? 0 : f.kept.size() - 1;
}

void logKept(Viewer& v, const char* state) {
  const ViewerModel& m = v.model;
  const ViewerModel::TimelineUi& t = m.timeline;
  const size_t i = size_t(t.shown);
  logLine(v.eventLog, {{"event", "history_frame"},
                       {"state", state},
                       {"index", i},
                       {"app_frame", i < t.numbers.size() ? nlohmann::json(t.numbers[i]) : nlohmann::json()},
                       {"frames", t.numbers},
                       {"limit", t.cacheLimit},
                       {"bytes", t.historyBytes},
                       {"probe", m.probePixel ? nlohmann::json::array({m.probePixel->x, m.probePixel->y}) : nlohmann::json()}});
}

void fill(Viewer& v, const LiveHistoryFrames& f, size_t shown) {
  ViewerModel::TimelineUi& t = v.model.timeline;
  fillTimelineFrames(t, f, shown);
  t.historyBytes = 0;
  for (const HistoryFrame& h : f.kept) t.historyBytes += h.bytes;
}

// Kept frame i on screen as a streamed frame is (the views kept), the probe along its track.
void showKept(Viewer& v, size_t i) {
  const HistoryFrame& h = v.liveHistory->kept[i];
  LiveFrameInfo info;
  info.stream = h.stream;
  info.appFrame = h.appFrame;
  info.endNs = h.endNs;
  v.captureA.frame = FrameSnapshot{};
  showStreamFrame(v, FrameSnapshot(*h.frame), info, true);
  v.model.timeline.shown = int(i);
  followTimelineProbe(v, i);
  v.model.uiChanged = true;
  logKept(v, "frozen");
}

// Frozen: the kept frames held, the newest shown where the viewer had not taken it yet.
bool freeze(Viewer& v) {
  auto f = std::make_shared<LiveHistoryFrames>(keptFrames(v));
  if (f->kept.empty()) return false;
  v.liveHistory = f;
  fill(v, *f, indexOf(*f, v.attachInfo.appFrame));
  if (f->kept.back().appFrame != v.attachInfo.appFrame) showKept(v, f->kept.size() - 1);
  else logKept(v, "frozen");
  trackTimelineProbe(v, *f);  // a probe made while it ran: followed through the kept frames now
  return true;
}

void thaw(Viewer& v) {
  ViewerModel& m = v.model;
  v.liveHistory.reset();
  m.track.reset();
  m.probeNote.clear();
  logKept(v, "live");
}

}  // namespace

bool updateLiveTimeline(Viewer& v) {
  ViewerModel& m = v.model;
  ViewerModel::TimelineUi& t = m.timeline;
  const LiveReceiver::State st = v.receiver->state();
  const size_t limit = st.historyLimit;
  if (limit == 0) return false;
  t.history = true;
  t.dir = "attach";
  t.cacheLimit = limit;
  if (t.requested >= 0 && m.playing) m.playing = false;  // a step or the slider freezes the stream
  if (m.playing) {
    if (v.liveHistory) thaw(v);
    if (v.liveNumbersFor == v.framesShown && t.on) return false;
    v.liveNumbersFor = v.framesShown;  // a new frame taken: the kept frames' numbers (none held)
    const LiveHistoryFrames f = keptFrames(v);
    if (f.kept.empty()) return false;
    fill(v, f, indexOf(f, v.attachInfo.appFrame));
    return true;
  }
  if (!v.liveHistory) {
    // Frozen once the receiver takes no more frames (it may finish one after the pause): the kept
    // frames are then the session's own, no more than K.
    if (v.attachPlaying || st.receiving) return true;  // another look soon
    if (!freeze(v)) return false;
    v.liveNumbersFor = 0;
  }
  if (t.requested < 0) return false;
  const int i = std::clamp(t.requested, 0, int(v.liveHistory->kept.size()) - 1);
  t.requested = -1;
  if (i != t.shown) showKept(v, size_t(i));
  return true;
}

void trackLiveProbe(Viewer& v) {
  if (!v.model.attach.on) return;
  if (v.liveHistory)
    trackTimelineProbe(v, *v.liveHistory);
  else
    v.model.track.reset();  // the stream runs: its frames move on
}

}  // namespace gb
