// The whole bench run: the method comparison on builtin:temple, then the variant sweep on each
// scene (per variant: warm-up, timed frames, one frame measured against the reference), the
// interleaved A/B checks of variants whose errors tie the defaults', the defaults once more, and
// the depth-range study, all within one time budget. Writes bench.json/csv/md and the plots.
#pragma once
#include <string>
#include <vector>

#include "app/bench/bench_run.h"
#include "app/bench/bench_variants.h"

namespace gb {

struct BenchPlan {
  BenchSettings settings;      // gblens bench's own flags
  RenderOptions defaults;      // the common options: the base of every variant
  int frames = 20;             // timed frames per variant at most (--frames)
  std::vector<int> lightCounts;
  std::vector<std::string> sizes;
  std::vector<BenchVariant> variants;  // after --only
  bool runMethods = true;
  bool runAttach = true;
  bool runTemporal = true;  // gblens motion per pair vs compare (bench_temporal.h)
};

// Fills lightCounts, sizes, the method lists and the variants from the settings' text lists and
// --only; false with a one-line message naming the flag.
bool planBench(BenchPlan& plan, std::string& error);

BenchReport runBench(GpuContext& ctx, const BenchPlan& plan);

// bench.json, bench.csv, bench.md, methods.csv and the plots in `dir` (each written atomically).
bool writeBenchFiles(const BenchReport& report, const std::string& dir, std::string& error);

}  // namespace gb
