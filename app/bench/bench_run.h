// Measuring one bench variant: timed frames after warm-up, an interleaved A/B against the
// defaults, and the depth-range study (position error of every depth source vs far/near).
#pragma once
#include <string>
#include <vector>

#include "app/bench/bench_attach.h"
#include "app/bench/bench_temporal.h"
#include "app/bench/bench_methods.h"
#include "app/bench/bench_report.h"
#include "renderer/frame/renderer.h"

namespace gb {

struct BenchSettings {  // gblens bench's own flags
  std::vector<std::string> scenes = {"builtin:temple"};
  std::string out = "out/bench";
  int warmup = 3;
  double variantSeconds = 60.0;  // most time the timed frames of one variant may take
  double budget = 780.0;         // the whole run (all scenes, A/B checks, depth study), seconds: 13 min
  int minFrames = 5;
  int abPairs = 20;              // interleaved A/B pairs per variant at most (20: a 96% interval r(6)..r(15))
  std::string lightsSweep = "0,16,256,1024,4096";
  std::string sizes = "640x360,1280x720,1920x1080";
  std::string only;              // comma-separated variant names or groups (empty: all)
  std::string depthRange = "on";
  // Off: every frame renders the shadow map, as when the sun or the geometry moves, so shadow
  // map sizes and formats pay for themselves. On: a static scene's reuse applies.
  std::string shadowReuse = "off";
  // The method comparison (and the skip savings) on builtin:temple; runs unless --only leaves
  // out "methods".
  MethodSettings methods;
  std::string methodsLights = "16,64,256,1024,4096";
  std::string methodsSizes = "1280x720";
  // The cost of gblens attach (bench_attach.h); runs unless --only leaves out "attach".
  AttachBenchSettings attach;
  TemporalBenchSettings temporal;
};

// Warm-up frames, then up to `frames` timed frames within `cap` seconds (at least minFrames):
// fills row.frames, frameMs, gpuMs, passes (notes when frames were cut).
void timeVariant(Renderer& r, const RenderOptions& o, const BenchSettings& s, int frames, double cap, BenchRow& row);

// Frames of the defaults (renderer a) and of a variant (renderer b) alternate, the order
// swapped every pair, so drift and other processes' load hit both alike: the per-pair
// frame-time ratios b / a and their statistics (bench_report.h).
AbResult interleavedRatio(Renderer& a, const RenderOptions& oa, Renderer& b, const RenderOptions& ob, int pairs,
                          bool reuse);

// builtin:depth-range at far/near 1e2..1e6: max/mean |P - P_ref| / depth of eye depth, D32F
// standard and reversed, D24, and stored positions.
std::vector<DepthRangeRow> depthRangeStudy(GpuContext& ctx, const RenderOptions& base);

// builtin:depth-range (far/near 1e6) with twin cards `gap` behind: the share of z-fighting pixels
// per card depth, for D32F and D24 with standard and reversed Z.
std::vector<DepthTestRow> depthTestStudy(GpuContext& ctx, const RenderOptions& base, const std::vector<double>& gaps,
                                         uint32_t width = 640, uint32_t height = 360);

}  // namespace gb
