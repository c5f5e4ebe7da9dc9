// Timing one variant, the interleaved A/B, and the depth-range study (see bench_run.h).
#include "app/bench/bench_run.h"

#include <algorithm>
#include <cstdio>

#include "renderer/core/statistics.h"
#include "renderer/frame/session.h"
#include "renderer/scene/builtin.h"
#include "views/analysis/accuracy.h"

namespace gb {

// Times one variant: warm-up, then timed frames within `cap` seconds.
void timeVariant(Renderer& r, const RenderOptions& o, const BenchSettings& s, int frames, double cap, BenchRow& row) {
  const bool reuse = s.shadowReuse == "on";
  double last = 0.0, warm = 0.0;
  // The first frame builds pipelines and targets; slow variants stop warming after a third of
  // their time cap.
  for (int i = 0; i < s.warmup && (i < 2 || warm < cap / 3.0); ++i) {
    if (!reuse) r.shadowKey.reset();
    const FrameStats& st = renderFrame(r, o);
    last = st.frameMs / 1000.0;
    warm += last;
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
    if (!reuse) r.shadowKey.reset();
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
  row.passes = passTimings(stats);
}

// Interleaved A/B: frames of the defaults (renderer a) and of a variant (renderer b, its own
// targets) alternate, order swapped every pair, so drift and load from other processes hit both
// alike. Returns the per-pair ratios b / a with their median and its confidence interval.
AbResult interleavedRatio(Renderer& a, const RenderOptions& oa, Renderer& b, const RenderOptions& ob, int pairs,
                          bool reuse) {
  auto frame = [reuse](Renderer& r, const RenderOptions& o) {
    if (!reuse) r.shadowKey.reset();
    return renderFrame(r, o).frameMs;
  };
  for (int i = 0; i < 2; ++i) {
    frame(a, oa);
    frame(b, ob);
  }
  std::vector<double> ratios;
  for (int i = 0; i < pairs; ++i) {
    double ta, tb;
    if (i % 2) {
      tb = frame(b, ob);
      ta = frame(a, oa);
    } else {
      ta = frame(a, oa);
      tb = frame(b, ob);
    }
    ratios.push_back(tb / ta);
  }
  return abStatistics(std::move(ratios));
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
      auto render = [&](const RenderOptions& ro, const std::vector<Target>& t) { return renderSnapshot(r, ro, t); };
      FrameError e = measureFrame(render, o, cache).error;
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

// Z-fighting per card depth: primitive_id says which of the two cards each pixel shows.
std::vector<DepthTestRow> depthTestStudy(GpuContext& ctx, const RenderOptions& base, const std::vector<double>& gaps,
                                         uint32_t width, uint32_t height) {
  std::vector<DepthTestRow> out;
  struct Config {
    const char* source;
    bool reversed;
    DepthFormat format;
  };
  const Config configs[] = {{"d32_standard", false, DepthFormat::D32S8},
                            {"d32_reversed", true, DepthFormat::D32S8},
                            {"d24_standard", false, DepthFormat::D24S8},
                            {"d24_reversed", true, DepthFormat::D24S8}};
  const double znear = 0.1, zfar = 1e5;
  for (double gap : gaps) {
    Scene scene = depthRangeScene(znear, zfar, gap);
    const Scene plain = depthRangeScene(znear, zfar);
    const uint32_t cards = scene.meshes[0].indexCount / 12, first = firstPrimitiveIds(scene)[0];
    Renderer r;
    initRenderer(r, ctx, scene);
    for (const Config& c : configs) {
      RenderOptions o = base;
      o.width = width;
      o.height = height;
      o.lights = 0;
      o.camera = 0;
      o.reversedZ = c.reversed;
      o.depthFormat = c.format;
      o.primitiveId = true;
      o.fairies = false;
      FrameSnapshot f = renderSnapshot(r, o, {Target::PrimitiveId});
      const CpuImage& ids = f.target(Target::PrimitiveId).image;
      std::vector<uint64_t> front(cards, 0), back(cards, 0);
      for (uint32_t y = 0; y < ids.height; ++y)
        for (uint32_t x = 0; x < ids.width; ++x) {
          uint32_t id = ids.raw(x, y, 0);
          if (id < first) continue;
          uint32_t t = (id - first) / 2;  // a card: two triangles; the twins come first
          if (t < cards)
            back[t]++;
          else if (t < 2 * cards)
            front[t - cards]++;
        }
      for (uint32_t k = 0; k < cards; ++k) {
        // The front card's depth, as built (the scene without twins has the same cards).
        double depth = -double(plain.vertices[plain.meshes[0].firstVertex + 4 * k].position.z);  // its front card
        uint64_t all = front[k] + back[k];
        out.push_back({c.source, gap, znear, zfar, depth, all ? double(back[k]) / double(all) : 0.0});
      }
    }
    destroyRenderer(r);
    std::fprintf(stderr, "gblens bench: depth test, gap %.0e measured\n", gap);
  }
  return out;
}

}  // namespace gb
