// Bench results: one row per (scene, variant) with timings and error figures; the Pareto
// frontier of time vs error per quality group; whether the defaults are dominated; and the
// files: bench.json, bench.csv, bench.md, time_vs_error.png, time_vs_lights.png, depth_range.png.
#pragma once
#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <vector>

#include "renderer/options.h"

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
// is no worse in frame time (within timeTolerance) and in every error figure (within
// errorTolerance, or an absolute floor), and better in at least one beyond them.
struct DefaultsCheck {
  std::string scene;
  bool onFrontier = true;
  std::vector<std::string> dominatedBy;
};
struct BenchTolerances {
  double time = 0.05;   // 5%: timings on a shared machine are noisy
  double error = 0.05;  // 5%
};
void markFrontiers(std::vector<BenchRow>& rows);
std::vector<DefaultsCheck> checkDefaults(const std::vector<BenchRow>& rows, const BenchTolerances& tol);

struct BenchReport {
  nlohmann::json meta;  // device, driver, git, settings
  std::vector<BenchRow> rows;
  std::vector<DepthRangeRow> depthRange;
  std::vector<DefaultsCheck> defaults;
  BenchTolerances tolerances;
};

nlohmann::json benchJson(const BenchReport& r);
std::string benchCsv(const BenchReport& r);
std::string benchMarkdown(const BenchReport& r);
// Writes the plots with gnuplot (data and scripts next to them). False with a message on failure.
bool writeBenchPlots(const BenchReport& r, const std::string& dir, std::string& error);

}  // namespace gb
