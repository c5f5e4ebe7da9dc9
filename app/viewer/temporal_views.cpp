// A sequence's temporal views (gblens view SEQ; docs/temporal.md "Viewer timeline"): the motion check
// of the pair ending at the frame shown (views/analysis/motion.h checkMotionPair, as `gblens motion`
// checks each pair) and the flicker of a view over the whole sequence (temporal.h flickerSequence, as
// `gblens flicker`), each computed in a worker thread from frames of the sequence's cache. Their maps
// are views of the frame (quantity -1), appended to its views as reference_error.cpp appends the
// reference error's: decoded images drawn, hovered and probed like a capture's. The strip's second
// row (views/ui/timeline_panel.cpp) says the pair's verdict in words and holds the Flicker button.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <future>

#include "app/viewer/viewer.h"
#include "views/analysis/temporal.h"
#include "views/analysis/visualize.h"

namespace gb {

// The class map's values (motion.h MotionPair::classMap) as the legend and the hover name them.
static const std::vector<std::string> kClassNames = {"none", "static", "moving", "disoccluded", "wrong"};
static const char* const kClassWhy[] = {
    "no surface", "agrees with the camera's motion, the previous frame holds the point",
    "disagrees, and the previous frame shows the same surface where the vector points",
    "the point was off screen or hidden in the previous frame",
    "the vector lands on another surface (or says static where the previous frame saw something else)"};

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

static TemporalWork& work(Viewer& v) {
  if (!v.temporal) v.temporal = std::make_shared<TemporalWork>();
  return *v.temporal;
}

static const Quantity* motionQuantity(const Viewer& v) { return v.captureA.frame.layout.find(QuantityKind::Motion); }

// ---- the views and their images ----------------------------------------------------------------

void appendTemporalViews(const Viewer& v, std::vector<ViewDef>& views) {
  if (!v.sequence) return;
  if (motionQuantity(v)) {
    ViewDef e;
    e.name = "Motion error";
    e.kind = QuantityKind::Count, e.visual = Visual::Count;  // the heat map, from 0 to the largest error
    e.componentNames = {"error"};
    e.channels = 0x1, e.autoRange = true, e.negativeSuspicious = false;
    e.unit = "px: |stored - expected| under the layout's convention";
    e.space = "the motion check of the pair ending at this frame (gblens motion -o: pair_NNNN.exr motion.error)";
    views.push_back(e);
    ViewDef c;
    c.name = "Motion class";
    c.kind = QuantityKind::Id, c.visual = Visual::Id, c.integer = true;
    c.componentNames = {"class"};
    c.channels = 0x1, c.negativeSuspicious = false;
    c.space = "the motion check's pixel classes (gblens motion -o: motion.class)";
    views.push_back(c);
  }
  if (v.temporal && v.temporal->flicker) {
    const TemporalWork& w = *v.temporal;
    for (const char* name : {"Flicker stddev", "Flicker max step"}) {
      ViewDef d;
      d.name = name;
      d.kind = QuantityKind::Scalar, d.visual = Visual::Scalar;
      d.components = std::min(w.flicker->report.components, 4u);
      for (uint32_t c = 0; c < d.components; ++c)
        d.componentNames.push_back(c < w.flickerOf.componentNames.size() ? w.flickerOf.componentNames[c] : std::to_string(c));
      d.channels = 0x1, d.autoRange = true, d.falseColor = true, d.negativeSuspicious = false;
      d.unit = std::string(name == std::string("Flicker stddev") ? "temporal standard deviation" : "largest frame-to-frame change") +
               " of " + w.flickerOf.name;
      d.space = "gblens flicker --quantity " + w.flickerOf.name + ", at the reference frame's pixels";
      views.push_back(d);
    }
  }
}

// An f32 map of `n` channels as a decoded view image (RGBA32F); NaN -> the empty texel (nothing there).
static CpuImage decodedFloats(const CpuImage& map, uint32_t n, const std::string& name) {
  CpuImage img;
  img.name = name;
  img.width = map.width, img.height = map.height;
  img.channels = {"0", "1", "2", "3"};
  img.data.resize(size_t(map.width) * map.height * 16);
  uint32_t* out = reinterpret_cast<uint32_t*>(img.data.data());
  for (uint32_t y = 0; y < map.height; ++y)
    for (uint32_t x = 0; x < map.width; ++x) {
      uint32_t* t = out + (size_t(y) * map.width + x) * 4;
      const bool none = std::isnan(map.value(x, y, 0));
      for (uint32_t c = 0; c < 4; ++c) {
        const float f = c < n ? float(map.value(x, y, c)) : 0.0f;
        std::memcpy(&t[c], &f, 4);
        if (none) t[c] = gpu::kEmptyTexel;
      }
    }
  return img;
}

static CpuImage decodedClasses(const CpuImage& map) {
  CpuImage img = map;  // u32, one channel: what the GPU's id mapping reads
  img.name = "Motion class";
  img.encoding = Encoding::Uint;
  return img;
}

static std::string sizeNote(const CpuImage& img, const FrameSnapshot& f) {
  if (img.width == f.camera.width && img.height == f.camera.height) return "";
  return "computed for a " + std::to_string(img.width) + "x" + std::to_string(img.height) + " frame; this one is " +
         std::to_string(f.camera.width) + "x" + std::to_string(f.camera.height);
}

// Why the motion views cannot show the frame shown ("" they can).
static std::string motionStatus(const Viewer& v, const TemporalWork* w) {
  const ViewerModel::TimelineUi& t = v.model.timeline;
  const size_t i = size_t(t.shown);
  if (i == 0) return "frame " + std::to_string(t.numbers[0]) + " is the sequence's first: no previous frame to check its motion against";
  if (!w || !w->motion || w->motion->index != i)
    return "checking the motion of frames " + std::to_string(t.numbers[i - 1]) + " -> " + std::to_string(t.numbers[i]) + " ...";
  if (!w->motion->error.empty()) return w->motion->error;
  return sizeNote(w->motionError, v.captureA.frame);
}

void fillTemporalViews(Viewer& v) {
  ViewerModel& m = v.model;
  const TemporalWork* w = v.temporal.get();
  m.classNames["Motion class"] = kClassNames;
  for (size_t k = 0; k < m.views.size() && k < v.decodedA.size(); ++k) {
    const std::string& name = m.views[k].name;
    if (m.views[k].quantity >= 0) continue;
    v.decodedA[k] = CpuImage{};
    std::string& why = m.unavailable[k];
    if (name == "Motion error" || name == "Motion class") {
      why = motionStatus(v, w);
      if (why.empty()) v.decodedA[k] = name == "Motion error" ? w->motionError : w->motionClass;
    } else if (w && w->flicker && (name == "Flicker stddev" || name == "Flicker max step")) {
      const size_t ref = w->flicker->index;
      why = size_t(m.timeline.shown) == ref ? sizeNote(w->flickerStddev, v.captureA.frame)
                                            : "flicker of " + w->flickerOf.name + " at frame " + std::to_string(m.timeline.numbers[ref]) +
                                                  "'s pixels (its reference): show that frame, or F here for this one";
      if (why.empty()) v.decodedA[k] = name == "Flicker stddev" ? w->flickerStddev : w->flickerMaxStep;
    }
    v.rangeKeys.resize(m.views.size());
    v.rangeKeys[k].clear();  // the automatic range of the new image
  }
}

// The maps changed (a result came): the images uploaded again; new views (flicker) rebuild the list.
static void refreshViews(Viewer& v, bool newViews) {
  if (newViews) return setCaptureViews(v);
  fillTemporalViews(v);
  uploadViewImages(v.imagesA, v.ctx, v.decodedA);
  v.model.uiChanged = true;
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

static void finishMotion(Viewer& v, TemporalWork& w) {
  TemporalWork::MotionResult r = w.motionJob.get();
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - w.motionStart).count();
  if (r.cancelled || int(r.index) != w.wanted) {
    logLine(v.eventLog, {{"event", "motion_pair_cancelled"}, {"index", r.index}, {"seconds", seconds}});
    return;
  }
  ViewerModel::TimelineUi& t = v.model.timeline;
  t.motionComputing = false;
  t.motionLine = r.error.empty() ? verdictLine(r.pair) : "Motion: " + r.error;
  if (r.error.empty()) {
    w.motionError = decodedFloats(r.pair.errorMap, 1, "Motion error");
    w.motionClass = decodedClasses(r.pair.classMap);
  }
  nlohmann::json j = {{"event", "motion_pair"}, {"index", r.index}, {"line", t.motionLine}, {"seconds", seconds}};
  if (r.error.empty()) j["pair"] = motionPairJson(r.pair);
  logLine(v.eventLog, j);
  w.motion = std::move(r);
  refreshViews(v, false);
}

// The motion views follow the frame shown: a new frame cancels the running check and starts its own.
static bool updateMotion(Viewer& v, TemporalWork& w) {
  ViewerModel::TimelineUi& t = v.model.timeline;
  if (!motionQuantity(v)) return t.motionLine.clear(), false;
  if (t.shown != w.wanted) {
    w.wanted = t.shown;
    if (w.motionJob.valid()) w.motionProgress->cancel = true;
    t.motionComputing = t.shown > 0;
    t.motionLine = t.shown > 0 ? "Motion " + std::to_string(t.numbers[size_t(t.shown) - 1]) + " -> " +
                                     std::to_string(t.numbers[size_t(t.shown)]) + ": checking ..."
                               : "Motion: frame " + std::to_string(t.numbers[0]) + " is the first: no previous frame to check against";
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
  refreshViews(v, true);
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

// ---- hover ---------------------------------------------------------------------------------------

std::string temporalHoverText(const Viewer& v, int view, glm::ivec2 texel) {
  const ViewerModel& m = v.model;
  if (view < 0 || size_t(view) >= m.views.size() || size_t(view) >= v.decodedA.size()) return "";
  const ViewDef& d = m.views[size_t(view)];
  const CpuImage& img = v.decodedA[size_t(view)];
  if (d.quantity >= 0 || img.empty() || texel.x < 0 || texel.y < 0 || uint32_t(texel.x) >= img.width || uint32_t(texel.y) >= img.height)
    return "";
  const uint32_t x = uint32_t(texel.x), y = uint32_t(texel.y);
  const TemporalWork& w = *v.temporal;
  char text[400];
  if (d.name == "Motion error" || d.name == "Motion class") {
    const MotionPair& p = w.motion->pair;
    const uint32_t c = w.motionClass.raw(x, y, 0);
    const std::string cls = c < kClassNames.size() ? kClassNames[c] : std::to_string(c);
    if (d.name == "Motion class") {
      std::snprintf(text, sizeof text, "Motion class: %u (%s: %s), frames %lld -> %lld", c, cls.c_str(),
                    c < kClassNames.size() ? kClassWhy[c] : "?", (long long)p.previous, (long long)p.current);
      return text;
    }
    if (img.raw(x, y, 0) == gpu::kEmptyTexel) return "Motion error: no surface (class " + cls + ")";
    std::snprintf(text, sizeof text, "Motion error: %.9g px (|stored - expected| under the layout's convention, frames %lld -> %lld), class %s",
                  img.value(x, y, 0), (long long)p.previous, (long long)p.current, cls.c_str());
    return text;
  }
  const FlickerReport& r = w.flicker->report;
  const int seen = int(r.seen.value(x, y, 0));
  std::string values;
  if (img.raw(x, y, 0) == gpu::kEmptyTexel) values = "no value (fewer than two frames saw the point)";
  else
    for (uint32_t c = 0; c < d.components; ++c) {
      char part[64];
      std::snprintf(part, sizeof part, "%s%s %.6g", c ? " " : "", d.componentNames[c].c_str(), img.value(x, y, c));
      values += part;
    }
  std::snprintf(text, sizeof text, "%s of %s at frame %lld's pixels: %s (seen in %d of %zu frames)", d.name.c_str(),
                w.flickerOf.name.c_str(), (long long)r.reference, values.c_str(), seen, r.frames);
  return text;
}

}  // namespace gb
