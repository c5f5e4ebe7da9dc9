// JSON reports of frames and options, with one name per thing (the CLI flag names).
#include "views/capture/report.h"

#include <algorithm>
#include <cstdio>

#include "renderer/core/statistics.h"

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

static nlohmann::json passJson(const PassStat& p, double ms) {
  nlohmann::json j = {{"name", p.name}, {"ms", p.skipped ? 0.0 : ms}, {"skipped", p.skipped}};
  if (p.skipped) j["reason"] = p.reason;
  return j;
}

static nlohmann::json cullingJson(const CullingStats& c) {
  if (!c.valid) return {{"valid", false}, {"reason", "needs coverage on and the coverage_masked and depth targets"}};
  return {{"valid", true},
          {"invocations", c.invocations},
          {"ideal_pairs", c.idealPairs},
          {"work_over_ideal", c.workOverIdeal},
          {"pipeline_invocations", c.pipelineInvocations}};
}

nlohmann::json frameStatsJson(const FrameStats& st) {
  nlohmann::json passes = nlohmann::json::array();
  for (const PassStat& p : st.passes) passes.push_back(passJson(p, p.ms));
  nlohmann::json j = {{"frame_ms", st.frameMs},
                      {"gpu_ms", st.gpuMs},
                      {"cpu_ms", st.cpuMs},
                      {"record_ms", st.recordMs},
                      {"render_pass_groups", {{"compiled", st.groupsCompiled}, {"reused", st.groupsReused}}},
                      {"method", {{"ran", st.method}, {"why", st.methodReason}}},
                      {"gbuffer", {{"ran", st.gbuffer}, {"why", st.gbufferReason}}},
                      {"light_setup", {{"ran", st.lightSetup}, {"why", st.lightSetupReason}}},
                      {"overlap", {{"ran", st.overlap}, {"why", st.overlapReason}}},
                      {"passes", passes}};
  if (!st.clusterAssign.empty()) j["cluster_assign"] = {{"ran", st.clusterAssign}, {"why", st.clusterAssignReason}};
  j["lights"] = {{"total", st.lights},
                 {"visible", st.lightsVisible},
                 {"near_plane", st.lightsInside},
                 {"stencil_layers", st.stencilLayers},
                 {"culled", st.lightsCulled},
                 {"culled_frustum", st.lightsCulledFrustum},
                 {"culled_empty", st.lightsCulledEmpty},
                 {"culled_subpixel", st.lightsCulledSubpixel},
                 {"subpixel_rule",
                  "skipped when the sphere's exact screen rectangle (+1/1000 px) holds no pixel centre: no shaded "
                  "point can be inside it"}};
  if (st.skyPixels >= 0) j["sky_pixels"] = st.skyPixels;
  if (st.clusters.valid)
    j["clusters"] = {{"occupied", st.clusters.clusters},
                     {"list_entries", st.clusters.listEntries},
                     {"lists_overflowed", st.clusters.listOverflows},
                     {"tiles_without_room", st.clusters.tilesWithoutRoom}};
  j["culling"] = cullingJson(st.culling);
  return j;
}

nlohmann::json statsJson(const std::vector<FrameStats>& frames, const StatsSource& source, const RenderOptions& o,
                         const FrameStats* counted, const FrameBurst* burst) {
  if (frames.empty()) return nlohmann::json();
  const FrameStats& last = frames.back();
  nlohmann::json j = frameStatsJson(last);
  // docs/json.md: version 2 added "gbuffer" (what filled the G-buffer and why), 3 "overlap"; version
  // 1 was unversioned.
  j["format"] = "gblens-frame-stats";
  j["version"] = 3;
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
  if (burst) {
    j["frame_ms"] = burst->msPerFrame;
    j["frames_in_flight"] = burst->inFlight;
    j["frame_intervals_ms"] = burst->intervalMs;
    j["frame_ms_measured"] = "throughput of frames in flight: wall time per frame of " +
                             std::to_string(burst->frames.size()) +
                             " timed after one waited for (a frame read back after them is waited for apart); "
                             "gpu_ms, cpu_ms and passes: medians over every frame";
  } else {
    j["frame_ms"] = median(frameMs);
    j["frame_ms_min"] = *std::min_element(frameMs.begin(), frameMs.end());
    j["frame_ms_max"] = *std::max_element(frameMs.begin(), frameMs.end());
    j["frame_ms_measured"] = "median over the frames, each recorded, submitted and waited for";
  }
  j["gpu_ms"] = median(gpuMs);
  j["cpu_ms"] = median(cpuMs);
  j["record_ms"] = median(recordMs);
  nlohmann::json passes = nlohmann::json::array();
  for (size_t i = 0; i < last.passes.size(); ++i) {
    // A pass is reported as the last frame ran it: a skipped pass costs 0 ms there even if an
    // earlier frame ran it (the shadow map is rendered once, then reused); runs counts those.
    std::vector<double> ms;
    for (const FrameStats& f : frames)
      if (i < f.passes.size() && f.passes[i].name == last.passes[i].name && !f.passes[i].skipped) ms.push_back(f.passes[i].ms);
    nlohmann::json p = passJson(last.passes[i], last.passes[i].skipped ? 0.0 : median(ms));
    p["runs"] = ms.size();
    passes.push_back(p);
  }
  j["passes"] = passes;
  if (counted) {
    j["culling"] = cullingJson(counted->culling);
    if (counted->culling.valid) j["culling"]["counted_on"] = "one more frame with coverage on, after the timed frames";
  }
  return j;
}

}  // namespace gb
