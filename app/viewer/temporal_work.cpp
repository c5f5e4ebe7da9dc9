// The workers of a sequence's temporal views (temporal_views.cpp has the views): the motion check of
// the pair ending at the frame shown, restarted when the frame changes (a running check is cancelled:
// its result dropped), on frames of the sequence's cache; the flicker of a view over the whole
// sequence on request (the button, F), the frames read by flickerSequence itself. Results are logged
// (motion_pair, flicker) and become the views' images.
#include <cstdio>

#include "app/viewer/temporal_work.h"

namespace gb {

static TemporalWork& work(Viewer& v) {
  if (!v.temporal) v.temporal = std::make_shared<TemporalWork>();
  return *v.temporal;
}

// ---- the motion check ----------------------------------------------------------------------------

static TemporalFrame temporalFrame(const Viewer& v, size_t i, const std::shared_ptr<const Capture>& c) {
  const SequenceFrame& f = openedSequence(v).frames[i];
  return TemporalFrame{&c->frame, f.number, f.time, f.jitter};
}

// Starts the check of the pair (i - 1 -> i), with i - 2 for the lag hypothesis, on frames of the cache.
static void startMotion(Viewer& v, TemporalWork& w, size_t i) {
  std::string error;
  std::shared_ptr<const Capture> cur = sequenceFrame(v, i, error), prev = cur ? sequenceFrame(v, i - 1, error) : nullptr;
  std::shared_ptr<const Capture> before = prev && i >= 2 ? sequenceFrame(v, i - 2, error) : nullptr;
  auto progress = std::make_shared<WorkProgress>();
  w.motionProgress = progress;
  w.motionStart = std::chrono::steady_clock::now();
  const TemporalFrame tc = cur ? temporalFrame(v, i, cur) : TemporalFrame{}, tp = prev ? temporalFrame(v, i - 1, prev) : TemporalFrame{};
  const std::optional<TemporalFrame> tb = before ? std::optional(temporalFrame(v, i - 2, before)) : std::nullopt;
  w.motionJob = std::async(std::launch::async, [cur, prev, before, tc, tp, tb, i, error, progress]() {
    TemporalWork::MotionResult r;
    r.index = i;
    if (!cur || !prev) {
      r.error = "the motion check needs frames " + std::to_string(tp.number) + " and " + std::to_string(tc.number) + ": " + error;
      return r;
    }
    if (progress->cancelled()) {
      r.cancelled = true;
      return r;
    }
    MotionPairOptions o;
    o.motion = cur->frame.layout.find(QuantityKind::Motion);
    r.pair = checkMotionPair(tp, tc, tb ? &*tb : nullptr, o);
    r.cancelled = progress->cancelled();  // superseded while it ran: dropped
    return r;
  });
}

// The convention's fields in words; a field the frames do not decide says so.
static std::string conventionWords(const MotionConvention& c, const MotionDecided& d) {
  const nlohmann::json j = conventionJson(c, &d);
  std::string out;
  for (const char* field : {"units", "direction", "y", "scale", "jitter", "lag"}) {
    const nlohmann::json& f = j[field];
    out += (out.empty() ? "" : ", ") + std::string(field) + " " + (f.is_null() ? "undecided" : f.is_string() ? f.get<std::string>() : f.dump());
  }
  return out;
}

// The pair's verdict as the strip says it: each difference in words, or agrees, or undecided and why.
static std::string verdictLine(const MotionPair& p) {
  std::string out = "Motion " + std::to_string(p.previous) + " -> " + std::to_string(p.current) + ": ";
  if (!p.detected) return out + "undecided: " + p.undecided;
  if (p.differences.empty()) out += "agrees with the layout";
  for (size_t k = 0; k < p.differences.size(); ++k) out += (k ? "; " : "") + p.differences[k];
  char stats[160];
  const double surface = std::max<double>(1.0, double(p.surfacePixels));
  std::snprintf(stats, sizeof stats, " | detected %s | static %.0f %%, wrong %.1f %%", conventionWords(p.found, p.decided).c_str(),
                100.0 * double(p.staticPixels) / surface, 100.0 * double(p.wrongMoving) / surface);
  return out + stats;
}

static std::string lineOf(const TemporalWork::MotionResult& r) { return r.error.empty() ? verdictLine(r.pair) : "Motion: " + r.error; }

static void finishMotion(Viewer& v, TemporalWork& w) {
  TemporalWork::MotionResult r = w.motionJob.get();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w.motionStart).count();
  if (r.cancelled || int(r.index) != w.wanted) {
    logLine(v.eventLog, {{"event", "motion_pair_cancelled"}, {"index", r.index}, {"seconds", seconds}});
    return;
  }
  ViewerModel::TimelineUi& t = v.model.timeline;
  t.motionComputing = false;
  t.motionLine = lineOf(r);
  if (r.error.empty()) {
    w.motionError = decodedFloats(r.pair.errorMap, 1, "Motion error");
    w.motionClass = decodedClasses(r.pair.classMap);
  }
  nlohmann::json j = {{"event", "motion_pair"}, {"index", r.index}, {"line", t.motionLine}, {"seconds", seconds}};
  if (r.error.empty()) j["pair"] = motionPairJson(r.pair);
  logLine(v.eventLog, j);
  w.motion = std::move(r);
  refreshTemporalViews(v, false);
}

// The motion views follow the frame shown: a new frame cancels the running check and starts its own.
static bool updateMotion(Viewer& v, TemporalWork& w) {
  ViewerModel::TimelineUi& t = v.model.timeline;
  if (!v.captureA.frame.layout.find(QuantityKind::Motion)) return t.motionLine.clear(), false;
  if (t.shown != w.wanted) {
    w.wanted = t.shown;
    if (w.motionJob.valid()) w.motionProgress->cancel = true;
    t.motionComputing = t.shown > 0;
    t.motionLine = t.shown > 0 ? "Motion " + std::to_string(t.numbers[size_t(t.shown) - 1]) + " -> " +
                                     std::to_string(t.numbers[size_t(t.shown)]) + ": checking ..."
                               : "Motion: frame " + std::to_string(t.numbers[0]) + " is the first: no previous frame to check against";
    if (w.motion && int(w.motion->index) == t.shown) t.motionLine = lineOf(*w.motion), t.motionComputing = false;  // kept
  }
  if (w.motionJob.valid() && w.motionJob.wait_for(std::chrono::seconds(0)) == std::future_status::ready) finishMotion(v, w);
  const bool done = w.motion && int(w.motion->index) == w.wanted;
  if (!w.motionJob.valid() && w.wanted > 0 && !done) startMotion(v, w, size_t(w.wanted));
  return w.motionJob.valid();
}

// ---- flicker -------------------------------------------------------------------------------------

// The view the Flicker button runs on: the one shown (grid: the one last used), if it decodes a quantity.
static const ViewDef* flickerView(const ViewerModel& m) {
  const int k = m.layout == LayoutMode::Grid ? m.edited : m.primary;
  if (k < 0 || size_t(k) >= m.views.size()) return nullptr;
  const ViewDef& d = m.views[size_t(k)];
  return d.quantity >= 0 && d.spreadOf < 0 && !d.sun ? &d : nullptr;
}

static void startFlicker(Viewer& v, TemporalWork& w, const ViewDef& view) {
  const size_t i = size_t(v.model.timeline.shown);
  FlickerOptions o;
  o.quantity = view.name;
  o.reference = v.model.timeline.numbers[i];
  auto progress = std::make_shared<WorkProgress>();
  progress->total = v.model.timeline.numbers.size();
  o.progress = [p = progress.get()](const std::string&) { p->done++; };
  w.flickerProgress = progress;
  w.flickerStart = std::chrono::steady_clock::now();
  w.flickerOf = view;
  w.flickerJob = std::async(std::launch::async, [seq = openedSequence(v), o, i]() {
    TemporalWork::FlickerResult r;
    r.index = i;
    if (!flickerSequence(seq, o, r.report, r.error) && r.error.empty()) r.error = "flicker failed";
    return r;
  });
}

static void finishFlicker(Viewer& v, TemporalWork& w) {
  TemporalWork::FlickerResult r = w.flickerJob.get();
  ViewerModel::TimelineUi& t = v.model.timeline;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w.flickerStart).count();
  t.flickerComputing = false;
  if (!r.error.empty()) {
    t.flickerLine = "flicker: " + r.error;
    logLine(v.eventLog, {{"event", "flicker"}, {"error", r.error}, {"seconds", seconds}});
    return;
  }
  char line[200];
  std::snprintf(line, sizeof line, "flicker of %s at frame %lld: mean stddev %.4g, p99 %.4g, largest step %.4g (%zu frames)",
                r.report.quantity.c_str(), (long long)r.report.reference, r.report.meanStddev, r.report.p99Stddev,
                r.report.maxStepAll, r.report.frames);
  t.flickerLine = line;
  w.flickerStddev = decodedFloats(r.report.stddev, r.report.components, "Flicker stddev");
  w.flickerMaxStep = decodedFloats(r.report.maxStep, r.report.components, "Flicker max step");
  nlohmann::json j = flickerReportJson(r.report);
  j["event"] = "flicker", j["index"] = r.index, j["seconds"] = seconds;
  logLine(v.eventLog, j);
  w.flicker = std::move(r);
  refreshTemporalViews(v, true);
}

static bool updateFlicker(Viewer& v, TemporalWork& w) {
  ViewerModel::TimelineUi& t = v.model.timeline;
  const ViewDef* view = flickerView(v.model);
  t.flickerOf = view ? view->name : "";
  if (t.flickerRequested && view && !w.flickerJob.valid()) {
    startFlicker(v, w, *view);
    t.flickerComputing = true;
    t.flickerLine = "flicker of " + view->name + ": 0 of " + std::to_string(t.numbers.size()) + " frames";
  }
  t.flickerRequested = false;
  if (!w.flickerJob.valid()) return false;
  if (w.flickerJob.wait_for(std::chrono::seconds(0)) == std::future_status::ready) return finishFlicker(v, w), false;
  const std::string line = "flicker of " + w.flickerOf.name + ": " + std::to_string(w.flickerProgress->done.load()) + " of " +
                           std::to_string(w.flickerProgress->total.load()) + " frames";
  if (line != t.flickerLine) t.flickerLine = line, v.model.uiChanged = true;
  return true;
}

bool updateTemporalViews(Viewer& v) {
  if (!v.sequence) return false;
  TemporalWork& w = work(v);
  const bool motion = updateMotion(v, w);
  return updateFlicker(v, w) || motion;
}

void stopTemporalViews(Viewer& v) {
  if (!v.temporal) return;
  TemporalWork& w = *v.temporal;
  if (w.motionProgress) w.motionProgress->cancel = true;
  if (w.motionJob.valid()) w.motionJob.wait();
  if (w.flickerJob.valid()) w.flickerJob.wait();
}

}  // namespace gb
