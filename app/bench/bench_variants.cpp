// The default bench sweep and its groups. To add a method (forward, tiled): add
// {"method", {{"method", "forward"}}} rows here, and a group {"method", "lighting_rel_mean", ...}.
#include "app/bench/bench_variants.h"

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

std::vector<BenchVariant> defaultSweep(const RenderOptions& base, const std::vector<int>& lightCounts,
                                       const std::vector<std::string>& sizes) {
  std::vector<BenchVariant> v = {{"default", {}}};
  // Every other value of one option of the option table.
  auto axis = [&](const char* group, const std::string& option, std::vector<std::string> values = {}) {
    if (values.empty()) values = findOption(option)->choices;
    for (const std::string& value : values)
      if (value != getOption(base, option)) v.push_back({group, {{option, value}}});
  };
  axis("normal", "normal_format");
  axis("normal", "oct_encoding");  // precise octahedral encoding: same storage, a lower largest error
  // Where positions come from: hardware depth in each format, or a stored position.
  for (BenchVariant d : std::vector<BenchVariant>{
           {"depth", {{"eye_depth", "off"}}},
           {"depth", {{"eye_depth", "off"}, {"reversed_z", "on"}}},
           {"depth", {{"eye_depth", "off"}, {"depth_format", "d24s8"}}},
           {"depth", {{"position", "rgba16f"}}},
           {"depth", {{"position", "rgba32f"}}},
           {"depth", {{"position", "rgba16f"}, {"position_space", "camera"}}},
           {"depth", {{"position", "rgba32f"}, {"position_space", "camera"}}}})
    v.push_back(d);
  // Light accumulation, path and culling: the same shading with other storage or work.
  axis("accumulation", "accum_format");
  axis("accumulation", "path");
  axis("accumulation", "stencil_culling");
  axis("accumulation", "stencil_mask");
  // Shadow map format, size and bias (bias: none, and four times the defaults).
  axis("shadow", "shadow_format");
  axis("shadow", "shadow_map_size", {"1024", "2048", "4096"});
  v.push_back({"shadow", {{"shadow_bias_constant", "0"}, {"shadow_bias_slope", "0"}}});
  v.push_back({"shadow", {{"shadow_bias_constant", "8"}, {"shadow_bias_slope", "10"}}});
  for (int n : lightCounts) v.push_back({"lights", {{"lights", std::to_string(n)}}});
  for (const std::string& s : sizes) v.push_back({"size", {{"size", s}}});
  return v;
}

}  // namespace gb
