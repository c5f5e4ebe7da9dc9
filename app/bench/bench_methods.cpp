// The method comparison and the skip savings of gblens bench (see bench_methods.h). Methods are
// timed in rounds, one burst of frames in flight of each per round in rotated order, on a renderer
// each (their own targets and pipelines), so drift and other processes' load hit every method
// alike and the ratios to the defaults (the method auto picks on this device) come from bursts
// taken side by side. A burst's frame time is its throughput (renderBurst: the CPU records a frame
// while the GPU runs the one before).
#include "app/bench/bench_methods.h"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <memory>

#include "renderer/core/method_choice.h"
#include "renderer/vk/check.h"

namespace gb {

namespace {

using Clock = std::chrono::steady_clock;
double since(Clock::time_point t) { return std::chrono::duration<double>(Clock::now() - t).count(); }


double passMs(const FrameStats& st, const std::string& name) {
  for (const PassStat& p : st.passes)
    if (p.name == name && !p.skipped) return p.ms;
  return 0.0;
}

// One (size, lights) cell of the comparison: each method's options, row, and whether it is timed.
struct Cell {
  std::vector<RenderOptions> opts;
  std::vector<MethodRow> rows;
  std::vector<bool> active;
  size_t reference = 0;  // the row auto picks: `x defaults` is relative to it
};

Cell makeCell(const GpuContext& ctx, const Scene& scene, const RenderOptions& base, const MethodSettings& s,
              const std::string& size, int lights) {
  const auto& methods = benchMethods();
  const size_t n = methods.size();
  Cell c{std::vector<RenderOptions>(n, base), std::vector<MethodRow>(n), std::vector<bool>(n, true), 0};
  RenderOptions autoOptions = base;
  autoOptions.method = Method::Auto;
  autoOptions.lights = lights;
  const MethodChoice pick = chooseMethod(autoOptions, ctx.isCpu ? DeviceKind::Cpu : DeviceKind::Gpu, scene.lights.size());
  for (size_t i = 0; i < n; ++i) {
    RenderOptions& o = c.opts[i];
    std::string error;
    const bool sizeOk = setOption(o, "size", size, error);  // checked by gblens bench
    GB_ASSERT(sizeOk);
    o.lights = lights;
    o.coverage = false;
    const std::string& m = methods[i].first;
    const bool parsed = parse(m == "deferred_unculled" ? std::string("deferred") : m, o.method);
    GB_ASSERT(parsed);
    o.stencilCulling = m != "deferred_unculled";
    MethodRow& row = c.rows[i];
    row.scene = scene.source;
    row.method = m;
    row.flags = methods[i].second;
    row.options = o;
    row.autoPick = m == name(pick.method);
    if (row.autoPick) c.reference = i;
    if (m == "forward" && lights > s.forwardMaxLights) {
      c.active[i] = false;
      row.note = "not measured above " + std::to_string(s.forwardMaxLights) + " lights (--methods-forward-max)";
    }
  }
  return c;
}

// A method's timed rounds: each burst's frame time (throughput), its counted frames, and the
// ratio to the reference method's burst of the same round.
struct Timed {
  std::vector<double> burstMs, ratios, steadyMs;
  std::vector<FrameStats> frames;
};

// Timed rounds: one burst of `burst` frames in flight of each active method per round, order
// rotated; per-round ratios to the reference method's burst.
void timeRounds(std::vector<std::unique_ptr<Renderer>>& rs, Cell& c, int rounds, int burst, std::vector<Timed>& timed) {
  const size_t n = c.rows.size();
  for (int k = 0; k < rounds; ++k) {
    std::vector<double> t(n, 0.0);
    for (size_t j = 0; j < n; ++j) {
      const size_t i = (j + size_t(k)) % n;  // rotated: no method always runs first
      if (!c.active[i]) continue;
      FrameBurst b = renderBurst(*rs[i], c.opts[i], burst);
      t[i] = b.msPerFrame;
      timed[i].burstMs.push_back(b.msPerFrame);
      if (b.steadyMs > 0.0) timed[i].steadyMs.push_back(b.steadyMs);
      for (FrameStats& f : b.frames) timed[i].frames.push_back(std::move(f));
    }
    for (size_t i = 0; i < n; ++i)
      if (c.active[i]) timed[i].ratios.push_back(t[i] / t[c.reference]);
  }
}

// A row's timings from its bursts (frame ms: the bursts' throughputs; GPU and CPU ms: their
// frames'), then its culling efficiency from one more frame with coverage on (not timed) where
// that is affordable.
void summarize(Renderer& r, const RenderOptions& o, MethodRow& row, const Timed& timed, const MethodSettings& s) {
  const std::vector<FrameStats>& frames = timed.frames;
  std::vector<double> gpuMs, cpuMs;
  for (const FrameStats& f : frames) {
    gpuMs.push_back(f.gpuMs);
    cpuMs.push_back(f.cpuMs);
  }
  row.measured = true;
  row.frames = int(frames.size());
  row.bursts = int(timed.burstMs.size());
  row.frameMs = timingOf(timed.burstMs);
  if (!timed.steadyMs.empty()) row.steadyMs = timingOf(timed.steadyMs);
  row.gpuMs = timingOf(gpuMs);
  row.cpuMs = timingOf(cpuMs);
  row.passes = passTimings(frames);
  row.overDefault = timingOf(timed.ratios).median;
  row.lightSetup = frames.back().lightSetup;
  row.gbuffer = frames.back().gbuffer;
  row.overlap = frames.back().overlap;
  row.clusterAssign = frames.back().clusterAssign;
  if (frames.back().clusters.valid) row.clusters = frames.back().clusters;
  // Forward's count is its visible lights times its shaded fragments; a frame over 3 s is not spent on it.
  if (row.frameMs.median > 3000.0) {
    row.note += "culling not measured (a frame takes " + std::to_string(int(row.frameMs.median / 1000.0)) + " s); ";
    return;
  }
  // The ideal pairs are counted on the CPU, light by light over its screen rectangle: at 4K with
  // 65536 lights that is about a minute per frame.
  if (double(o.width) * o.height * o.lights > s.cullingMaxPixelLights) {
    row.note += "culling not measured (pixels x lights above --methods-culling-max); ";
    return;
  }
  const FrameStats& st = renderCountingFrame(r, o);
  row.cullingValid = st.culling.valid;
  row.invocations = st.culling.invocations;
  row.idealPairs = st.culling.idealPairs;
  row.workOverIdeal = st.culling.workOverIdeal;
}

void logRow(const std::string& size, int lights, const MethodRow& row) {
  std::fprintf(stderr, "[methods] %-10s %5d lights %-18s ", size.c_str(), lights, row.method.c_str());
  if (row.measured)
    std::fprintf(stderr, "%2d fr %9.2f ms (cpu %.2f) x%.2f defaults  work/ideal %s  gbuffer %s%s\n", row.frames,
                 row.frameMs.median, row.cpuMs.median, row.overDefault,
                 row.cullingValid ? std::to_string(row.workOverIdeal).c_str() : "-", row.gbuffer.c_str(),
                 row.autoPick ? "  [auto]" : "");
  else
    std::fprintf(stderr, "%s\n", row.note.c_str());
}

}  // namespace

// Per-pass medians over frames, in the last frame's pass order (a pass counts where it ran).
std::vector<PassTiming> passTimings(const std::vector<FrameStats>& frames) {
  std::vector<PassTiming> out;
  if (frames.empty()) return out;
  const FrameStats& last = frames.back();
  for (size_t i = 0; i < last.passes.size(); ++i) {
    PassTiming p;
    p.name = last.passes[i].name;
    p.skipped = last.passes[i].skipped;
    p.reason = last.passes[i].reason;
    std::vector<double> ms, before;
    for (const FrameStats& f : frames)
      if (i < f.passes.size() && f.passes[i].name == p.name && !f.passes[i].skipped) {
        ms.push_back(f.passes[i].ms);
        before.push_back(f.passes[i].beforeMs);
      }
    p.ms = timingOf(ms);
    p.beforeMs = timingOf(before);
    out.push_back(p);
  }
  return out;
}

std::vector<MethodRow> methodStudy(GpuContext& ctx, Scene& scene, const RenderOptions& base, const MethodSettings& s) {
  const auto start = Clock::now();
  const size_t n = benchMethods().size();
  std::vector<MethodRow> out;
  const size_t cellsTotal = s.sizes.size() * s.lights.size();
  size_t cellsDone = 0;
  for (const std::string& size : s.sizes) {
    std::vector<std::unique_ptr<Renderer>> rs;
    for (size_t i = 0; i < n; ++i) {
      rs.push_back(std::make_unique<Renderer>());
      initRenderer(*rs.back(), ctx, scene);
    }
    std::vector<double> lastMs(n, 0.0);  // each method's last frame at this size
    int lastLights = 0;
    for (int lights : s.lights) {
      ++cellsDone;
      if (scene.generatedLights) generateLights(scene, lights);
      Cell c = makeCell(ctx, scene, base, s, size, lights);
      // Warm-up: a frame of each (pipelines, targets, light buffers), except for a method that
      // already ran at this size and takes over a second a frame: its estimate is scaled.
      double roundMs = 0.0;
      for (size_t i = 0; i < n; ++i) {
        if (!c.active[i]) continue;
        if (lastMs[i] == 0.0 || lastMs[i] < 1000.0) {
          lastMs[i] = renderFrame(*rs[i], c.opts[i]).frameMs;
          if (lastMs[i] > 1000.0)  // slow cells say where the time goes
            std::fprintf(stderr, "[methods] %s %d lights %s: warm-up frame %.1f s\n", size.c_str(), lights,
                         c.rows[i].method.c_str(), lastMs[i] / 1000.0);
        } else if (lastLights > 0) {
          lastMs[i] *= double(std::max(lights, 1)) / std::max(lastLights, 1);
        }
        roundMs += lastMs[i] * s.burst;
      }
      lastLights = lights;
      // This cell's share of what is left of the comparison's time.
      const double share = (s.seconds - since(start)) / double(cellsTotal - cellsDone + 1);
      const int rounds = std::clamp(int(share * 1000.0 / std::max(roundMs, 1e-3)), s.minRounds, s.rounds);
      std::vector<Timed> timed(n);
      timeRounds(rs, c, rounds, s.burst, timed);
      for (size_t i = 0; i < n; ++i) {
        if (!c.active[i]) continue;
        summarize(*rs[i], c.opts[i], c.rows[i], timed[i], s);
        lastMs[i] = c.rows[i].frameMs.median;
      }
      for (const MethodRow& row : c.rows) {
        logRow(size, lights, row);
        out.push_back(row);
      }
    }
    for (auto& r : rs) destroyRenderer(*r);
  }
  if (scene.generatedLights) generateLights(scene, base.lights);
  return out;
}
std::vector<SkipRow> skipSavings(GpuContext& ctx, Scene& scene, const RenderOptions& base, int pairs) {
  if (scene.generatedLights) generateLights(scene, base.lights);
  Renderer r;
  initRenderer(r, ctx, scene);
  std::vector<SkipRow> out;
  // Pairs of frames, one running the pass and one skipping it, the order swapped every pair.
  auto measure = [&](SkipRow row, auto&& runFrame, auto&& skipFrame) {
    runFrame();
    skipFrame();  // warm-up of both shapes
    std::vector<double> saved, ms;
    for (int k = 0; k < pairs; ++k) {
      double tRun, tSkip;
      if (k % 2) {
        tSkip = skipFrame().frameMs;
        const FrameStats& st = runFrame();
        tRun = st.frameMs;
        ms.push_back(passMs(st, row.pass));
      } else {
        const FrameStats& st = runFrame();
        tRun = st.frameMs;
        ms.push_back(passMs(st, row.pass));
        tSkip = skipFrame().frameMs;
      }
      saved.push_back(tRun - tSkip);
    }
    row.savedMs = timingOf(saved).median;
    row.passMs = timingOf(ms).median;
    row.pairs = pairs;
    std::fprintf(stderr, "[skips] %-14s saves %.2f ms a frame (the pass: %.2f ms)\n", row.pass.c_str(), row.savedMs,
                 row.passMs);
    out.push_back(row);
  };
  RenderOptions o = base;
  o.coverage = false;
  measure({"shadow_map", "sun and geometry unchanged since the last frame (reused)", "frames re-rendering the map vs reusing it"},
          [&]() -> const FrameStats& { r.shadowKey.reset(); return renderFrame(r, o); },
          [&]() -> const FrameStats& { return renderFrame(r, o); });
  RenderOptions noSky = o;
  noSky.sky = false;
  measure({"skybox", "no sky pixel in the last frame with this camera and geometry",
           "sky on vs off (the temple's view shows sky; off stands in for a covered view)"},
          [&]() -> const FrameStats& { return renderFrame(r, o); },
          [&]() -> const FrameStats& { return renderFrame(r, noSky); });
  RenderOptions noFairies = o;
  noFairies.fairies = false;
  measure({"fairy_lights", "fairies disabled, or no visible point light", "fairies on vs off"},
          [&]() -> const FrameStats& { return renderFrame(r, o); },
          [&]() -> const FrameStats& { return renderFrame(r, noFairies); });
  destroyRenderer(r);
  return out;
}

}  // namespace gb
