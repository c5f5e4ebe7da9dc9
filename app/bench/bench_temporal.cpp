// What `gblens motion` costs (issue 38) in make bench: a sequence of builtin:temple (orbiting, jittered
// camera, the motion target) rendered in process at the bench size, each pair of frames checked by
// checkMotionPair, beside the time compare takes for the same two frames. Both run on snapshots in
// memory (loading captures from disk is the same for both and left out); the ratio is per pair.
#include "app/bench/bench_temporal.h"

#include <chrono>
#include <cstdio>
#include <deque>

#include "renderer/core/camera_motion.h"
#include "renderer/core/statistics.h"
#include "renderer/frame/session.h"
#include "renderer/scene/scene.h"
#include "views/analysis/compare.h"
#include "views/analysis/motion.h"

namespace gb {

static double secondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t).count();
}

nlohmann::json temporalStudy(GpuContext& ctx, const RenderOptions& base, const TemporalBenchSettings& s) {
  RenderOptions o = base;
  std::string error;
  if (!setOption(o, "size", s.size, error)) return {{"error", "--temporal-size " + s.size + ": " + error}};
  o.cameraMotion = CameraMotion::Orbit;
  o.jitter = Jitter::Halton;
  o.motion = true;
  o.timeStep = 1.0 / 30.0;
  Scene scene = loadScene("builtin:temple", o.lights);
  Renderer r;
  initRenderer(r, ctx, scene);
  const std::vector<Target> targets = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth,
                                       Target::DepthStencil, Target::Motion};
  struct Held {
    Capture capture;
    TemporalFrame frame;
  };
  std::deque<Held> window;
  std::vector<double> motionMs, compareMs, ratios;
  nlohmann::json verdicts = nlohmann::json::object();
  for (int i = 0; i < s.frames; ++i) {
    o.time = i * o.timeStep;
    Held h;
    h.capture.frame = renderSnapshot(r, o, targets);
    h.frame.number = i, h.frame.time = o.time, h.frame.jitter = frameJitter(o);
    window.push_back(std::move(h));
    if (window.size() > 3) window.pop_front();
    for (Held& w : window) w.frame.frame = &w.capture.frame;  // the deque moved them
    if (window.size() < 2) continue;
    const Held& cur = window.back();
    const Held& prev = window[window.size() - 2];
    const auto t0 = std::chrono::steady_clock::now();
    const MotionPair p = checkMotionPair(prev.frame, cur.frame, window.size() == 3 ? &window[0].frame : nullptr, {});
    const double m = secondsSince(t0) * 1e3;
    const auto t1 = std::chrono::steady_clock::now();
    CompareReport report;
    compareCaptures(prev.capture, cur.capture, ThresholdSettings{}, report, error);
    const double c = secondsSince(t1) * 1e3;
    motionMs.push_back(m), compareMs.push_back(c), ratios.push_back(m / c);
    const std::string v = p.differences.empty() ? "agrees" : "differs";
    verdicts[v] = verdicts.value(v, 0) + 1;
  }
  destroyRenderer(r);
  std::fprintf(stderr, "gblens bench: motion on %d frames of %s measured\n", s.frames, s.size.c_str());
  return {{"size", s.size},
          {"frames", s.frames},
          {"pairs", motionMs.size()},
          {"targets", "albedo_specular, normal_shadow, depth, depth_stencil, motion"},
          {"motion_ms_per_pair", {{"median", median(motionMs)}, {"p95", percentile(motionMs, 0.95)}}},
          {"compare_ms_per_pair", {{"median", median(compareMs)}, {"p95", percentile(compareMs, 0.95)}}},
          {"motion_over_compare", {{"median", median(ratios)}, {"min", percentile(ratios, 0.0)}, {"max", percentile(ratios, 1.0)}}},
          {"verdicts", verdicts},
          {"what", "in memory: checkMotionPair (144 conventions on up to 40000 pixels, then every pixel classed) vs "
                   "compareCaptures of the same two frames; one thread each"}};
}

std::string temporalMarkdown(const nlohmann::json& t) {
  if (t.is_null()) return "";
  if (t.contains("error")) return "## gblens motion\n\n" + t["error"].get<std::string>() + "\n";
  char line[2048];
  std::snprintf(line, sizeof line,
                "## gblens motion\n\n%s, %d frames (%zu pairs) of builtin:temple, orbiting jittered camera, motion target on.\n\n"
                "| per pair | median ms | p95 ms |\n| --- | --- | --- |\n| motion (checkMotionPair) | %.1f | %.1f |\n"
                "| compare (compareCaptures) | %.1f | %.1f |\n\nmotion / compare: median %.2f (%.2f .. %.2f); verdicts %s\n",
                t["size"].get<std::string>().c_str(), t["frames"].get<int>(), t["pairs"].get<size_t>(),
                t["motion_ms_per_pair"]["median"].get<double>(), t["motion_ms_per_pair"]["p95"].get<double>(),
                t["compare_ms_per_pair"]["median"].get<double>(), t["compare_ms_per_pair"]["p95"].get<double>(),
                t["motion_over_compare"]["median"].get<double>(), t["motion_over_compare"]["min"].get<double>(),
                t["motion_over_compare"]["max"].get<double>(), t["verdicts"].dump().c_str());
  return line;
}

}  // namespace gb
