// JSON reports of frames and options, with one name per thing (the CLI flag names).
#include "views/report.h"

#include <algorithm>
#include <cstdio>

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
          {"sky", o.sky},
          {"exposure", o.exposure},
          {"coverage", o.coverage},
          {"keep_gbuffer", o.keepGBuffer}};
}

// Reads one member; a missing member keeps the default (manifests of older versions), a
// member of the wrong type or an unknown name is an error.
template <class T>
static bool member(const nlohmann::json& j, const char* key, T& out, std::string& error) {
  auto it = j.find(key);
  if (it == j.end()) return true;
  try {
    out = it->get<T>();
  } catch (const nlohmann::json::exception&) {
    error = std::string("options.") + key + ": unexpected value " + it->dump();
    return false;
  }
  return true;
}
template <class E>
static bool named(const nlohmann::json& j, const char* key, E& out, std::string& error) {
  std::string text;
  if (!j.contains(key)) return true;
  if (!member(j, key, text, error)) return false;
  if (!parse(text, out)) {
    error = std::string("options.") + key + ": unknown value \"" + text + "\"";
    return false;
  }
  return true;
}
static bool onOff(const nlohmann::json& j, const char* key, bool& out, std::string& error) {
  std::string text = out ? "on" : "off";
  if (!member(j, key, text, error)) return false;
  if (text != "on" && text != "off") {
    error = std::string("options.") + key + ": expected on or off, got \"" + text + "\"";
    return false;
  }
  out = text == "on";
  return true;
}

bool optionsFromJson(const nlohmann::json& j, RenderOptions& o, std::string& error) {
  if (!j.is_object()) {
    error = "options: not an object";
    return false;
  }
  std::string size = std::to_string(o.width) + "x" + std::to_string(o.height);
  if (!member(j, "size", size, error)) return false;
  unsigned w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(size.c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || x != 'x' || !w || !h) {
    error = "options.size: expected WxH, got \"" + size + "\"";
    return false;
  }
  o.width = w;
  o.height = h;
  nlohmann::json bias = j.value("shadow_bias", nlohmann::json::object());
  return member(j, "time", o.time, error) && member(j, "lights", o.lights, error) &&
         member(j, "camera", o.camera, error) && named(j, "path", o.path, error) &&
         named(j, "method", o.method, error) && onOff(j, "eye_depth", o.eyeDepth, error) &&
         onOff(j, "stencil_culling", o.stencilCulling, error) && named(j, "stencil_mask", o.stencilMask, error) &&
         member(j, "reversed_z", o.reversedZ, error) && named(j, "normal_format", o.normalFormat, error) &&
         named(j, "depth_format", o.depthFormat, error) && named(j, "accum_format", o.accumFormat, error) &&
         named(j, "shadow_format", o.shadowFormat, error) && member(j, "shadow_map_size", o.shadowMapSize, error) &&
         member(bias, "constant", o.shadowBiasConstant, error) && member(bias, "slope", o.shadowBiasSlope, error) &&
         member(bias, "clamp", o.shadowBiasClamp, error) && member(j, "fairies", o.fairies, error) &&
         member(j, "sky", o.sky, error) && member(j, "exposure", o.exposure, error) &&
         member(j, "coverage", o.coverage, error) && member(j, "keep_gbuffer", o.keepGBuffer, error);
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
