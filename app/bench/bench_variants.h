// The bench sweep as a table of named variants: each one sets options of the option table
// (renderer/options.h) on top of the base options, so a variant's name is its settings
// ("normal_format=oct-rg16", "eye_depth=off+reversed_z=on"): one name in flags, JSON and bench.
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "app/bench/bench_report.h"
#include "renderer/core/options.h"

namespace gb {

struct BenchVariant {
  std::string group;  // a quality axis (Pareto panel) or a workload sweep, see benchGroups()
  std::vector<std::pair<std::string, std::string>> set;  // option name -> value
  std::string name() const;   // "default" or "a=b+c=d"
  std::string label() const;  // short plot label: the values ("oct-rg16", "off+on")
};

// The default sweep: the defaults, then one axis at a time around them (every other value of
// normal_format, accum_format, path, culling, shadow format/size; fixed depth/position and bias
// combinations), then light counts and sizes. Values equal to `base`'s are left out.
std::vector<BenchVariant> defaultSweep(const RenderOptions& base, const std::vector<int>& lightCounts,
                                       const std::vector<std::string>& sizes);

}  // namespace gb
