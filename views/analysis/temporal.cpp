// A sequence's motion vectors checked pair by pair (three frames in memory at a time) and summed up
// as one verdict; flicker: each frame's decoded values carried to the reference frame's pixels by
// reprojection (depth and cameras), then per-pixel standard deviation and largest frame-to-frame step.
#include "views/analysis/temporal.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <deque>
#include <memory>

#include "renderer/core/decode.h"
#include "renderer/core/statistics.h"
#include "views/analysis/decoded_image.h"
#include "views/analysis/view_table.h"

namespace gb {

bool loadTemporalFrame(const Sequence& seq, size_t i, LoadedFrame& out, std::string& error) {
  out.capture = std::make_shared<Capture>();
  if (!loadCapture(seq.captureDir(i), *out.capture, error)) return false;
  out.frame.frame = &out.capture->frame;
  out.frame.number = seq.frames[i].number;
  out.frame.time = seq.frames[i].time;
  out.frame.jitter = seq.frames[i].jitter;
  return true;
}

bool walkFramePairs(const Sequence& seq, const char* what, const FramePairVisit& visit, std::string& error) {
  if (seq.frames.size() < 2) {
    error = seq.dir + ": " + what + " needs two frames at least (the sequence has " + std::to_string(seq.frames.size()) + ")";
    return false;
  }
  std::deque<LoadedFrame> window;
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    LoadedFrame l;
    if (!loadTemporalFrame(seq, i, l, error)) return false;
    window.push_back(std::move(l));
    if (window.size() > 3) window.pop_front();
    const TemporalFrame* previous = window.size() >= 2 ? &window[window.size() - 2].frame : nullptr;
    const TemporalFrame* before = window.size() == 3 ? &window[0].frame : nullptr;
    if (!visit(i, before, previous, window.back().frame, error)) return false;
  }
  return true;
}

const char* sequenceVerdict(const std::vector<std::string>& findings, bool anyDecided) {
  return !findings.empty() ? "differs" : anyDecided ? "agrees" : "undecided";
}

void addFindingOnce(std::vector<std::string>& list, const std::string& s) {
  if (std::find(list.begin(), list.end(), s) == list.end()) list.push_back(s);
}

bool checkMotionSequence(const Sequence& seq, const MotionSequenceOptions& o, MotionReport& out, std::string& error) {
  out = MotionReport{};
  bool anyDecided = false;
  const bool ok = walkFramePairs(seq, "motion", [&](size_t i, const TemporalFrame* before, const TemporalFrame* prev,
                                          const TemporalFrame& cur, std::string& why) {
    if (!prev) {
      const Layout& layout = cur.frame->layout;
      const Quantity* q = o.motion.empty() ? layout.find(QuantityKind::Motion) : layout.findByName(o.motion);
      if (!q || q->kind != QuantityKind::Motion) {
        why = seq.captureDir(i) + ": " +
              (o.motion.empty() ? std::string("the layout has no motion quantity") : "--motion " + o.motion + ": not a motion quantity of the layout");
        return false;
      }
      out.motion = q->name;
      return true;
    }
    if (o.progress) o.progress("frames " + std::to_string(prev->number) + " -> " + std::to_string(cur.number));
    MotionPairOptions po;
    po.motion = cur.frame->layout.findByName(out.motion);
    po.inlierPixels = o.inlierPixels;
    MotionPair p = checkMotionPair(*prev, cur, before, po);
    anyDecided = anyDecided || p.detected;
    for (const std::string& d : p.differences) addFindingOnce(out.findings, d);
    if (p.surfacePixels && double(p.wrongMoving) > o.wrongFraction * double(p.surfacePixels))
      addFindingOnce(out.findings, "vectors that land on another surface in the previous frame (more than " +
                                       std::to_string(int(o.wrongFraction * 100)) + " % of the surface in a pair)");
    out.pairs.push_back(std::move(p));
    return true;
  }, error);
  if (!ok) return false;
  out.verdict = sequenceVerdict(out.findings, anyDecided);
  return true;
}

nlohmann::json motionReportJson(const MotionReport& r, const std::string& dir) {
  nlohmann::json pairs = nlohmann::json::array();
  for (const MotionPair& p : r.pairs) pairs.push_back(motionPairJson(p));
  return {{"format", "gblens-motion"}, {"version", 1}, {"sequence", dir}, {"motion", r.motion}, {"verdict", r.verdict}, {"findings", r.findings}, {"pairs", pairs}};
}

std::string motionReportText(const MotionReport& r) {
  std::string s;
  char line[512];
  for (const MotionPair& p : r.pairs) {
    const double n = std::max<double>(1.0, double(p.surfacePixels));
    std::snprintf(line, sizeof line,
                  "frames %lld -> %lld: static %5.1f %% (error median %.2g, p95 %.2g, max %.2g px; bound %.3f px), "
                  "moving %.1f %%, disoccluded %.1f %%, wrong %.1f %%\n",
                  (long long)p.previous, (long long)p.current, 100.0 * p.staticPixels / n, p.medianError, p.p95Error,
                  p.maxError, p.bound, 100.0 * p.movingPixels / n, 100.0 * p.disoccluded / n, 100.0 * p.wrongMoving / n);
    s += line;
    if (!p.detected) {
      s += "  convention: undecided (" + p.undecided + ")\n";
    } else {
      s += "  convention: " + conventionJson(p.found, &p.decided).dump() + "\n";
      for (const std::string& d : p.differences) s += "  DIFFERS: " + d + "\n";
    }
  }
  s += "verdict: " + r.verdict;
  if (r.verdict == "agrees") s += " (the vectors follow the layout's convention)";
  s += "\n";
  for (const std::string& f : r.findings) s += "  " + f + "\n";
  return s;
}

// ---------------------------------------------------------------------------------------------

bool flickerSequence(const Sequence& seq, const FlickerOptions& o, FlickerReport& out, std::string& error) {
  out = FlickerReport{};
  size_t refIndex = 0;
  if (o.reference >= 0) {
    const int i = seq.find(o.reference);
    if (i < 0) {
      error = "--reference " + std::to_string(o.reference) + ": not a frame of " + seq.dir;
      return false;
    }
    refIndex = size_t(i);
  }
  LoadedFrame ref;
  if (!loadTemporalFrame(seq, refIndex, ref, error)) return false;
  const FrameSnapshot& R = *ref.frame.frame;
  const std::vector<ViewDef> views = layoutViews(R.layout);
  const int v = findView(views, o.quantity);
  if (v < 0 || views[size_t(v)].sun) {
    error = "--quantity " + o.quantity + ": not a quantity of the layout (" + viewNameList(views) + ")";
    return false;
  }
  const ViewDef& view = views[size_t(v)];
  const uint32_t w = R.camera.width, h = R.camera.height, n = decodedComponents(R, view);
  out.quantity = view.name, out.components = n, out.reference = seq.frames[refIndex].number;
  // Where each reference pixel's point is in every frame (null: not seen) and the running sums.
  const size_t count = size_t(w) * h;
  std::vector<double> sum(count * n, 0.0), sum2(count * n, 0.0), last(count * n, NAN), step(count * n, NAN);
  std::vector<uint32_t> seen(count, 0);
  std::vector<std::optional<glm::dvec3>> points(count);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) points[size_t(y) * w + x] = surfacePoint(R, x, y, ref.frame.jitter.value_or(glm::dvec2(0.0)));
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    LoadedFrame l;
    if (i == refIndex) l = ref;
    else if (!loadTemporalFrame(seq, i, l, error)) return false;
    const FrameSnapshot& F = *l.frame.frame;
    if (F.camera.width != w || F.camera.height != h) {
      error = seq.captureDir(i) + ": " + std::to_string(F.camera.width) + "x" + std::to_string(F.camera.height) +
              ", the reference frame is " + std::to_string(w) + "x" + std::to_string(h);
      return false;
    }
    if (o.progress) o.progress("frame " + std::to_string(l.frame.number));
    const std::vector<ViewDef> fv = layoutViews(F.layout);
    const int k = findView(fv, o.quantity);
    if (k < 0) {
      error = seq.captureDir(i) + ": no quantity " + o.quantity;
      return false;
    }
    const std::vector<double> values = decodedImage<double>(F, fv[size_t(k)]);
    const glm::dvec2 jit = l.frame.jitter.value_or(glm::dvec2(0.0));
    for (uint32_t y = 0; y < h; ++y)
      for (uint32_t x = 0; x < w; ++x) {
        const size_t at = size_t(y) * w + x;
        uint32_t sx = x, sy = y;
        if (o.reproject) {
          if (!points[at]) continue;
          const std::optional<glm::dvec2> p = projectToPixel(F.camera, *points[at]);
          if (!p) continue;
          const glm::dvec2 t = *p + jit;  // the jittered frame shows the point there
          if (t.x < 0 || t.y < 0 || t.x >= w || t.y >= h) continue;
          sx = uint32_t(t.x), sy = uint32_t(t.y);
          // Occluded in this frame: it shows something else at the point's place.
          const std::optional<glm::dvec3> there = surfacePoint(F, sx, sy, jit);
          if (!there || glm::length(*there - *points[at]) > 0.02 * glm::length(*points[at] - glm::dvec3(F.camera.worldFromEye[3])) + 1e-3)
            continue;
        }
        const double* val = &values[(size_t(sy) * w + sx) * n];
        if (!std::isfinite(val[0])) continue;
        ++seen[at];
        for (uint32_t c = 0; c < n; ++c) {
          const size_t a = at * n + c;
          sum[a] += val[c], sum2[a] += val[c] * val[c];
          if (std::isfinite(last[a])) step[a] = std::max(std::isfinite(step[a]) ? step[a] : 0.0, std::fabs(val[c] - last[a]));
          last[a] = val[c];
        }
      }
    out.frames++;
  }
  auto image = [&](const char* name, PixelType type, uint32_t channels) {
    CpuImage im;
    im.name = name, im.type = type, im.width = w, im.height = h;
    for (uint32_t c = 0; c < channels; ++c)
      im.channels.push_back(std::string(name) == "flicker_seen" ? std::string("count")
                            : c < view.componentNames.size() ? view.name + "." + view.componentNames[c]
                                                             : view.name + "." + std::to_string(c));
    im.data.resize(size_t(w) * h * channels * 4);
    return im;
  };
  out.stddev = image("flicker_stddev", PixelType::F32, n);
  out.maxStep = image("flicker_max_step", PixelType::F32, n);
  out.seen = image("flicker_seen", PixelType::F32, 1);  // float: image tools read a UINT channel normalised
  std::vector<double> all;
  float* sd = reinterpret_cast<float*>(out.stddev.data.data());
  float* ms = reinterpret_cast<float*>(out.maxStep.data.data());
  float* sn = reinterpret_cast<float*>(out.seen.data.data());
  for (size_t at = 0; at < count; ++at) sn[at] = float(seen[at]);
  for (size_t at = 0; at < count; ++at)
    for (uint32_t c = 0; c < n; ++c) {
      const size_t a = at * n + c;
      const double k = seen[at];
      const double var = k >= 2 ? std::max(0.0, (sum2[a] - sum[a] * sum[a] / k) / (k - 1)) : NAN;
      sd[a] = float(std::sqrt(var));
      ms[a] = float(k >= 2 ? step[a] : NAN);
      if (std::isfinite(var)) all.push_back(std::sqrt(var));
      if (k >= 2 && std::isfinite(step[a])) out.maxStepAll = std::max(out.maxStepAll, step[a]);
    }
  double total = 0.0;
  for (double s : all) total += s;
  out.meanStddev = all.empty() ? 0.0 : total / double(all.size());
  out.p99Stddev = percentile(all, 0.99);
  return true;
}

nlohmann::json flickerReportJson(const FlickerReport& r) {
  return {{"format", "gblens-flicker"}, {"version", 1},       {"quantity", r.quantity},          {"reference", r.reference},
          {"frames", r.frames}, {"components", r.components},      {"stddev", {{"mean", r.meanStddev}, {"p99", r.p99Stddev}}},
          {"max_step", r.maxStepAll}};
}

}  // namespace gb
