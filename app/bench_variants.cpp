// The default bench sweep and its groups. To add a method (forward, tiled): add
// {"method", {{"method", "forward"}}} rows here, and a group {"method", "lighting_rel_mean", ...}.
#include "app/bench_variants.h"

namespace gb {

std::string BenchVariant::name() const {
  if (set.empty()) return "default";
  std::string n;
  for (auto& [k, v] : set) n += (n.empty() ? "" : "+") + k + "=" + v;
  return n;
}

std::string BenchVariant::label() const {
  if (set.empty()) return "default";
  std::string n;
  for (auto& [k, v] : set) n += (n.empty() ? "" : "+") + v;
  return n;
}

std::vector<BenchVariant> defaultSweep(const std::vector<int>& lightCounts, const std::vector<std::string>& sizes) {
  std::vector<BenchVariant> v = {
      {"default", {}},
      // Normal storage (normal_shadow).
      {"normal", {{"normal_format", "rgba8-snorm"}}},
      {"normal", {{"normal_format", "oct-rg16"}}},
      {"normal", {{"normal_format", "rgb10a2"}}},
      // Where positions come from: hardware depth in each format, or a stored position.
      {"depth", {{"eye_depth", "off"}}},
      {"depth", {{"eye_depth", "off"}, {"reversed_z", "on"}}},
      {"depth", {{"eye_depth", "off"}, {"depth_format", "d24s8"}}},
      {"depth", {{"position", "rgba16f"}}},
      {"depth", {{"position", "rgba32f"}}},
      {"depth", {{"position", "rgba16f"}, {"position_space", "camera"}}},
      {"depth", {{"position", "rgba32f"}, {"position_space", "camera"}}},
      // Light accumulation, path and culling: same shading, different storage or work.
      {"accumulation", {{"accum_format", "rgba32f"}}},
      {"accumulation", {{"accum_format", "rgba8"}}},
      {"accumulation", {{"path", "single-pass"}}},
      {"accumulation", {{"stencil_culling", "off"}}},
      {"accumulation", {{"stencil_mask", "shared"}}},
      // Shadow map format, size and bias (defaults: d32f, 2048, constant 2 / slope 2.5).
      {"shadow", {{"shadow_format", "d16"}}},
      {"shadow", {{"shadow_map_size", "1024"}}},
      {"shadow", {{"shadow_map_size", "4096"}}},
      {"shadow", {{"shadow_bias_constant", "0"}, {"shadow_bias_slope", "0"}}},
      {"shadow", {{"shadow_bias_constant", "8"}, {"shadow_bias_slope", "8"}}},
  };
  for (int n : lightCounts) v.push_back({"lights", {{"lights", std::to_string(n)}}});
  for (const std::string& s : sizes) v.push_back({"size", {{"size", s}}});
  return v;
}

}  // namespace gb
