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
  return {{"size", std::to_string(o.width) + "x" + std::to_string(o.height)},
          {"time", o.time},
          {"lights", o.lights},
          {"camera", o.camera},
          {"path", name(o.path)},
          {"method", name(o.method)},
          {"eye_depth", o.eyeDepth ? "on" : "off"},
          {"stencil_culling", o.stencilCulling ? "on" : "off"},
          {"stencil_mask", name(o.stencilMask)},
          {"reversed_z", o.reversedZ},
          {"normal_format", name(o.normalFormat)},
          {"depth_format", name(o.depthFormat)},
          {"accum_format", name(o.accumFormat)},
          {"shadow_format", name(o.shadowFormat)},
          {"shadow_map_size", o.shadowMapSize},
          {"shadow_bias", {{"constant", o.shadowBiasConstant}, {"slope", o.shadowBiasSlope}, {"clamp", o.shadowBiasClamp}}},
          {"fairies", o.fairies},
          {"exposure", o.exposure}};
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
    // A pass is reported as the last frame ran it: a skipped pass costs 0 ms there even if an
    // earlier frame ran it (the shadow map is rendered once, then reused); runs counts those.
    std::vector<double> ms;
    for (const FrameStats& f : frames)
      if (i < f.passes.size() && f.passes[i].name == last.passes[i].name && !f.passes[i].skipped) ms.push_back(f.passes[i].ms);
    const bool skipped = last.passes[i].skipped;
    nlohmann::json p = {{"name", last.passes[i].name}, {"ms", skipped ? 0.0 : medianOf(ms)}, {"skipped", skipped},
                        {"runs", ms.size()}};
    if (skipped) p["reason"] = last.passes[i].reason;
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
