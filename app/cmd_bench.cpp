// gblens bench: first the method comparison and skip savings on builtin:temple
// (app/bench_methods.cpp); then the sweep of app/bench_variants.cpp on each scene: per variant, warm-up frames,
// then the median (min, max) of timed frames (whole-frame wall ms, GPU ms, per pass), then one
// frame measured against the reference; then the depth-range study (builtin:depth-range). Writes
// bench.json, bench.csv, bench.md, methods.csv and the plots to --out. A whole-run time budget shortens the
// timed runs of slow variants rather than overrunning (each row says how many frames it got).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "renderer/version.h"
#include "app/bench_run.h"
#include "app/bench_variants.h"
#include "app/cli.h"
#include "renderer/builtin.h"
#include "views/accuracy.h"
#include "views/bench_report.h"
#include "views/image_io.h"
#include "views/report.h"

namespace gb {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }

std::vector<std::string> split(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  for (std::string item; std::getline(ss, item, ',');)
    if (!item.empty()) out.push_back(item);
  return out;
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

std::string minutes(double s) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%dm%02ds", int(s) / 60, int(s) % 60);
  return buf;
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
  cmd->add_option("--lights-sweep", s->lightsSweep, "light counts of the lights sweep")->capture_default_str();
  cmd->add_option("--sizes", s->sizes, "output sizes of the size sweep")->capture_default_str();
  cmd->add_option("--only", s->only,
                  "measure only these variants or groups (comma-separated names, e.g. default,normal; \"methods\": the "
                  "method comparison and skip savings)");
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
  cmd->add_option("--shadow-reuse", s->shadowReuse,
                  "off: timed frames render the shadow map every frame (a moving sun); on: a static scene reuses it")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  return {cmd, [o, s]() -> int {
            std::string error;
            if (!finishCommonOptions(*o, error)) {
              std::fprintf(stderr, "gblens bench: %s\n", error.c_str());
              return 2;
            }
            // Each comma-separated value checked as the option it sets; one message naming the flag.
            auto values = [&error](const char* flag, const char* option, const std::string& list,
                                   std::vector<RenderOptions>& out) {
              for (const std::string& v : split(list)) {
                out.emplace_back();
                if (!setOption(out.back(), option, v, error)) {
                  std::fprintf(stderr, "gblens bench: %s: %s\n", flag, error.c_str());
                  return false;
                }
              }
              return true;
            };
            std::vector<RenderOptions> sweepLights, sweepSizes, methodLights, methodSizes;
            if (!values("--lights-sweep", "lights", s->lightsSweep, sweepLights) ||
                !values("--sizes", "size", s->sizes, sweepSizes) ||
                !values("--methods-lights", "lights", s->methodsLights, methodLights) ||
                !values("--methods-sizes", "size", s->methodsSizes, methodSizes))
              return 2;
            std::vector<int> lightCounts;
            for (const RenderOptions& v : sweepLights) lightCounts.push_back(v.lights);
            std::vector<std::string> sizes = split(s->sizes);
            s->methods.lights.clear();
            for (const RenderOptions& v : methodLights) s->methods.lights.push_back(v.lights);
            s->methods.sizes = split(s->methodsSizes);
            s->methods.minRounds = std::min(s->methods.minRounds, s->methods.rounds);
            std::vector<BenchVariant> variants = defaultSweep(o->render, lightCounts, sizes);
            bool runMethods = true;
            if (!s->only.empty()) {
              std::vector<std::string> only = split(s->only);
              runMethods = std::find(only.begin(), only.end(), "methods") != only.end();
              std::vector<BenchVariant> kept;
              for (const BenchVariant& v : variants)
                if (std::find(only.begin(), only.end(), v.name()) != only.end() ||
                    std::find(only.begin(), only.end(), v.group) != only.end())
                  kept.push_back(v);
              if (kept.empty() && !runMethods) {
                std::fprintf(stderr, "gblens bench: --only %s: no variant or group of that name\n", s->only.c_str());
                return 2;
              }
              variants = kept;
            }
            std::error_code ec;
            std::filesystem::create_directories(s->out, ec);
            if (ec) {
              std::fprintf(stderr, "gblens bench: --out %s: %s\n", s->out.c_str(), ec.message().c_str());
              return 2;
            }

            ContextOptions co;
            co.validation = o->validate;
            co.device = o->device;
            GpuContext ctx = createContext(co);
            const auto start = Clock::now();
            BenchReport report;
            report.meta = {{"device", ctx.deviceName},
                           {"driver", ctx.driverName},
                           {"git", gitHash()},
                           {"version", GBLENS_VERSION},
                           {"settings",
                            {{"frames", o->frames},
                             {"warmup", s->warmup},
                             {"variant_seconds", s->variantSeconds},
                             {"budget_seconds", s->budget},
                             {"lights_sweep", lightCounts},
                             {"sizes", sizes},
                             {"shadow_band_texels", kShadowBandTexels},
                             {"shadow_reuse", s->shadowReuse}}},
                           {"frames_note", "Timed frames: " + std::to_string(o->frames) +
                                               " after " + std::to_string(s->warmup) +
                                               " warm-up frames; a variant whose timed run would exceed " +
                                               std::to_string(int(s->variantSeconds)) +
                                               " s (or what the remaining budget leaves it after the typical row time for each row to come) gets fewer (at least " +
                                               std::to_string(s->minFrames) +
                                               "). " + (s->shadowReuse == "on" ? "Shadow map reused in steady state. "
                                                                                : "Every timed frame renders the shadow map (as with a moving sun). ") +
                                               "Error figures: one more frame with primitive_id on and fairies off."}};
            // The method comparison first, on builtin:temple: its time comes out of the budget, and
            // the sweep's rows below shorten to what is left.
            if (runMethods) {
              report.meta["methods_settings"] = {{"scene", "builtin:temple"},
                                                 {"lights", s->methods.lights},
                                                 {"sizes", s->methods.sizes},
                                                 {"forward_max_lights", s->methods.forwardMaxLights},
                                                 {"rounds", s->methods.rounds},
                                                 {"min_rounds", s->methods.minRounds},
                                                 {"seconds", s->methods.seconds},
                                                 {"shadow_map", "reused (a static scene)"}};
              Scene temple = loadScene("builtin:temple", o->render.lights);
              report.methods = methodStudy(ctx, temple, o->render, s->methods);
              report.skips = skipSavings(ctx, temple, o->render, 6);
              std::fprintf(stderr, "gblens bench: method comparison done [%s]\n", minutes(since(start)).c_str());
            }
            // Every scene first: one that does not load is skipped before the budget is shared out.
            std::vector<std::string> skippedScenes;
            std::vector<std::unique_ptr<Scene>> scenes;
            for (const std::string& spec : variants.empty() ? std::vector<std::string>{} : s->scenes) {
              try {
                scenes.push_back(std::make_unique<Scene>(loadScene(spec, o->render.lights)));
              } catch (const SceneError& e) {
                std::fprintf(stderr, "gblens bench: skipping %s: %s\n", spec.c_str(), e.message.c_str());
                skippedScenes.push_back(spec + ": " + e.message);
              }
            }
            const size_t rowsTotal = variants.size() * scenes.size();
            size_t rowsDone = 0;
            std::vector<double> rowSeconds;  // whole time of each measured row (warm-up, timed, error)
            for (std::unique_ptr<Scene>& loaded : scenes) {
              Scene& scene = *loaded;
              Renderer r;
              initRenderer(r, ctx, scene);
              ReferenceCache cache(scene);
              std::map<std::string, size_t> measuredRows;  // options -> row index
              for (const BenchVariant& v : variants) {
                ++rowsDone;
                BenchRow row;
                row.scene = scene.source;
                row.group = v.group;
                row.name = v.name();
                row.label = v.label();
                row.options = o->render;
                for (auto& [k, value] : v.set)
                  if (!setOption(row.options, k, value, error)) {
                    std::fprintf(stderr, "gblens bench: variant %s: %s\n", row.name.c_str(), error.c_str());
                    return 2;
                  }
                if (v.group == "lights" && !scene.generatedLights) {
                  row.note = "the scene has its own lights";
                  report.rows.push_back(row);
                  continue;
                }
                if (scene.generatedLights && int(scene.lights.size()) != row.options.lights)
                  generateLights(scene, row.options.lights);
                std::string key = optionsJson(row.options).dump();
                if (auto it = measuredRows.find(key); it != measuredRows.end()) {
                  BenchRow copy = report.rows[it->second];
                  copy.group = row.group;
                  copy.name = row.name;
                  copy.label = row.label;
                  copy.note = "same options as " + report.rows[it->second].name;
                  report.rows.push_back(copy);
                  continue;
                }
                // 85% of the budget for the sweep rows (the rest: A/B checks, depth study). A row may
                // use what is left after the typical row's time is set aside for each row to come,
                // so slow rows (4096 lights) get their frames when the run is on schedule.
                const auto rowStart = Clock::now();
                double left = 0.85 * s->budget - since(start);
                double typical = rowSeconds.empty() ? 10.0 : timingOf(rowSeconds).median;
                double cap = std::min(s->variantSeconds, std::max(left - typical * double(rowsTotal - rowsDone), 0.0));
                timeVariant(r, row.options, *s, o->frames, cap, row);
                FrameError e = measureFrame(r, row.options, cache);
                rowSeconds.push_back(since(rowStart));
                row.error = errorSummary(e);
                row.errorDetail = errorJson(e);
                row.measured = true;
                measuredRows[key] = report.rows.size();
                report.rows.push_back(row);
                std::fprintf(stderr,
                             "[%2zu/%zu] %-16s %-44s %3d fr %8.1f ms (%.1f-%.1f) | normal %.2e deg  pos %.1e  shadow "
                             "%.3f%%  light %.1e  hdr %.1e  [%s]\n",
                             rowsDone, rowsTotal, scene.source.c_str(), row.name.c_str(), row.frames, row.frameMs.median,
                             row.frameMs.min, row.frameMs.max, row.error["normal_deg_mean"], row.error["position_rel_mean"],
                             100.0 * row.error["shadow_mismatch"], row.error["lighting_rel_mean"],
                             row.error["hdr_rel_mean"], minutes(since(start)).c_str());
              }
              // Variants whose errors are no worse than the defaults': only time can make them
              // dominate, so it is measured again by an interleaved A/B (the sweep's medians drift).
              const std::string defaultKey = optionsJson(o->render).dump();
              if (measuredRows.count(defaultKey)) {
                if (scene.generatedLights) generateLights(scene, o->render.lights);
                for (const std::string& name : errorNoWorseThanDefaults(report.rows, scene.source, report.tolerances)) {
                  {
                    BenchRow* v = nullptr;
                    for (BenchRow& row : report.rows)
                      if (row.scene == scene.source && row.name == name) v = &row;
                    if (!v || v->note.rfind("same options", 0) == 0) continue;
                    // Up to 12 pairs, within a quarter of the budget left.
                    double left = s->budget - since(start);
                    int pairs = std::clamp(int(left / 4.0 / std::max(v->frameMs.median * 2e-3, 1e-3)), 0, 12);
                    if (pairs < 4) continue;
                    Renderer ra, rb;  // both fresh: neither side inherits the sweep's history
                    initRenderer(ra, ctx, scene);
                    initRenderer(rb, ctx, scene);
                    AbResult ab = interleavedRatio(ra, o->render, rb, v->options, pairs, s->shadowReuse == "on");
                    v->abTimeRatio = ab.median;
                    v->abTimeRatioUpperQuartile = ab.upperQuartile;
                    v->abPairs = pairs;
                    destroyRenderer(rb);
                    destroyRenderer(ra);
                    std::fprintf(stderr, "[a/b] %-16s %-44s %.3fx the defaults' frame time (upper quartile %.3fx, %d "
                                 "interleaved pairs)\n",
                                 scene.source.c_str(), name.c_str(), v->abTimeRatio, v->abTimeRatioUpperQuartile, pairs);
                  }
                }
              }
              // The defaults once more: drift of the machine during the sweep (the defaults check
              // takes the faster of the two runs, so noise cannot make a variant look better).
              if (measuredRows.count(optionsJson(o->render).dump()) && since(start) < 0.9 * s->budget) {
                if (scene.generatedLights) generateLights(scene, o->render.lights);
                BenchRow row;
                row.scene = scene.source;
                row.group = "repeat";
                row.name = row.label = "default (repeat)";
                row.options = o->render;
                timeVariant(r, row.options, *s, o->frames, s->variantSeconds, row);
                row.measured = true;
                row.error = report.rows[measuredRows[optionsJson(o->render).dump()]].error;
                std::fprintf(stderr, "[repeat] %-16s %-44s %3d fr %8.1f ms (%.1f-%.1f)\n", scene.source.c_str(),
                             row.name.c_str(), row.frames, row.frameMs.median, row.frameMs.min, row.frameMs.max);
                report.rows.push_back(row);
              }
              if (scene.generatedLights) generateLights(scene, o->render.lights);
              destroyRenderer(r);
              std::fprintf(stderr, "gblens bench: %s done (reference: %.1f s of CPU time)\n", scene.source.c_str(),
                           cache.seconds);
            }
            if (s->depthRange == "on" && !variants.empty() && since(start) < 0.95 * s->budget)
              report.depthRange = depthRangeStudy(ctx, o->render);
            else if (s->depthRange == "on" && !variants.empty())
              std::fprintf(stderr, "gblens bench: no time left for the depth-range study (--budget)\n");
            report.meta["skipped_scenes"] = skippedScenes;
            report.meta["seconds"] = since(start);
            markFrontiers(report.rows);
            report.defaults = checkDefaults(report.rows, report.tolerances);

            int status = 0;
            const std::filesystem::path dir(s->out);
            if (!writeFile((dir / "bench.json").string(), benchJson(report).dump(2) + "\n", error) ||
                !writeFile((dir / "bench.csv").string(), benchCsv(report), error) ||
                !writeFile((dir / "bench.md").string(), benchMarkdown(report), error) ||
                (!report.methods.empty() && !writeFile((dir / "methods.csv").string(), methodsCsv(report), error)) ||
                !writeBenchPlots(report, s->out, error)) {
              std::fprintf(stderr, "gblens bench: %s\n", error.c_str());
              status = 2;
            }
            for (const DefaultsCheck& c : report.defaults)
              std::fprintf(stderr, "gblens bench: %s: defaults %s\n", c.scene.c_str(),
                           c.onFrontier ? "on the frontier" : ("dominated by " + [&] {
                             std::string d;
                             for (const std::string& n : c.dominatedBy) d += n + " ";
                             return d;
                           }()).c_str());
            std::fprintf(stderr, "gblens bench: wrote %s/{bench.json,bench.csv,bench.md,time_vs_error.png,time_vs_lights.png%s%s} in %s\n",
                         s->out.c_str(), report.depthRange.empty() ? "" : ",depth_range.png",
                         report.methods.empty() ? "" : ",methods.csv,methods_vs_lights.png", minutes(since(start)).c_str());
            bool anyMeasured = false;
            for (const BenchRow& row : report.rows) anyMeasured |= row.measured;
            for (const MethodRow& row : report.methods) anyMeasured |= row.measured;
            if (!anyMeasured && status == 0) {
              std::fprintf(stderr, "gblens bench: no scene could be measured\n");
              status = 2;
            }
            if (reportValidation(ctx) && status == 0) status = 1;
            destroyContext(ctx);
            return status;
          }};
}

}  // namespace gb
