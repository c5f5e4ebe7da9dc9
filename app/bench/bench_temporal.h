// The cost of `gblens motion` in make bench (issue 38): time per pair of frames beside compare's
// time for the same pair, on a sequence of gblens's own renderer (bench_temporal.cpp).
#pragma once
#include <nlohmann/json.hpp>

#include <string>

#include "renderer/core/options.h"

namespace gb {

struct GpuContext;

struct TemporalBenchSettings {
  std::string size = "1920x1080";
  int frames = 60;
};

nlohmann::json temporalStudy(GpuContext& ctx, const RenderOptions& base, const TemporalBenchSettings& s);
// The bench.md section ("" when the study did not run).
std::string temporalMarkdown(const nlohmann::json& study);

}  // namespace gb
