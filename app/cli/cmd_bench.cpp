// gblens bench: the method comparison, the variant sweep with its error figures, and the depth-range
// study (app/bench/bench_sweep.h), written to --out as bench.json, bench.csv, bench.md, methods.csv
// and the plots. A whole-run time budget shortens the timed runs of slow variants rather than
// overrunning (each row says how many frames it got).
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/bench/bench_sweep.h"
#include "app/cli/cli.h"
#include "renderer/frame/session.h"

namespace gb {

// The summary lines of a finished run; false when nothing could be measured.
static bool printSummary(const BenchReport& report, const std::string& out) {
  for (const DefaultsCheck& c : report.defaults) {
    std::string by;
    for (const std::string& n : c.dominatedBy) by += n + " ";
    std::fprintf(stderr, "gblens bench: %s: defaults %s\n", c.scene.c_str(),
                 c.onFrontier ? "on the frontier" : ("dominated by " + by).c_str());
  }
  std::fprintf(stderr, "gblens bench: wrote %s/{bench.json,bench.csv,bench.md,time_vs_error.png,time_vs_lights.png%s%s} in %.0f s\n",
               out.c_str(), report.depthRange.empty() ? "" : ",depth_range.png",
               report.methods.empty() ? "" : ",methods.csv,methods_vs_lights.png", report.meta.value("seconds", 0.0));
  bool anyMeasured = false;
  for (const BenchRow& row : report.rows) anyMeasured |= row.measured;
  for (const MethodRow& row : report.methods) anyMeasured |= row.measured;
  anyMeasured |= !report.attach.is_null() || !report.temporal.is_null();
  if (!anyMeasured) std::fprintf(stderr, "gblens bench: no scene could be measured\n");
  return anyMeasured;
}

static int bench(const CommonOptions& o, BenchSettings settings) {
  BenchPlan plan;
  plan.settings = std::move(settings);
  plan.defaults = o.render;
  plan.frames = o.frames;
  std::string error;
  if (!planBench(plan, error)) {
    std::fprintf(stderr, "gblens bench: %s\n", error.c_str());
    return 2;
  }
  std::error_code ec;
  std::filesystem::create_directories(plan.settings.out, ec);
  if (ec) {
    std::fprintf(stderr, "gblens bench: --out %s: %s\n", plan.settings.out.c_str(), ec.message().c_str());
    return 2;
  }
  HeadlessSession session({o.device, o.validate});
  BenchReport report = runBench(session.context(), plan);
  int status = 0;
  if (!writeBenchFiles(report, plan.settings.out, error)) {
    std::fprintf(stderr, "gblens bench: %s\n", error.c_str());
    status = 2;
  }
  if (!printSummary(report, plan.settings.out) && status == 0) status = 2;
  if (session.reportValidation() && status == 0) status = 1;
  return status;
}

Command addBenchCommand(CLI::App& root) {
  auto o = std::make_shared<CommonOptions>();
  auto s = std::make_shared<BenchSettings>();
  o->frames = 20;
  CLI::App* cmd = root.add_subcommand(
      "bench", "time vs error: the variant sweep on scenes (warm-up, median of timed frames, error vs the reference)");
  addCommonOptions(cmd, *o, {"scene"});
  cmd->add_option("SCENES", s->scenes, "scenes to sweep (a .gltf/.glb that fails to load is skipped with a message)")
      ->capture_default_str();
  cmd->add_option("--out", s->out, "folder for bench.json, bench.csv, bench.md and the plots")->capture_default_str();
  cmd->add_option("--warmup", s->warmup, "untimed frames before the timed ones")->check(CLI::Range(1, 1000))->capture_default_str();
  cmd->add_option("--variant-seconds", s->variantSeconds, "longest timed run of one variant (fewer frames, at least 5)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--budget", s->budget, "seconds for the whole run: later variants get fewer frames to stay within it")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--ab-pairs", s->abPairs,
                  "interleaved A/B pairs per variant whose errors tie the defaults' (the time verdict's sample)")
      ->check(CLI::Range(6, 1000))
      ->capture_default_str();
  cmd->add_option("--lights-sweep", s->lightsSweep, "light counts of the lights sweep")->capture_default_str();
  cmd->add_option("--sizes", s->sizes, "output sizes of the size sweep")->capture_default_str();
  cmd->add_option("--only", s->only,
                  "measure only these variants or groups (comma-separated names, e.g. default,normal; \"methods\": the "
                  "method comparison and skip savings; \"attach\": the cost of gblens attach; \"motion\": gblens motion per pair vs compare)");
  cmd->add_option("--depth-range", s->depthRange, "the depth-precision study on builtin:depth-range")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--methods-lights", s->methodsLights, "light counts of the method comparison")->capture_default_str();
  cmd->add_option("--methods-sizes", s->methodsSizes, "output sizes of the method comparison")->capture_default_str();
  cmd->add_option("--methods-forward-max", s->methods.forwardMaxLights,
                  "largest light count at which forward is measured (it shades every light at every fragment)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--methods-seconds", s->methods.seconds,
                  "time for the method comparison (rounds per cell shrink to fit, down to --methods-min-rounds)")
      ->check(CLI::PositiveNumber)
      ->capture_default_str();
  cmd->add_option("--methods-culling-max", s->methods.cullingMaxPixelLights,
                  "largest pixels x lights at which the culling efficiency is measured (ideal pairs are counted on the CPU)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--methods-rounds", s->methods.rounds, "timed rounds per cell of the method comparison, at most")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--methods-min-rounds", s->methods.minRounds, "timed rounds per cell, at least")
      ->check(CLI::Range(1, 1000))
      ->capture_default_str();
  cmd->add_option("--methods-burst", s->methods.burst,
                  "frames in flight per method per round; the first is waited for and not counted, frame ms is "
                  "the rest's throughput")
      ->check(CLI::Range(2, 1000))
      ->capture_default_str();
  cmd->add_option("--shadow-reuse", s->shadowReuse,
                  "off: timed frames render the shadow map every frame (a moving sun); on: a static scene reuses it")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--attach-rounds", s->attach.rounds, "gblens attach's cost: interleaved rounds of its variants")
      ->check(CLI::Range(1, 100))
      ->capture_default_str();
  cmd->add_option("--motion-size", s->temporal.size, "gblens motion's cost: the sequence's size")->capture_default_str();
  cmd->add_option("--motion-frames", s->temporal.frames, "gblens motion's cost: frames of the sequence (pairs: one fewer)")
      ->check(CLI::Range(3, 10000))
      ->capture_default_str();
  cmd->add_option("--attach-size", s->attach.size, "gblens attach's cost: the application's output size")
      ->capture_default_str();
  cmd->add_option("--attach-gbuffer", s->attach.gbuffer, "gblens attach's cost: the application's --gbuffer")
      ->check(CLI::IsMember({"raster", "visibility", "auto"}))
      ->capture_default_str();
  cmd->add_option("--attach-frames", s->attach.frames, "gblens attach's cost: frames per run of the application")
      ->check(CLI::Range(3, 100000))
      ->capture_default_str();
  cmd->add_option("--attach-app", s->attach.application,
                  "gblens attach's cost for another application: its command line (words split at spaces), {frames} for its frame count "
                  "(e.g. \"./tiler_deferred --size 1280x720 --frames {frames}\"), with --attach-app-layout");
  cmd->add_option("--attach-app-layout", s->attach.applicationLayout, "the layout --attach-app's application streams under");
  cmd->add_option("--attach-app-frames", s->attach.applicationFrames, "--attach-app: frames of its shorter run (the longer: 4x)")
      ->check(CLI::Range(2, 100000))
      ->capture_default_str();
  cmd->add_option("--attach-soak", s->attach.soakFrames, "gblens attach's cost: frames of the memory soak")
      ->check(CLI::Range(100, 1000000))
      ->capture_default_str();
  return {cmd, [o, s]() -> int {
            std::string error;
            if (!finishCommonOptions(*o, error)) {
              std::fprintf(stderr, "gblens bench: %s\n", error.c_str());
              return 2;
            }
            const AttachBenchSettings& a = s->attach;
            if (!a.application.empty() && (a.applicationLayout.empty() || a.application.find("{frames}") == std::string::npos)) {
              std::fprintf(stderr, "gblens bench: --attach-app \"%s\": %s\n", a.application.c_str(),
                           a.applicationLayout.empty() ? "needs --attach-app-layout (the layout it streams under)"
                                                       : "needs {frames} where its frame count goes (it is run at two)");
              return 2;
            }
            return bench(*o, *s);
          }};
}

}  // namespace gb
