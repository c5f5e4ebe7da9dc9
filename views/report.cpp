// JSON reports of frames and options, with one name per thing (the CLI flag names).
#include "views/report.h"

#include <algorithm>

namespace gb {

static double medianOf(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

nlohmann::json optionsJson(const RenderOptions& o) {
  // Every option-table entry under its one name; numbers as JSON numbers.
  nlohmann::json j = nlohmann::json::object();
  for (const OptionInfo& info : optionTable()) {
    std::string v = getOption(o, info.name);
    if (info.kind == OptionKind::Integer)
      j[info.name] = std::stoll(v);
    else if (info.kind == OptionKind::Real)
      j[info.name] = std::stod(v);
    else
      j[info.name] = v;
  }
  return j;
}

nlohmann::json statsJson(const std::vector<FrameStats>& frames, const GpuContext& ctx, const RenderOptions& o,
                         const Scene& scene) {
  nlohmann::json j;
  if (frames.empty()) return j;
  const FrameStats& last = frames.back();
  std::vector<double> frameMs, gpuMs;
  for (const FrameStats& f : frames) {
    frameMs.push_back(f.frameMs);
    gpuMs.push_back(f.gpuMs);
  }
  j["device"] = ctx.deviceName;
  j["driver"] = ctx.driverName;
  j["scene"] = scene.source;
  j["options"] = optionsJson(o);
  j["frames"] = frames.size();
  j["frame_ms"] = medianOf(frameMs);
  j["frame_ms_min"] = *std::min_element(frameMs.begin(), frameMs.end());
  j["frame_ms_max"] = *std::max_element(frameMs.begin(), frameMs.end());
  j["gpu_ms"] = medianOf(gpuMs);
  nlohmann::json passes = nlohmann::json::array();
  for (size_t i = 0; i < last.passes.size(); ++i) {
    std::vector<double> ms;
    for (const FrameStats& f : frames)
      if (i < f.passes.size() && f.passes[i].name == last.passes[i].name && !f.passes[i].skipped) ms.push_back(f.passes[i].ms);
    nlohmann::json p = {{"name", last.passes[i].name}, {"ms", medianOf(ms)}, {"skipped", last.passes[i].skipped}};
    if (last.passes[i].skipped) p["reason"] = last.passes[i].reason;
    passes.push_back(p);
  }
  j["passes"] = passes;
  j["lights"] = {{"total", last.lights},
                 {"visible", last.lightsVisible},
                 {"near_plane", last.lightsInside},
                 {"culled", last.lightsCulled}};
  if (last.culling.valid)
    j["culling"] = {{"invocations", last.culling.invocations},
                    {"ideal_pairs", last.culling.idealPairs},
                    {"work_over_ideal", last.culling.workOverIdeal},
                    {"pipeline_invocations", last.culling.pipelineInvocations}};
  return j;
}

}  // namespace gb
