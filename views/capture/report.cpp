// JSON reports of frames and options, with one name per thing (the CLI flag names).
#include "views/capture/report.h"

#include "renderer/core/statistics.h"

#include <algorithm>
#include <cstdio>

namespace gb {

nlohmann::json optionsJson(const RenderOptions& o) {
  // Every option-table entry under its one name; numbers as JSON numbers. coverage and
  // keep_gbuffer are not user options but say which targets a capture could hold.
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
  j["coverage"] = o.coverage;
  j["keep_gbuffer"] = o.keepGBuffer;
  return j;
}

// Reads one boolean member; a missing member keeps the default.
static bool flag(const nlohmann::json& j, const char* key, bool& out, std::string& error) {
  auto it = j.find(key);
  if (it == j.end()) return true;
  if (!it->is_boolean()) {
    error = std::string("options.") + key + ": unexpected value " + it->dump();
    return false;
  }
  out = it->get<bool>();
  return true;
}

bool optionsFromJson(const nlohmann::json& j, RenderOptions& o, std::string& error) {
  if (!j.is_object()) {
    error = "options: not an object";
    return false;
  }
  // Members left out keep their defaults (manifests of older versions); an unknown value or a
  // member of the wrong type is an error naming it. Older manifests wrote on/off options as
  // booleans and the shadow bias as one object: both are still read.
  auto set = [&](const std::string& name, const nlohmann::json& v) {
    std::string text;
    if (v.is_string())
      text = v.get<std::string>();
    else if (v.is_boolean())
      text = v.get<bool>() ? "on" : "off";
    else if (v.is_number_integer() || v.is_number_unsigned())
      text = std::to_string(v.get<long long>());
    else if (v.is_number_float()) {
      char buf[64];
      std::snprintf(buf, sizeof buf, "%.17g", v.get<double>());
      text = buf;
    } else {
      error = "options." + name + ": unexpected value " + v.dump();
      return false;
    }
    std::string why;
    if (!setOption(o, name, text, why)) {
      error = "options." + name + ": unknown value " + v.dump();
      return false;
    }
    return true;
  };
  for (const OptionInfo& info : optionTable())
    if (auto it = j.find(info.name); it != j.end() && !set(info.name, *it)) return false;
  if (auto bias = j.find("shadow_bias"); bias != j.end()) {
    if (!bias->is_object()) {
      error = "options.shadow_bias: unexpected value " + bias->dump();
      return false;
    }
    for (const char* part : {"constant", "slope", "clamp"})
      if (auto it = bias->find(part); it != bias->end() && !set(std::string("shadow_bias_") + part, *it)) return false;
  }
  return flag(j, "coverage", o.coverage, error) && flag(j, "keep_gbuffer", o.keepGBuffer, error);
}

nlohmann::json statsJson(const std::vector<FrameStats>& frames, const StatsSource& source, const RenderOptions& o,
                         const FrameStats* counted) {
  nlohmann::json j;
  if (frames.empty()) return j;
  const FrameStats& last = frames.back();
  std::vector<double> frameMs, gpuMs, cpuMs, recordMs;
  for (const FrameStats& f : frames) {
    frameMs.push_back(f.frameMs);
    cpuMs.push_back(f.cpuMs);
    recordMs.push_back(f.recordMs);
    gpuMs.push_back(f.gpuMs);
  }
  j["device"] = source.device;
  j["driver"] = source.driver;
  j["scene"] = source.scene;
  j["options"] = optionsJson(o);
  j["frames"] = frames.size();
  j["frame_ms"] = median(frameMs);
  j["frame_ms_min"] = *std::min_element(frameMs.begin(), frameMs.end());
  j["frame_ms_max"] = *std::max_element(frameMs.begin(), frameMs.end());
  j["gpu_ms"] = median(gpuMs);
  j["cpu_ms"] = median(cpuMs);
  j["record_ms"] = median(recordMs);
  j["method"] = {{"ran", last.method}, {"why", last.methodReason}};
  j["light_setup"] = {{"ran", last.lightSetup}, {"why", last.lightSetupReason}};
  j["render_pass_groups"] = {{"compiled", last.groupsCompiled}, {"reused", last.groupsReused}};
  nlohmann::json passes = nlohmann::json::array();
  for (size_t i = 0; i < last.passes.size(); ++i) {
    // A pass is reported as the last frame ran it: a skipped pass costs 0 ms there even if an
    // earlier frame ran it (the shadow map is rendered once, then reused); runs counts those.
    std::vector<double> ms;
    for (const FrameStats& f : frames)
      if (i < f.passes.size() && f.passes[i].name == last.passes[i].name && !f.passes[i].skipped) ms.push_back(f.passes[i].ms);
    const bool skipped = last.passes[i].skipped;
    nlohmann::json p = {{"name", last.passes[i].name}, {"ms", skipped ? 0.0 : median(ms)}, {"skipped", skipped},
                        {"runs", ms.size()}};
    if (skipped) p["reason"] = last.passes[i].reason;
    passes.push_back(p);
  }
  j["passes"] = passes;
  j["lights"] = {{"total", last.lights},
                 {"visible", last.lightsVisible},
                 {"near_plane", last.lightsInside},
                 {"stencil_layers", last.stencilLayers},
                 {"culled", last.lightsCulled},
                 {"culled_frustum", last.lightsCulledFrustum},
                 {"culled_empty", last.lightsCulledEmpty},
                 {"culled_subpixel", last.lightsCulledSubpixel},
                 {"subpixel_rule",
                  "skipped when the sphere's exact screen rectangle (+1/1000 px) holds no pixel centre: no shaded "
                  "point can be inside it"}};
  if (last.skyPixels >= 0) j["sky_pixels"] = last.skyPixels;
  if (last.clusters.valid)
    j["clusters"] = {{"occupied", last.clusters.clusters},
                     {"list_entries", last.clusters.listEntries},
                     {"lists_overflowed", last.clusters.listOverflows},
                     {"tiles_without_room", last.clusters.tilesWithoutRoom}};
  const CullingStats& culling = counted ? counted->culling : last.culling;
  if (culling.valid) {
    j["culling"] = {{"invocations", culling.invocations},
                    {"ideal_pairs", culling.idealPairs},
                    {"work_over_ideal", culling.workOverIdeal},
                    {"pipeline_invocations", culling.pipelineInvocations}};
    if (counted) j["culling"]["counted_on"] = "one more frame with coverage on, after the timed frames";
  }
  return j;
}

}  // namespace gb
