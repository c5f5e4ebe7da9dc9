// Sequences in the viewer (gblens view SEQ, SEQ@N; views/capture/sequence.h): one frame shown as a
// capture is, the timeline's state in the model (views/ui/timeline_panel.cpp draws it), frames loaded
// lazily into a bounded cache, played at the sequence's rate, and the probe's point followed through
// the frames (views/analysis/probe_track.h). Changing frame keeps the views, zoom, pan and the view
// selected (setCaptureViews keeps the settings of views of the same name).
#include <algorithm>
#include <charconv>
#include <filesystem>

#include "app/viewer/timeline.h"
#include "app/viewer/viewer.h"
#include "views/analysis/probe.h"
#include "views/analysis/probe_track.h"
#include "views/analysis/sample_views.h"
#include "views/capture/sequence.h"

namespace gb {

// At most this many frames of a sequence are held in memory at once (the least recently used one
// goes first); the frame shown is a copy of one of them (captureA). README and docs/temporal.md say so.
constexpr size_t kSequenceCacheFrames = 8;

struct SequenceSource : TimelineFrames {
  Sequence seq;
  struct Cached {
    size_t index = 0;
    std::shared_ptr<const Capture> capture;
    uint64_t used = 0;
  };
  std::vector<Cached> cache;
  uint64_t clock = 0;
  double played = 0.0;  // seconds since the frame shown was shown, while playing

  size_t count() const override { return seq.frames.size(); }
  int64_t number(size_t i) const override { return seq.frames[i].number; }
  std::optional<double> time(size_t i) const override { return seq.frames[i].time; }
  std::optional<glm::dvec2> jitter(size_t i) const override { return seq.frames[i].jitter; }
  std::shared_ptr<const FrameSnapshot> frame(size_t i, std::string& error) override;
  size_t inMemory() const override { return cache.size(); }
};

// "SEQ@N" split into SEQ and N; false when `text` has no such form.
static bool splitFrame(const std::string& text, std::string& dir, int64_t& number) {
  const size_t at = text.rfind('@');
  if (at == std::string::npos || at == 0 || at + 1 == text.size()) return false;
  const char* b = text.data() + at + 1;
  const char* e = text.data() + text.size();
  auto r = std::from_chars(b, e, number);
  if (r.ec != std::errc() || r.ptr != e) return false;
  dir = text.substr(0, at);
  return true;
}

bool sequenceArgument(const std::string& text) {
  if (isSequence(text)) return true;
  std::string dir;
  int64_t number = 0;
  std::error_code ec;
  return !std::filesystem::is_directory(text, ec) && splitFrame(text, dir, number) && isSequence(dir);
}

// Frame i from the cache, else loaded (evicting the least recently used beyond the limit).
static std::shared_ptr<const Capture> cachedFrame(SequenceSource& s, size_t i, std::string& error) {
  ++s.clock;
  for (SequenceSource::Cached& c : s.cache)
    if (c.index == i) {
      c.used = s.clock;
      return c.capture;
    }
  auto capture = std::make_shared<Capture>();
  if (!loadCapture(s.seq.captureDir(i), *capture, error)) return nullptr;
  if (s.cache.size() >= kSequenceCacheFrames)
    s.cache.erase(std::min_element(s.cache.begin(), s.cache.end(), [](const auto& a, const auto& b) { return a.used < b.used; }));
  s.cache.push_back({i, capture, s.clock});
  return capture;
}

std::shared_ptr<const FrameSnapshot> SequenceSource::frame(size_t i, std::string& error) {
  const std::shared_ptr<const Capture> c = cachedFrame(*this, i, error);
  return c ? std::shared_ptr<const FrameSnapshot>(c, &c->frame) : nullptr;
}

std::shared_ptr<const Capture> sequenceFrame(Viewer& v, size_t i, std::string& error) {
  if (!v.sequence || i >= v.sequence->seq.frames.size()) return error = "no such frame", nullptr;
  std::shared_ptr<const Capture> c = cachedFrame(*v.sequence, i, error);
  v.model.timeline.cached = v.sequence->cache.size();
  return c;
}

const Sequence& openedSequence(const Viewer& v) { return v.sequence->seq; }

// How long frame i stays on screen while playing: to the next frame's time when both are known.
static double frameSeconds(const ViewerModel::TimelineUi& t, size_t i) {
  if (i + 1 < t.times.size() && t.times[i] && t.times[i + 1] && *t.times[i + 1] > *t.times[i]) return *t.times[i + 1] - *t.times[i];
  return 1.0 / t.fps;
}

static void fillTimeline(Viewer& v, size_t shown) {
  ViewerModel::TimelineUi& t = v.model.timeline;
  fillTimelineFrames(t, *v.sequence, shown);
  t.dir = v.sequence->seq.dir;
  t.cacheLimit = kSequenceCacheFrames;
  // The rate: the frames' mean rate when every frame has a time, else 30 fps.
  const bool timed = t.times.size() > 1 && std::all_of(t.times.begin(), t.times.end(), [](const auto& x) { return x.has_value(); });
  const double span = timed ? *t.times.back() - *t.times.front() : 0.0;
  t.fpsFromTimes = timed && span > 0.0;
  t.fps = t.fpsFromTimes ? double(t.times.size() - 1) / span : 30.0;
}

static void logShown(Viewer& v) {
  const ViewerModel& m = v.model;
  const ViewerModel::TimelineUi& t = m.timeline;
  const size_t i = size_t(t.shown);
  logLine(v.eventLog, {{"event", "sequence_frame"},
                       {"index", i},
                       {"frame", t.numbers[i]},
                       {"time", t.times[i] ? nlohmann::json(*t.times[i]) : nlohmann::json()},
                       {"frames", t.numbers.size()},
                       {"cached", t.cached},
                       {"probe", m.probePixel ? nlohmann::json::array({m.probePixel->x, m.probePixel->y}) : nlohmann::json()}});
}

bool openSequence(Viewer& v, std::string& error) {
  std::string dir = v.args.capture;
  int64_t number = 0;
  const bool named = !isSequence(dir) && splitFrame(v.args.capture, dir, number);
  v.sequence = std::make_shared<SequenceSource>();
  if (!loadSequence(dir, v.sequence->seq, error)) return false;
  const Sequence& seq = v.sequence->seq;
  const int start = named ? seq.find(number) : 0;
  if (start < 0) {
    error = v.args.capture + ": the sequence has no frame " + std::to_string(number) + " (frames " +
            std::to_string(seq.frames.front().number) + ".." + std::to_string(seq.frames.back().number) + ")";
    return false;
  }
  const std::shared_ptr<const Capture> c = cachedFrame(*v.sequence, size_t(start), error);
  if (!c) return false;
  v.captureA = *c;
  fillTimeline(v, size_t(start));
  logShown(v);
  return true;
}

// Shows frame i: the views decoded again (the same views, zoom and pan), the probe moved to where its
// track puts the point in that frame (else the same pixel, with a note), the region recomputed.
static void showFrame(Viewer& v, size_t i) {
  ViewerModel& m = v.model;
  ViewerModel::TimelineUi& t = m.timeline;
  std::string error;
  const std::shared_ptr<const Capture> c = cachedFrame(*v.sequence, i, error);
  t.cached = v.sequence->cache.size();
  if (!c) {
    t.status = "frame " + std::to_string(t.numbers[i]) + ": " + error;
    logLine(v.eventLog, {{"event", "sequence_error"}, {"index", i}, {"error", t.status}});
    return;
  }
  v.captureA = *c;
  if (m.sampleShown && frameSamples(v.captureA.frame) > 1)
    showSample(v.captureA.frame, m.sampleShown % uint32_t(frameSamples(v.captureA.frame)));
  t.shown = int(i);
  t.status.clear();
  v.framesShown++;  // the shadow marks are counted again for the new frame
  m.captureInfo = describeCapture(v.captureA);
  v.renderer.camera = v.captureA.frame.camera;
  m.rendered = v.captureA.frame.options;
  setCaptureViews(v);
  m.regionDirty = m.region.has_value();
  followTimelineProbe(v, i);
  m.uiChanged = true;
  logShown(v);
}

bool updateSequence(Viewer& v, double dt) {
  if (!v.sequence) return false;
  ViewerModel::TimelineUi& t = v.model.timeline;
  SequenceSource& s = *v.sequence;
  const int n = int(t.numbers.size());
  if (t.playing && n > 1) {
    s.played += dt;
    const double due = frameSeconds(t, size_t(t.shown));
    if (s.played >= due) {
      s.played = std::min(s.played - due, due);  // late frames are not caught up in a burst
      if (t.requested < 0) t.requested = (t.shown + 1) % n;  // plays in a loop
    }
  } else {
    s.played = 0.0;
  }
  if (t.requested >= 0) {
    const int i = std::clamp(t.requested, 0, n - 1);
    t.requested = -1;
    if (i != t.shown) showFrame(v, size_t(i));
  }
  return t.playing && n > 1;
}

void trackSequenceProbe(Viewer& v) {
  if (v.sequence) trackTimelineProbe(v, *v.sequence);
}

}  // namespace gb
