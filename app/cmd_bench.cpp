// gblens bench: the sweep of app/bench_variants.cpp on each scene: per variant, warm-up frames,
// then the median (min, max) of timed frames (whole-frame wall ms, GPU ms, per pass), then one
// frame measured against the reference; then the depth-range study (builtin:depth-range). Writes
// bench.json, bench.csv, bench.md and the plots to --out. A whole-run time budget shortens the
// timed runs of slow variants rather than overrunning (each row says how many frames it got).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>
#include <sstream>

#include "app/bench_variants.h"
#include "app/cli.h"
#include "renderer/builtin.h"
#include "views/accuracy.h"
#include "views/bench_report.h"
#include "views/image_io.h"
#include "views/report.h"

namespace gb {

namespace {

struct BenchSettings {
  std::vector<std::string> scenes = {"builtin:temple"};
  std::string out = "out/bench";
  int warmup = 3;
  double variantSeconds = 30.0;  // most time the timed frames of one variant may take
  double budget = 840.0;         // the whole run (all scenes and the depth-range study), seconds
  int minFrames = 5;
  std::string lightsSweep = "0,16,256,1024,4096";
  std::string sizes = "640x360,1280x720,1920x1080";
  std::string only;              // comma-separated variant names or groups (empty: all)
  std::string depthRange = "on";
  // Off: every frame renders the shadow map, as when the sun or the geometry moves, so shadow
  // map sizes and formats pay for themselves. On: a static scene's reuse applies.
  std::string shadowReuse = "off";
};

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

// Times one variant: warm-up, then timed frames within `cap` seconds.
void timeVariant(Renderer& r, const RenderOptions& o, const BenchSettings& s, int frames, double cap, BenchRow& row) {
  const bool reuse = s.shadowReuse == "on";
  double last = 0.0;
  for (int i = 0; i < s.warmup; ++i) {
    if (!reuse) r.shadowKey.clear();
    const FrameStats& st = renderFrame(r, o);
    last = st.frameMs / 1000.0;
    if (reuse)
      for (const PassStat& p : st.passes)
        if (p.name == "shadow_map" && !p.skipped) row.note += "shadow map rendered in " + std::to_string(p.ms) + " ms (reused after); ";
  }
  int n = frames;
  if (last * n > cap) {
    n = std::max(s.minFrames, int(cap / std::max(last, 1e-6)));
    if (n < frames) row.note += "frames reduced to " + std::to_string(n) + " (time budget); ";
  }
  std::vector<FrameStats> stats;
  for (int i = 0; i < n; ++i) {
    if (!reuse) r.shadowKey.clear();
    stats.push_back(renderFrame(r, o));
  }
  std::vector<double> frameMs, gpuMs;
  for (const FrameStats& f : stats) {
    frameMs.push_back(f.frameMs);
    gpuMs.push_back(f.gpuMs);
  }
  row.frames = n;
  row.frameMs = timingOf(frameMs);
  row.gpuMs = timingOf(gpuMs);
  const FrameStats& lastFrame = stats.back();
  for (size_t i = 0; i < lastFrame.passes.size(); ++i) {
    PassTiming p;
    p.name = lastFrame.passes[i].name;
    p.skipped = lastFrame.passes[i].skipped;
    p.reason = lastFrame.passes[i].reason;
    std::vector<double> ms;
    for (const FrameStats& f : stats)
      if (i < f.passes.size() && f.passes[i].name == p.name && !f.passes[i].skipped) ms.push_back(f.passes[i].ms);
    p.ms = timingOf(ms);
    row.passes.push_back(p);
  }
}

// Position error of every depth source across far/near ratios (the depth-precision targets).
std::vector<DepthRangeRow> depthRangeStudy(GpuContext& ctx, const RenderOptions& base) {
  std::vector<DepthRangeRow> out;
  struct Config {
    const char* source;
    bool reversed;
    DepthFormat format;
    PositionSource position;
    PositionSpace space;
  };
  const Config configs[] = {{"d32_standard", false, DepthFormat::D32S8, PositionSource::Depth, PositionSpace::World},
                            {"d32_reversed", true, DepthFormat::D32S8, PositionSource::Depth, PositionSpace::World},
                            {"d24_standard", false, DepthFormat::D24S8, PositionSource::Depth, PositionSpace::World},
                            {"rgba32f_world", false, DepthFormat::D32S8, PositionSource::Rgba32f, PositionSpace::World},
                            {"rgba32f_camera", false, DepthFormat::D32S8, PositionSource::Rgba32f, PositionSpace::Camera},
                            {"rgba16f_camera", false, DepthFormat::D32S8, PositionSource::Rgba16f, PositionSpace::Camera}};
  for (double ratio : {1e2, 1e3, 1e4, 1e5, 1e6}) {
    const double znear = 0.1, zfar = znear * ratio;
    Scene scene = depthRangeScene(znear, zfar);
    Renderer r;
    initRenderer(r, ctx, scene);
    ReferenceCache cache(scene);
    for (const Config& c : configs) {
      RenderOptions o = base;
      o.width = 640;
      o.height = 360;
      o.lights = 0;
      o.camera = 0;
      o.reversedZ = c.reversed;
      o.depthFormat = c.format;
      o.position = c.position;
      o.positionSpace = c.space;
      FrameError e = measureFrame(r, o, cache);
      auto add = [&](const std::string& source, const PositionError& p) {
        out.push_back({ratio, znear, zfar, source, p.relative.max, p.relative.mean});
      };
      if (c.position != PositionSource::Depth) {
        add(c.source, e.fromPosition);
        continue;
      }
      if (&c == &configs[0]) add("eye_depth", e.fromEyeDepth);
      add(c.source, e.fromHardwareDepth);
    }
    destroyRenderer(r);
    std::fprintf(stderr, "gblens bench: depth range far/near %.0e measured\n", ratio);
  }
  return out;
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
  cmd->add_option("--only", s->only, "measure only these variants or groups (comma-separated names, e.g. default,normal)");
  cmd->add_option("--depth-range", s->depthRange, "the depth-precision study on builtin:depth-range")
      ->check(CLI::IsMember({"on", "off"}))
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
            std::vector<int> lightCounts;
            for (const std::string& v : split(s->lightsSweep)) {
              RenderOptions probe;
              if (!setOption(probe, "lights", v, error)) {
                std::fprintf(stderr, "gblens bench: --lights-sweep: %s\n", error.c_str());
                return 2;
              }
              lightCounts.push_back(probe.lights);
            }
            std::vector<std::string> sizes = split(s->sizes);
            for (const std::string& v : sizes) {
              RenderOptions probe;
              if (!setOption(probe, "size", v, error)) {
                std::fprintf(stderr, "gblens bench: --sizes: %s\n", error.c_str());
                return 2;
              }
            }
            std::vector<BenchVariant> variants = defaultSweep(lightCounts, sizes);
            if (!s->only.empty()) {
              std::vector<std::string> only = split(s->only);
              std::vector<BenchVariant> kept;
              for (const BenchVariant& v : variants)
                if (std::find(only.begin(), only.end(), v.name()) != only.end() ||
                    std::find(only.begin(), only.end(), v.group) != only.end())
                  kept.push_back(v);
              if (kept.empty()) {
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
                           {"git", GBLENS_GIT_HASH},
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
                                               " s (or its share of the remaining budget) gets fewer (at least " +
                                               std::to_string(s->minFrames) +
                                               "). " + (s->shadowReuse == "on" ? "Shadow map reused in steady state. "
                                                                                : "Every timed frame renders the shadow map (as with a moving sun). ") +
                                               "Error figures: one more frame with primitive_id on and fairies off."}};
            std::vector<std::string> skippedScenes;
            const size_t rowsTotal = variants.size() * s->scenes.size();
            size_t rowsDone = 0;
            for (const std::string& spec : s->scenes) {
              Scene scene;
              try {
                scene = loadScene(spec, o->render.lights);
              } catch (const SceneError& e) {
                std::fprintf(stderr, "gblens bench: skipping %s: %s\n", spec.c_str(), e.message.c_str());
                skippedScenes.push_back(spec + ": " + e.message);
                rowsDone += variants.size();
                continue;
              }
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
                double left = s->budget - since(start);
                double cap = std::min(s->variantSeconds, std::max(left, 0.0) / double(rowsTotal - rowsDone + 1) * 0.7);
                timeVariant(r, row.options, *s, o->frames, cap, row);
                FrameError e = measureFrame(r, row.options, cache);
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
              // The defaults once more: drift of the machine during the sweep (the defaults check
              // takes the faster of the two runs, so noise cannot make a variant look better).
              if (measuredRows.count(optionsJson(o->render).dump()) && since(start) < s->budget) {
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
            if (s->depthRange == "on") report.depthRange = depthRangeStudy(ctx, o->render);
            report.meta["skipped_scenes"] = skippedScenes;
            report.meta["seconds"] = since(start);
            markFrontiers(report.rows);
            report.defaults = checkDefaults(report.rows, report.tolerances);

            int status = 0;
            const std::filesystem::path dir(s->out);
            if (!writeFile((dir / "bench.json").string(), benchJson(report).dump(2) + "\n", error) ||
                !writeFile((dir / "bench.csv").string(), benchCsv(report), error) ||
                !writeFile((dir / "bench.md").string(), benchMarkdown(report), error) ||
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
            std::fprintf(stderr, "gblens bench: wrote %s/{bench.json,bench.csv,bench.md,time_vs_error.png,time_vs_lights.png%s} in %s\n",
                         s->out.c_str(), report.depthRange.empty() ? "" : ",depth_range.png", minutes(since(start)).c_str());
            bool anyMeasured = false;
            for (const BenchRow& row : report.rows) anyMeasured |= row.measured;
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
