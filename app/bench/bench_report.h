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
};

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
  // Interleaved A/B against the defaults (frames alternating, two renderers): median of the
  // per-pair ratio variant / defaults. 0: not run. Measured for variants that seem to dominate.
  double abTimeRatio = 0.0;
  double abTimeRatioUpperQuartile = 0.0;  // faster in at least 3 of 4 pairs when below 1
  int abPairs = 0;
};

// Keys of BenchRow::error, in column order, with their meaning.
const std::vector<std::pair<std::string, std::string>>& errorSummaryKeys();

// One depth-range measurement: position error of one source at one far/near ratio.
struct DepthRangeRow {
  double ratio = 0.0, znear = 0.0, zfar = 0.0;
  std::string source;  // "eye_depth", "d32_standard", "d32_reversed", "d24_standard", "rgba32f_world", ...
  double relMax = 0.0, relMean = 0.0;
};

// A quality group's frontier and the defaults check: a variant dominates the defaults when it
// is no worse in frame time and in every error figure, and better in at least one, each beyond
// a relative tolerance and the figure's significance floor (differences below it are not
// meaningful: a fraction of a float ulp, a hundredth of a percent of pixels). Where an
// interleaved A/B ran, its time ratios replace the sweep's medians, and being faster also needs
// the upper quartile below 1 (faster in at least 3 of 4 pairs: noise alone rarely is).
struct DefaultsCheck {
  std::string scene;
  bool onFrontier = true;
  std::vector<std::string> dominatedBy;
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
  int frames = 0;
  Timing frameMs, gpuMs, cpuMs;  // cpuMs: the CPU's part before submission (FrameStats::cpuMs)
  std::string lightSetup;        // where the lights were set up ("cpu", "gpu")
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

struct BenchReport {
  nlohmann::json meta;  // device, driver, git, settings
  std::vector<BenchRow> rows;
  std::vector<MethodRow> methods;
  std::vector<SkipRow> skips;
  std::vector<DepthRangeRow> depthRange;
  std::vector<DefaultsCheck> defaults;
  BenchTolerances tolerances;
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
