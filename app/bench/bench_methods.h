// The method comparison of gblens bench (deferred stencil-culled, deferred unculled, forward,
// tiled, clustered at each size and light count, interleaved rounds of bursts of frames in
// flight, culling efficiency) and what the frame function's skips save (shadow map reuse,
// skybox, fairy lights).
#pragma once
#include <string>
#include <vector>

#include "app/bench/bench_report.h"
#include "renderer/frame/renderer.h"

namespace gb {

struct MethodSettings {
  std::vector<int> lights = {16, 64, 256, 1024, 4096};
  std::vector<std::string> sizes = {"1280x720"};
  // Forward shades every visible light at every fragment: on lavapipe about 11 s a frame at
  // 1024 lights, 45 s at 4096. Above this count it is listed as not measured.
  int forwardMaxLights = 1024;
  int rounds = 5;          // timed rounds per cell at most (one burst of each method per round)
  int minRounds = 3;       // ... and at least
  double seconds = 150.0;  // the whole comparison's share of the bench budget
  // Frames per burst (renderBurst): submitted in flight, the first waited for and not counted;
  // a method's frame ms is the bursts' throughput (--methods-burst).
  int burst = 6;
  // Culling efficiency needs the ideal pairs, counted on the CPU: cells with more pixels x
  // lights than this (1080p at 65536 lights) skip it.
  double cullingMaxPixelLights = 1920.0 * 1080.0 * 65536.0;
};

// How a method's frame ms is measured (bench.json's methods_settings.frame_ms, bench.md).
inline constexpr const char* kBurstFrameMs =
    "throughput of frames in flight: per round, one burst of `burst` frames of each method; the first is submitted "
    "and waited for (not counted), the others are submitted back to back (the CPU records a frame while the GPU runs "
    "the one before, at most frames_in_flight submitted); frame ms = wall time from the start of the second frame to "
    "the end of the last / (burst - 1), median over rounds (it includes the pipeline's fill: the smaller of one "
    "frame's CPU and GPU time over burst - 1); gpu ms and cpu ms are the counted frames' medians";
// How a method's steady ms is measured (methods_settings.steady_ms, bench.md).
inline constexpr const char* kSteadyMs =
    "the same bursts' steady state without the pipeline's fill: the GPU clock from the end of the first counted "
    "frame to the end of the last / (counted frames - 1), median over rounds; frame ms exceeds it by the fill, one "
    "frame's latency beyond the interval between frames over burst - 1 (larger where a frame's visibility pass runs "
    "before its compute part, beside the frame before: GBLENS_OVERLAP); absent without GPU timestamps";

// Every method at every (size, lights) of `s` on `scene` (generated lights), from `base`.
std::vector<MethodRow> methodStudy(GpuContext& ctx, Scene& scene, const RenderOptions& base, const MethodSettings& s);

// Per-pass medians over frames, in the last frame's pass order (a pass counts where it ran).
std::vector<PassTiming> passTimings(const std::vector<FrameStats>& frames);

// The defaults' frame with each skippable pass run and skipped, alternating on one renderer.
std::vector<SkipRow> skipSavings(GpuContext& ctx, Scene& scene, const RenderOptions& base, int pairs);

}  // namespace gb
