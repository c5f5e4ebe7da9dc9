// Writing captures: EXRs, final.png, lights.json, then manifest.json with every file's size and
// SHA-256, all in a temporary directory that is renamed into place only when complete.
#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "renderer/core/layout_json.h"
#include "renderer/core/sha256.h"
#include "renderer/core/version.h"
#include "views/capture/capture.h"
#include "views/capture/exr.h"
#include "views/capture/image_io.h"
#include "views/capture/manifest_check.h"
#include "views/capture/report.h"

namespace gb {

namespace fs = std::filesystem;

std::vector<Target> availableTargets(const RenderOptions& o, bool sceneHasSun) {
  std::vector<Target> out;
  for (size_t i = 0; i < kTargetCount; ++i)
    if (targetAbsence(Target(i), o, sceneHasSun) == Absent::No) out.push_back(Target(i));
  return out;
}

static nlohmann::json vec3Json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

// Lights exactly as uploaded (float values print and parse back bit-exactly through double).
static nlohmann::json lightsJson(const FrameSnapshot& f) {
  nlohmann::json lights = nlohmann::json::array();
  std::vector<std::string> cls(f.eyeLights.size(), "culled");
  for (size_t k = 0; k < f.visibleLights.size(); ++k) cls[f.visibleLights[k]] = k < f.stencilCount ? "stencil" : "near_plane";
  for (size_t i = 0; i < f.eyeLights.size(); ++i) {
    const gpu::PointLight& l = f.eyeLights[i];
    glm::dvec3 eye(l.eyePositionRadius);
    nlohmann::json j = {{"index", i},
                        {"class", cls[i]},
                        {"eye_position", vec3Json(eye)},
                        {"radius", double(l.eyePositionRadius.w)},
                        {"color", vec3Json(glm::dvec3(l.color))},
                        {"world_position", vec3Json(glm::dvec3(f.camera.worldFromEye * glm::dvec4(eye, 1.0)))}};
    if (i < f.lightDescs.size()) {
      const PointLightDesc& d = f.lightDescs[i];
      j["desc"] = {{"center", vec3Json(d.center)}, {"orbit_radius", d.orbitRadius}, {"orbit_speed", d.orbitSpeed},
                   {"phase", d.phase},  {"bob", d.bob}, {"radius", d.radius},
                   {"color", vec3Json(glm::dvec3(d.color))}, {"intensity", d.intensity}};
    }
    lights.push_back(j);
  }
  nlohmann::json j = {{"format", "gblens-lights"}, {"time", f.options.time}, {"visible", f.visibleLights},
                      {"stencil_count", f.stencilCount}, {"layer_starts", f.layerStarts}, {"lights", lights}};
  if (auto why = f.unknown.find("lights"); why != f.unknown.end()) j["unknown"] = why->second, j.erase("time");
  return j;
}

static std::string utcNow() {
  std::time_t t = std::chrono::system_clock::to_time_t(std::chrono::system_clock::now());
  std::tm tm{};
  gmtime_r(&t, &tm);
  char buf[32];
  std::strftime(buf, sizeof(buf), "%Y-%m-%dT%H:%M:%SZ", &tm);
  return buf;
}

static bool writeText(const fs::path& path, const std::string& text, std::string& error) {
  std::ofstream out(path, std::ios::binary);
  out << text;
  out.close();
  if (!out) error = path.string() + ": cannot write";
  return bool(out);
}

// Adds `file` (in `tmp`) to the manifest's file list with its size and digest.
static bool record(const fs::path& tmp, const std::string& file, nlohmann::json& files, std::string& error) {
  std::string hex;
  if (!sha256File((tmp / file).string(), hex, error)) return false;
  files[file] = {{"bytes", fs::file_size(tmp / file)}, {"sha256", hex}};
  return true;
}

// What the frame's source does not say is left out with why ("unknown"), never written as a
// default: FrameSnapshot::unknown's fields, the options nobody stated, and the device, driver and
// scene digest no one recorded.
static void leaveOutUnknown(const FrameSnapshot& f, nlohmann::json& m) {
  nlohmann::json unknown = nlohmann::json::object();
  for (const auto& [field, why] : f.unknown) unknown[field] = why;
  for (const char* key : {"device", "driver"})
    if (m[key] == "") m.erase(key), unknown[key] = "not recorded";
  if (m["scene"]["content_sha256"] == "") m["scene"].erase("content_sha256"), unknown["scene.content_sha256"] = "not recorded";
  for (const auto& [field, why] : f.unknown) {
    const size_t dot = field.find('.');
    if (field == "options" && m.contains("options")) {
      nlohmann::json stated = nlohmann::json::object();
      for (const std::string& name : f.statedOptions)
        if (m["options"].contains(name)) stated[name] = m["options"][name];
      m["options"] = stated;
    } else if (field == "lights") {  // lights.json stays (empty lists, saying why): the summary's figures go
      for (const char* key : {"count", "visible", "stencil_class", "culled", "sha256"}) m["lights"].erase(key);
    } else if (dot == std::string::npos) {
      m.erase(field);
    } else if (m.contains(field.substr(0, dot))) {
      m[field.substr(0, dot)].erase(field.substr(dot + 1));
    }
  }
  if (!unknown.empty()) m["unknown"] = unknown;
}

static bool writeContents(const fs::path& tmp, const FrameSnapshot& f, const CaptureMeta& meta, std::string& error) {
  nlohmann::json files = nlohmann::json::object(), targets = nlohmann::json::array();
  nlohmann::json skipped = nlohmann::json::array();
  for (size_t i = 0; i < f.images.size(); ++i) {
    const std::string& targetName = f.layout.targets[i].name;
    const TargetImage& ti = f.images[i];
    if (!ti.present()) {
      skipped.push_back({{"name", targetName},
                         {"reason", absentText(f.absences[i] == Absent::No ? Absent::NotCaptured : f.absences[i])}});
      continue;
    }
    if (!ti.whole()) {
      error = targetName + ": a region read-back cannot be captured (whole targets only)";
      return false;
    }
    std::string file = targetName + ".exr";
    // A multisampled target's file is sample 0 whichever sample the frame shows.
    if (!writeExr((tmp / file).string(), ti.samples.empty() ? ti.image : ti.samples[0], error) || !record(tmp, file, files, error)) return false;
    nlohmann::json exr = nlohmann::json::array();
    for (const ExrChannel& c : exrChannels(ti.image)) exr.push_back({{"name", c.name}, {"type", c.type}});
    targets.push_back({{"name", targetName}, {"file", file}, {"width", ti.image.width},
                       {"height", ti.image.height}, {"type", name(ti.image.type)},
                       {"encoding", name(ti.image.encoding)}, {"channels", ti.image.channels},
                       {"exr_channels", exr}});
    if (!ti.samples.empty()) {  // a multisampled target: sample 0 is `file`, sample k NAME.sK.exr
      nlohmann::json sampleFiles = {file};
      for (size_t k = 1; k < ti.samples.size(); ++k) {
        const std::string sf = targetName + ".s" + std::to_string(k) + ".exr";
        if (!writeExr((tmp / sf).string(), ti.samples[k], error) || !record(tmp, sf, files, error)) return false;
        sampleFiles.push_back(sf);
      }
      targets.back()["sample_files"] = sampleFiles;
    }
    if (int(i) == f.indexOf(Target::Final)) {  // the tone-mapped sRGB bytes, exactly
      Rgba8Image png{ti.image.width, ti.image.height, ti.image.data};
      if (ti.image.type != PixelType::U8 || ti.image.channelCount() != 4) {
        error = "final: expected 8-bit RGBA";
        return false;
      }
      if (!writePng((tmp / "final.png").string(), png, error) || !record(tmp, "final.png", files, error)) return false;
    }
  }
  if (!writeText(tmp / "lights.json", lightsJson(f).dump(1) + "\n", error) ||
      !record(tmp, "lights.json", files, error))
    return false;

  uint32_t culled = uint32_t(f.eyeLights.size() - f.visibleLights.size());
  nlohmann::json m = {
      {"format", "gblens-capture"},
      {"format_version", std::any_of(f.images.begin(), f.images.end(), [](const TargetImage& t) { return !t.samples.empty(); })
                             ? kCaptureFormatVersion : 1},
      {"gblens", {{"version", GBLENS_VERSION}, {"git", gitHash()}}},
      {"created_utc", utcNow()},
      {"command", meta.commandLine},
      {"device", meta.device},
      {"driver", meta.driver},
      {"scene", {{"source", meta.scene}, {"content_sha256", meta.sceneSha256}}},
      {"size", {f.camera.width, f.camera.height}},
      {"time", f.options.time},
      {"options", optionsJson(f.options)},
      {"layout", layoutJson(f.layout)},
      {"camera", cameraJson(f.camera)},
      {"lightClipFromWorld", matrixJson(f.lightClipFromWorld)},
      {"sun", {{"enabled", f.sun.enabled}, {"to_sun", vec3Json(f.sun.toSun)},
               {"color", vec3Json(glm::dvec3(f.sun.color))}, {"eye_direction", vec3Json(f.sunEyeDirection())}}},
      {"sky", {{"zenith", vec3Json(glm::dvec3(f.sky.zenith))}, {"horizon", vec3Json(glm::dvec3(f.sky.horizon))},
               {"ground", vec3Json(glm::dvec3(f.sky.ground))}, {"ambient", vec3Json(glm::dvec3(f.sky.ambient))}}},
      {"lights", {{"file", "lights.json"}, {"sha256", files["lights.json"]["sha256"]},
                  {"count", f.eyeLights.size()}, {"visible", f.visibleLights.size()},
                  {"stencil_class", f.stencilCount}, {"culled", culled}}},
      {"stats", frameStatsJson(meta.stats)},
      {"targets", targets},
      {"skipped", skipped},
      {"files", files}};
  // gblens's render options describe gblens's frames; another renderer's G-buffer has none.
  if (!gblensLayout(f.layout)) m.erase("options");
  if (!meta.source.is_null()) m["source"] = meta.source;
  leaveOutUnknown(f, m);
  // Written last: a directory without it is never a capture.
  return writeText(tmp / "manifest.json", m.dump(2) + "\n", error);
}

bool writeCapture(const std::string& dirText, const FrameSnapshot& f, const CaptureMeta& meta, std::string& error) {
  return replaceDirectory(dirText, "manifest.json", "capture", [&](const std::string& tmp, std::string& e) {
    // The capture as the readers will read it, before it is moved into place: what they would refuse
    // (a value JSON cannot hold, written as null; a name OpenEXR would merge) is not written at all.
    if (writeContents(tmp, f, meta, e) && checkWrittenManifest(tmp, e)) return true;
    if (e.rfind("manifest.json", 0) == 0 || e.rfind("lights.json", 0) == 0)
      e = dirText + ": not written, it would not read back: " + e;
    return false;
  }, error);
}

}  // namespace gb
