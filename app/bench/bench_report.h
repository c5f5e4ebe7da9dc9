// Bench results: one row per (scene, variant) with timings and error figures; the Pareto
// frontier of time vs error per quality group; whether the defaults are dominated; and the
// files: bench.json, bench.csv, bench.md, time_vs_error.png, time_vs_lights.png, depth_range.png;
// with the method comparison also methods.csv and methods_vs_lights.png.
#pragma once
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "renderer/core/frame_stats.h"
#include "renderer/core/options.h"

namespace gb {

// How a group of variants is judged: by one error figure (a key of BenchRow::error), or not at
// all for workload sweeps (lights, size), which get time-vs-workload plots instead. The bench
// sweep (app/bench_variants.cpp) names these groups.
struct BenchGroup {
  std::string name;
  std::string metric;  // empty: a workload sweep
  std::string title;   // plot panel title
};
const std::vector<BenchGroup>& benchGroups();
const BenchGroup* findBenchGroup(const std::string& name);

struct Timing {
  double median = 0.0, min = 0.0, max = 0.0;
};
Timing timingOf(std::vector<double> values);

struct PassTiming {
  std::string name;
  bool skipped = false;
  std::string reason;
  Timing ms;
  Timing beforeMs;  // PassStat::beforeMs: the gap between the pass before it and this one
};

// An interleaved A/B (bench_run.cpp): frames of the defaults and of a variant alternating, the
// per-pair frame-time ratios variant / defaults, and a distribution-free confidence interval of
// their median (order statistics k and n+1-k of the sorted ratios: for 12 pairs r(3)..r(10), 96%).
struct AbResult {
  std::vector<double> ratios;  // sorted
  double median = 0.0, lowerQuartile = 0.0, upperQuartile = 0.0;
  double ciLow = 0.0, ciHigh = 0.0, confidence = 0.0;  // the interval of the median and its coverage
  int pairs() const { return int(ratios.size()); }
};
AbResult abStatistics(std::vector<double> ratios);
// Time, judged from an A/B at its confidence: "faster" (the interval below 1), "slower" (above 1),
// "same within 5%" (inside [1 - tol, 1 + tol]), or "undecided" (the spread is wider than that).
std::string abVerdict(const AbResult& ab, double tolerance);

struct BenchRow {
  std::string scene, group, name, label;
  RenderOptions options;
  bool measured = false;     // false: skipped (see note)
  std::string note;          // why skipped, or "same as <row>", or "frames reduced"
  int frames = 0;
  Timing frameMs, gpuMs;     // whole-frame wall time (record + submit + wait); first to last GPU timestamp
  std::vector<PassTiming> passes;
  std::map<std::string, double> error;  // the summary figures (keys: see errorSummaryKeys())
  nlohmann::json errorDetail;           // the full gblens error JSON
  bool frontier = false;                // on its group's time-vs-error Pareto frontier
  // Interleaved A/B against the defaults (frames alternating, two fresh renderers), run for
  // variants whose errors are no worse than the defaults' (only time can decide those). Empty: not run.
  AbResult ab;
};

// Keys of BenchRow::error, in column order, with their meaning.
const std::vector<std::pair<std::string, std::string>>& errorSummaryKeys();

// One depth-range measurement: position error of one source at one far/near ratio.
struct DepthRangeRow {
  double ratio = 0.0, znear = 0.0, zfar = 0.0;
  std::string source;  // "eye_depth", "d32_standard", "d32_reversed", "d24_standard", "rgba32f_world", ...
  double relMax = 0.0, relMean = 0.0;
};

// A quality group's frontier and the defaults check. Error figures are deterministic (one frame
// against the reference): a variant's is no worse within a relative tolerance and the figure's
// significance floor (a fraction of a float ulp, a hundredth of a percent of pixels), better
// beyond them. Time is noisy: it is judged only from the interleaved A/B's confidence interval of
// the median ratio, never from the sweep's medians. A variant dominates the defaults when every
// error is no worse, its time is not slower (the interval's top at most 1 + tolerance), and it is
// better somewhere: an error figure, or time (the whole interval below 1).
struct DefaultsCheck {
  std::string scene;
  bool onFrontier = true;
  std::vector<std::string> dominatedBy;
  // Variants whose errors are no worse and better somewhere, but whose A/B could not show they are
  // not slower (undecided): dominance not established either way.
  std::vector<std::string> undecided;
};
struct BenchTolerances {
  double time = 0.05;   // 5%: timings on a shared machine are noisy
  double error = 0.05;  // 5%
};
// The error figures the defaults check compares, with their significance floors.
const std::vector<std::pair<std::string, double>>& dominanceObjectives();
void markFrontiers(std::vector<BenchRow>& rows);
// Variants of a quality group whose error figures are all no worse than the defaults' (so only
// frame time can decide whether they dominate): the ones to confirm by an interleaved A/B.
std::vector<std::string> errorNoWorseThanDefaults(const std::vector<BenchRow>& rows, const std::string& scene,
                                                  const BenchTolerances& tol);
std::vector<DefaultsCheck> checkDefaults(const std::vector<BenchRow>& rows, const BenchTolerances& tol);

// One cell of the method comparison (app/bench_methods.cpp): a lighting method at one size and
// light count, timed in rounds interleaved with the other methods (the same drift and load hit
// all), and its culling efficiency from one more frame with coverage on.
struct MethodRow {
  std::string scene;
  std::string method;  // "deferred" (stencil-culled), "deferred_unculled", "forward", "tiled", "clustered"
  std::string flags;   // the gblens flags that select it
  RenderOptions options;
  bool autoPick = false;  // the method --method auto (the defaults) runs in this cell on this device
  bool measured = false;
  std::string note;  // why not measured, or what was cut
  int frames = 0;  // counted frames (each burst's but its first)
  int bursts = 0;  // timed rounds: one burst of frames in flight each
  // frameMs: the bursts' throughput (wall time per counted frame, renderBurst); gpuMs, cpuMs: the
  // counted frames' (cpuMs: the CPU's part before submission, FrameStats::cpuMs).
  Timing frameMs, gpuMs, cpuMs;
  // The bursts' steady state without the pipeline's fill (FrameBurst::steadyMs); median 0: no
  // GPU timestamps.
  Timing steadyMs;
  std::string lightSetup;        // where the lights were set up ("cpu", "gpu")
  std::string gbuffer;           // how the G-buffer was filled ("raster", "visibility"; --gbuffer)
  bool overlap = false;          // its visibility pass ran beside the previous frame (GBLENS_OVERLAP)
  std::string clusterAssign;     // method clustered: where its lights were assigned ("cpu" grid, "gpu")
  ClusterStats clusters;         // method clustered: occupied clusters, list entries
  std::vector<PassTiming> passes;
  // Median over the rounds of this method's frame time / the auto-picked method's (the defaults)
  // in the same round (above 1: slower than the defaults).
  double overDefault = 0.0;
  // Culling efficiency: fragment invocations of the lighting work (coverage_masked summed: what
  // each method evaluated) / ideal (pixel, light) pairs (surface point inside the radius).
  bool cullingValid = false;
  uint64_t invocations = 0, idealPairs = 0;
  double workOverIdeal = 0.0;
};
// The methods' names in table order, and their flags.
const std::vector<std::pair<std::string, std::string>>& benchMethods();
// Lighting work of a method's frame: the sum of its lighting passes' ms (directional_light,
// light_mask, point_lights, tiled_lighting, the cluster passes, clustered_lighting, forward).
double lightingMs(const MethodRow& row);

// What a skip saves: frames with the pass run and frames with it skipped, alternating on one
// renderer; the median per-pair difference of the whole frame time, and the pass's own ms.
struct SkipRow {
  std::string pass, skippedWhen, measuredAs;
  double savedMs = 0.0, passMs = 0.0;
  int pairs = 0;
};

// The depth test's resolution: builtin:depth-range with a twin card behind each card at depth
// x (1 + gap), drawn after it; the share of the card's pixels where the twin wins the depth test
// (z-fighting: the depth format cannot separate the two at that depth).
struct DepthTestRow {
  std::string source;  // "d32_standard", "d32_reversed", "d24_standard", "d24_reversed"
  double gap = 0.0, znear = 0.0, zfar = 0.0;
  double depth = 0.0;          // the front card's eye depth
  double fighting = 0.0;       // fraction of its pixels showing the card behind
};

struct BenchReport {
  nlohmann::json meta;  // device, driver, git, settings
  std::vector<BenchRow> rows;
  std::vector<MethodRow> methods;
  std::vector<SkipRow> skips;
  std::vector<DepthRangeRow> depthRange;
  std::vector<DepthTestRow> depthTest;
  std::vector<DefaultsCheck> defaults;
  BenchTolerances tolerances;
  nlohmann::json temporal;  // gblens motion per pair vs compare (bench_temporal.h); null when not run
  nlohmann::json attach;  // the cost of gblens attach (bench_attach.h); null when not run
  nlohmann::json attachApplication;  // the same for another application (--attach-app); null without one
};

nlohmann::json benchJson(const BenchReport& r);
std::string benchCsv(const BenchReport& r);
std::string benchMarkdown(const BenchReport& r);
// The method comparison and the skip savings (bench_methods_report.cpp): JSON, methods.csv, the
// bench.md section, and the targets they measure (appended to the report's targets).
nlohmann::json methodsJson(const BenchReport& r);
std::string methodsCsv(const BenchReport& r);
std::string methodsMarkdown(const BenchReport& r);
nlohmann::json methodTargets(const BenchReport& r);
// Writes the plots with gnuplot (data and scripts next to them). False with a message on failure.
bool writeBenchPlots(const BenchReport& r, const std::string& dir, std::string& error);

}  // namespace gb
