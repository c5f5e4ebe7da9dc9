// The bench run (see bench_sweep.h): planning, the sweep with its budget, A/B checks, files.
#include "app/bench/bench_sweep.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>

#include "app/bench/bench_report.h"
#include "renderer/core/assert.h"
#include "renderer/core/version.h"
#include "renderer/frame/session.h"
#include "renderer/scene/builtin.h"
#include "views/analysis/accuracy.h"
#include "views/capture/image_io.h"
#include "views/capture/report.h"

namespace gb {

namespace {

using Clock = std::chrono::steady_clock;
double sweepSeconds(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
}

std::string minutes(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  return buf;
}

std::map<std::string, double> errorSummary(const FrameError& e) {
  double pixels = double(e.width) * e.height;
  return {{"normal_deg_mean", e.normalDeg.mean},
          {"normal_deg_max", e.normalDeg.max},
          {"eye_depth_rel_max", e.eyeDepthRelative.max},
          {"position_rel_mean", e.used.relative.mean},
          {"position_rel_max", e.used.relative.max},
          {"shadow_mismatch", e.shadow.fraction},
          {"hdr_rel_mean", e.hdr.relative.mean},
          {"hdr_rel_rms", e.hdr.relative.rms},
          {"lighting_rel_mean", e.lighting.relative.mean},
          {"lighting_per_contribution_max", e.lighting.perContribution.max},
          {"silhouette_fraction", (e.silhouette + e.coverageOnlyGpu + e.coverageOnlyReference) / std::max(pixels, 1.0)}};
}

// Each comma-separated value checked as the option it sets.
bool optionValues(const char* flag, const char* option, const std::string& list, std::vector<RenderOptions>& out,
                  std::string& error) {
  for (const std::string& v : split(list)) {
    out.emplace_back();
    std::string why;
    if (!setOption(out.back(), option, v, why)) {
      error = std::string(flag) + ": " + why;
      return false;
    }
  }
  return true;
}

nlohmann::json benchMeta(const GpuContext& ctx, const BenchPlan& p) {
  const BenchSettings& s = p.settings;
  // docs/json.md: format_version 2 added each method row's "gbuffer" and each pass's "before_ms"
  // (version 1 was unversioned), 3 each method row's "overlap", 4 each method row's "steady_ms" and
  // methods_settings' "steady_ms" (methods.csv a steady_ms column), 5 "attach_application", 6 the
  // attach variants with a viewer (each row's "viewer"); "version" is gblens's.
  return {{"format", "gblens-bench"},
          {"format_version", 6},
          {"device", ctx.deviceName},
          {"driver", ctx.driverName},
          {"git", gitHash()},
          {"version", GBLENS_VERSION},
          {"settings",
           {{"frames", p.frames},
            {"warmup", s.warmup},
            {"variant_seconds", s.variantSeconds},
            {"budget_seconds", s.budget},
            {"lights_sweep", p.lightCounts},
            {"sizes", p.sizes},
            {"shadow_band_texels", kShadowBandTexels},
            {"shadow_reuse", s.shadowReuse}}},
          {"frames_note",
           "Timed frames: " + std::to_string(p.frames) + " after " + std::to_string(s.warmup) +
               " warm-up frames; a variant whose timed run would exceed " + std::to_string(int(s.variantSeconds)) +
               " s (or what the remaining budget leaves it after the typical row time for each row to come) gets "
               "fewer (at least " +
               std::to_string(s.minFrames) + "). " +
               (s.shadowReuse == "on" ? "Shadow map reused in steady state. "
                                      : "Every timed frame renders the shadow map (as with a moving sun). ") +
               "Error figures: one more frame with primitive_id on and fairies off."}};
}

// The state of one run: the budget's clock and the rows measured so far.
struct Run {
  GpuContext& ctx;
  const BenchPlan& plan;
  BenchReport& report;
  Clock::time_point start = Clock::now();
  size_t rowsTotal = 0, rowsDone = 0;
  std::vector<double> rowSeconds;  // whole time of each measured row (warm-up, timed, error)
};

// One variant of the sweep on `scene`: timed, then measured (or copied from a row of the same
// options, or noted when it does not apply).
void sweepRow(Run& run, Scene& scene, Renderer& r, ReferenceCache& cache, const BenchVariant& v,
              std::map<std::string, size_t>& measuredRows) {
  const BenchPlan& p = run.plan;
  BenchReport& report = run.report;
  ++run.rowsDone;
  BenchRow row;
  row.scene = scene.source;
  row.group = v.group;
  row.name = v.name();
  row.label = v.label();
  row.options = p.defaults;
  for (auto& [k, value] : v.set) {
    std::string error;
    bool ok = setOption(row.options, k, value, error);
    GB_ASSERT(ok);  // planBench checked every variant's values
  }
  if (v.group == "lights" && !scene.generatedLights) {
    row.note = "the scene has its own lights";
    report.rows.push_back(row);
    return;
  }
  if (scene.generatedLights && int(scene.lights.size()) != row.options.lights) generateLights(scene, row.options.lights);
  std::string key = optionsJson(row.options).dump();
  if (auto it = measuredRows.find(key); it != measuredRows.end()) {
    BenchRow copy = report.rows[it->second];
    copy.group = row.group;
    copy.name = row.name;
    copy.label = row.label;
    copy.note = "same options as " + report.rows[it->second].name;
    report.rows.push_back(copy);
    return;
  }
  // 85% of the budget for the sweep rows (the rest: A/B checks, depth study). A row may use what
  // is left after the typical row's time is set aside for each row to come, so slow rows (4096
  // lights) get their frames when the run is on schedule.
  const auto rowStart = Clock::now();
  double left = 0.85 * p.settings.budget - sweepSeconds(run.start);
  double typical = run.rowSeconds.empty() ? 10.0 : timingOf(run.rowSeconds).median;
  double cap = std::min(p.settings.variantSeconds, std::max(left - typical * double(run.rowsTotal - run.rowsDone), 0.0));
  timeVariant(r, row.options, p.settings, p.frames, cap, row);
  auto render = [&](const RenderOptions& ro, const std::vector<Target>& t) { return renderSnapshot(r, ro, t); };
  FrameError e = measureFrame(render, row.options, cache).error;
  run.rowSeconds.push_back(sweepSeconds(rowStart));
  row.error = errorSummary(e);
  row.errorDetail = errorJson(e);
  row.measured = true;
  measuredRows[key] = report.rows.size();
  report.rows.push_back(row);
  std::fprintf(stderr,
               "[%2zu/%zu] %-16s %-44s %3d fr %8.1f ms (%.1f-%.1f) | normal %.2e deg  pos %.1e  shadow %.3f%%  light "
               "%.1e  hdr %.1e  [%s]\n",
               run.rowsDone, run.rowsTotal, scene.source.c_str(), row.name.c_str(), row.frames, row.frameMs.median,
               row.frameMs.min, row.frameMs.max, row.error["normal_deg_mean"], row.error["position_rel_mean"],
               100.0 * row.error["shadow_mismatch"], row.error["lighting_rel_mean"], row.error["hdr_rel_mean"],
               minutes(sweepSeconds(run.start)).c_str());
}

// Variants whose errors are no worse than the defaults': only time can make them dominate, so it
// is measured again by an interleaved A/B (the sweep's medians drift).
void abChecks(Run& run, Scene& scene) {
  const BenchPlan& p = run.plan;
  BenchReport& report = run.report;
  if (scene.generatedLights) generateLights(scene, p.defaults.lights);
  for (const std::string& name : errorNoWorseThanDefaults(report.rows, scene.source, report.tolerances)) {
    BenchRow* v = nullptr;
    for (BenchRow& row : report.rows)
      if (row.scene == scene.source && row.name == name) v = &row;
    if (!v || v->note.rfind("same options", 0) == 0) continue;
    // Up to --ab-pairs pairs, within a quarter of the budget left; at least 6 (a 97% interval of
    // the median needs 6 ratios: the whole range).
    double left = p.settings.budget - sweepSeconds(run.start);
    int pairs = std::clamp(int(left / 4.0 / std::max(v->frameMs.median * 2e-3, 1e-3)), 0, p.settings.abPairs);
    if (pairs < 6) continue;
    Renderer ra, rb;  // both fresh: neither side inherits the sweep's history
    initRenderer(ra, run.ctx, scene);
    initRenderer(rb, run.ctx, scene);
    v->ab = interleavedRatio(ra, p.defaults, rb, v->options, pairs, p.settings.shadowReuse == "on");
    destroyRenderer(rb);
    destroyRenderer(ra);
    std::fprintf(stderr, "[a/b] %-16s %-44s %.3fx the defaults' frame time [%.3f-%.3f, %.0f%%] %s (%d pairs)\n",
                 scene.source.c_str(), name.c_str(), v->ab.median, v->ab.ciLow, v->ab.ciHigh, 100.0 * v->ab.confidence,
                 abVerdict(v->ab, run.report.tolerances.time).c_str(), pairs);
  }
}

// The defaults once more: drift of the machine during the sweep (the defaults check takes the
// faster of the two runs, so noise cannot make a variant look better).
void repeatDefaults(Run& run, Scene& scene, Renderer& r, size_t defaultRow) {
  const BenchPlan& p = run.plan;
  if (scene.generatedLights) generateLights(scene, p.defaults.lights);
  BenchRow row;
  row.scene = scene.source;
  row.group = "repeat";
  row.name = row.label = "default (repeat)";
  row.options = p.defaults;
  timeVariant(r, row.options, p.settings, p.frames, p.settings.variantSeconds, row);
  row.measured = true;
  row.error = run.report.rows[defaultRow].error;
  std::fprintf(stderr, "[repeat] %-16s %-44s %3d fr %8.1f ms (%.1f-%.1f)\n", scene.source.c_str(), row.name.c_str(),
               row.frames, row.frameMs.median, row.frameMs.min, row.frameMs.max);
  run.report.rows.push_back(row);
}

void sweepScene(Run& run, Scene& scene) {
  const BenchPlan& p = run.plan;
  Renderer r;
  initRenderer(r, run.ctx, scene);
  ReferenceCache cache(scene);
  std::map<std::string, size_t> measuredRows;  // options -> row index
  for (const BenchVariant& v : p.variants) sweepRow(run, scene, r, cache, v, measuredRows);
  const std::string defaultKey = optionsJson(p.defaults).dump();
  if (measuredRows.count(defaultKey)) abChecks(run, scene);
  if (measuredRows.count(defaultKey) && sweepSeconds(run.start) < 0.9 * p.settings.budget)
    repeatDefaults(run, scene, r, measuredRows[defaultKey]);
  if (scene.generatedLights) generateLights(scene, p.defaults.lights);
  destroyRenderer(r);
  std::fprintf(stderr, "gblens bench: %s done (reference: %.1f s of CPU time)\n", scene.source.c_str(), cache.seconds);
}

bool writeFile(const std::string& path, const std::string& text, std::string& error) {
  bool ok = writeAtomically(path, ".tmp", [&](const std::string& tmp) {
    std::ofstream f(tmp);
    f << text;
    return bool(f);
  });
  if (!ok) error = path + ": cannot write";
  return ok;
}

}  // namespace

bool planBench(BenchPlan& p, std::string& error) {
  BenchSettings& s = p.settings;
  std::vector<RenderOptions> sweepLights, sweepSizes, methodLights, methodSizes;
  if (!optionValues("--lights-sweep", "lights", s.lightsSweep, sweepLights, error) ||
      !optionValues("--sizes", "size", s.sizes, sweepSizes, error) ||
      !optionValues("--methods-lights", "lights", s.methodsLights, methodLights, error) ||
      !optionValues("--methods-sizes", "size", s.methodsSizes, methodSizes, error))
    return false;
  for (const RenderOptions& v : sweepLights) p.lightCounts.push_back(v.lights);
  p.sizes = split(s.sizes);
  s.methods.lights.clear();
  for (const RenderOptions& v : methodLights) s.methods.lights.push_back(v.lights);
  s.methods.sizes = split(s.methodsSizes);
  s.methods.minRounds = std::min(s.methods.minRounds, s.methods.rounds);
  p.variants = defaultSweep(p.defaults, p.lightCounts, p.sizes);
  for (const BenchVariant& v : p.variants) {
    RenderOptions o = p.defaults;
    for (auto& [k, value] : v.set)
      if (!setOption(o, k, value, error)) {
        error = "variant " + v.name() + ": " + error;
        return false;
      }
  }
  p.runMethods = true;
  if (s.only.empty()) return true;
  std::vector<std::string> only = split(s.only);
  p.runMethods = std::find(only.begin(), only.end(), "methods") != only.end();
  p.runAttach = std::find(only.begin(), only.end(), "attach") != only.end();
  p.runTemporal = std::find(only.begin(), only.end(), "motion") != only.end();
  std::vector<BenchVariant> kept;
  for (const BenchVariant& v : p.variants)
    if (std::find(only.begin(), only.end(), v.name()) != only.end() ||
        std::find(only.begin(), only.end(), v.group) != only.end())
      kept.push_back(v);
  if (kept.empty() && !p.runMethods && !p.runAttach && !p.runTemporal) {
    error = "--only " + s.only + ": no variant or group of that name";
    return false;
  }
  p.variants = kept;
  return true;
}

BenchReport runBench(GpuContext& ctx, const BenchPlan& p) {
  const BenchSettings& s = p.settings;
  BenchReport report;
  Run run{ctx, p, report};
  report.meta = benchMeta(ctx, p);
  // The method comparison first, on builtin:temple: its time comes out of the budget, and the
  // sweep's rows below shorten to what is left.
  if (p.runMethods) {
    report.meta["methods_settings"] = {{"scene", "builtin:temple"},
                                       {"lights", s.methods.lights},
                                       {"sizes", s.methods.sizes},
                                       {"forward_max_lights", s.methods.forwardMaxLights},
                                       {"rounds", s.methods.rounds},
                                       {"min_rounds", s.methods.minRounds},
                                       {"burst", s.methods.burst},
                                       {"frames_in_flight", kFrameSlots},
                                       {"frame_ms", kBurstFrameMs},
                                       {"steady_ms", kSteadyMs},
                                       {"seconds", s.methods.seconds},
                                       {"shadow_map", "reused (a static scene)"}};
    Scene temple = loadScene("builtin:temple", p.defaults.lights);
    report.methods = methodStudy(ctx, temple, p.defaults, s.methods);
    report.skips = skipSavings(ctx, temple, p.defaults, 6);
    std::fprintf(stderr, "gblens bench: method comparison done [%s]\n", minutes(sweepSeconds(run.start)).c_str());
  }
  // Every scene first: one that does not load is skipped before the budget is shared out.
  std::vector<std::string> skippedScenes;
  std::vector<std::unique_ptr<Scene>> scenes;
  for (const std::string& spec : p.variants.empty() ? std::vector<std::string>{} : s.scenes) {
    try {
      scenes.push_back(std::make_unique<Scene>(loadScene(spec, p.defaults.lights)));
    } catch (const SceneError& e) {
      std::fprintf(stderr, "gblens bench: skipping %s: %s\n", spec.c_str(), e.message.c_str());
      skippedScenes.push_back(spec + ": " + e.message);
    }
  }
  run.rowsTotal = p.variants.size() * scenes.size();
  for (std::unique_ptr<Scene>& scene : scenes) sweepScene(run, *scene);
  if (s.depthRange == "on" && !p.variants.empty() && sweepSeconds(run.start) < 0.95 * s.budget) {
    report.depthRange = depthRangeStudy(ctx, p.defaults);
    report.depthTest = depthTestStudy(ctx, p.defaults, {1e-3, 1e-4, 1e-5});
  }
  else if (s.depthRange == "on" && !p.variants.empty())
    std::fprintf(stderr, "gblens bench: no time left for the depth-range study (--budget)\n");
  if (p.runAttach) {
    report.attach = attachStudy(s.attach);
    report.attachApplication = attachApplicationStudy(s.attach);
    std::fprintf(stderr, "gblens bench: attach done [%s]\n", minutes(sweepSeconds(run.start)).c_str());
  }
  if (p.runTemporal) {
    report.temporal = temporalStudy(ctx, p.defaults, s.temporal);
    std::fprintf(stderr, "gblens bench: motion done [%s]\n", minutes(sweepSeconds(run.start)).c_str());
  }
  report.meta["skipped_scenes"] = skippedScenes;
  report.meta["seconds"] = sweepSeconds(run.start);
  markFrontiers(report.rows);
  report.defaults = checkDefaults(report.rows, report.tolerances);
  return report;
}

bool writeBenchFiles(const BenchReport& report, const std::string& out, std::string& error) {
  const std::filesystem::path dir(out);
  return writeFile((dir / "bench.json").string(), benchJson(report).dump(2) + "\n", error) &&
         writeFile((dir / "bench.csv").string(), benchCsv(report), error) &&
         writeFile((dir / "bench.md").string(), benchMarkdown(report), error) &&
         (report.methods.empty() || writeFile((dir / "methods.csv").string(), methodsCsv(report), error)) &&
         writeBenchPlots(report, out, error);
}

}  // namespace gb
