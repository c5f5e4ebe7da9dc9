// Writing captures: EXRs, final.png, lights.json, then manifest.json with every file's size and
// SHA-256, all in a temporary directory that is renamed into place only when complete.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <ctime>
#include <filesystem>
#include <fstream>

#include "renderer/version.h"
#include "views/capture.h"
#include "views/exr.h"
#include "views/image_io.h"
#include "views/report.h"
#include "views/sha256.h"

namespace gb {

namespace fs = std::filesystem;

std::vector<Target> availableTargets(const RenderOptions& o, const Scene* scene) {
  std::vector<Target> out;
  for (size_t i = 0; i < kTargetCount; ++i)
    if (targetUnavailable(Target(i), o, scene).empty()) out.push_back(Target(i));
  return out;
}

FrameRequest captureRequest(const std::vector<Target>& targets, const RenderOptions& o) {
  FrameRequest r;
  r.readback = targets;
  auto has = [&](Target t) { return std::find(targets.begin(), targets.end(), t) != targets.end(); };
  r.cullingStats = o.coverage && has(Target::CoverageMasked) && has(Target::Depth);
  return r;
}

static nlohmann::json vec3Json(const glm::dvec3& v) { return {v.x, v.y, v.z}; }

std::string sceneContentSha256(const Scene& s) {
  Sha256 h;
  h.addString("gblens-scene-v1");
  h.addValue(uint64_t(s.vertices.size()));
  h.add(s.vertices.data(), s.vertices.size() * sizeof(Vertex));
  h.addValue(uint64_t(s.indices.size()));
  h.add(s.indices.data(), s.indices.size() * sizeof(uint32_t));
  for (const Mesh& m : s.meshes) {
    h.addValue(m.firstIndex), h.addValue(m.indexCount), h.addValue(m.firstVertex), h.addValue(m.material);
  }
  for (const MaterialDesc& m : s.materials) {
    h.addValue(m.baseColor), h.addValue(m.specular), h.addValue(m.baseColorTexture), h.addValue(m.baseColorUv);
    h.addValue(m.normalTexture), h.addValue(m.normalUv), h.addValue(m.normalScale), h.addValue(m.alphaMode);
    h.addValue(m.alphaCutoff), h.addValue(m.doubleSided), h.addValue(m.baseUvTransform), h.addValue(m.normalUvTransform);
  }
  for (const Texture& t : s.textures) {
    h.addValue(t.width), h.addValue(t.height), h.addValue(t.srgb), h.addValue(t.repeat);
    h.add(t.rgba8.data(), t.rgba8.size());
  }
  for (const Instance& i : s.instances) h.addValue(i.mesh), h.addValue(i.worldFromObject), h.addValue(i.castsShadow);
  for (const CameraDesc& c : s.cameras) {
    h.addValue(c.worldFromEye), h.addValue(c.yfov), h.addValue(c.aspect), h.addValue(c.znear), h.addValue(c.zfar);
  }
  h.addValue(s.sun.enabled), h.addValue(s.sun.toSun), h.addValue(s.sun.color);
  h.addValue(s.sky.zenith), h.addValue(s.sky.horizon), h.addValue(s.sky.ground), h.addValue(s.sky.ambient);
  return h.hex();
}

static nlohmann::json statsJson(const FrameStats& st) {
  nlohmann::json passes = nlohmann::json::array();
  for (const PassStat& p : st.passes) {
    nlohmann::json j = {{"name", p.name}, {"ms", p.ms}, {"skipped", p.skipped}};
    if (p.skipped) j["reason"] = p.reason;
    passes.push_back(j);
  }
  nlohmann::json j = {{"frame_ms", st.frameMs}, {"gpu_ms", st.gpuMs}, {"passes", passes},
                      {"lights", {{"total", st.lights}, {"visible", st.lightsVisible},
                                  {"near_plane", st.lightsInside}, {"culled", st.lightsCulled}}}};
  if (st.culling.valid)
    j["culling"] = {{"valid", true},
                    {"invocations", st.culling.invocations},
                    {"ideal_pairs", st.culling.idealPairs},
                    {"work_over_ideal", st.culling.workOverIdeal},
                    {"pipeline_invocations", st.culling.pipelineInvocations}};
  else
    j["culling"] = {{"valid", false}, {"reason", "needs coverage on and the coverage_masked and depth targets"}};
  return j;
}

// Lights exactly as uploaded (float values print and parse back bit-exactly through double).
static nlohmann::json lightsJson(const FrameSnapshot& f, const Scene* scene) {
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
                        {"world_position", vec3Json(glm::dvec3(f.view.worldFromEye * glm::dvec4(eye, 1.0)))}};
    if (scene && i < scene->lights.size()) {
      const PointLightDesc& d = scene->lights[i];
      j["desc"] = {{"center", vec3Json(d.center)}, {"orbit_radius", d.orbitRadius}, {"orbit_speed", d.orbitSpeed},
                   {"phase", d.phase},  {"bob", d.bob}, {"radius", d.radius},
                   {"color", vec3Json(glm::dvec3(d.color))}, {"intensity", d.intensity}};
    }
    lights.push_back(j);
  }
  return {{"format", "gblens-lights"}, {"time", f.options.time}, {"visible", f.visibleLights},
          {"stencil_count", f.stencilCount}, {"lights", lights}};
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

static bool writeContents(const fs::path& tmp, const FrameSnapshot& f, const CaptureMeta& meta, std::string& error) {
  nlohmann::json files = nlohmann::json::object(), targets = nlohmann::json::array();
  nlohmann::json skipped = nlohmann::json::array();
  for (size_t i = 0; i < kTargetCount; ++i) {
    Target t = Target(i);
    const TargetImage& ti = f.targets[i];
    if (!ti.present()) {
      skipped.push_back({{"name", targetName(t)}, {"reason", f.absent[i].empty() ? "not captured" : f.absent[i]}});
      continue;
    }
    if (!ti.whole()) {
      error = std::string(targetName(t)) + ": a region read-back cannot be captured (whole targets only)";
      return false;
    }
    std::string file = std::string(targetName(t)) + ".exr";
    if (!writeExr((tmp / file).string(), ti.image, error) || !record(tmp, file, files, error)) return false;
    nlohmann::json exr = nlohmann::json::array();
    for (const ExrChannel& c : exrChannels(ti.image)) exr.push_back({{"name", c.name}, {"type", c.type}});
    targets.push_back({{"name", targetName(t)}, {"file", file}, {"width", ti.image.width},
                       {"height", ti.image.height}, {"type", name(ti.image.type)},
                       {"encoding", name(ti.image.encoding)}, {"channels", ti.image.channels},
                       {"exr_channels", exr}});
    if (t == Target::Final) {  // the tone-mapped sRGB bytes, exactly
      Rgba8Image png{ti.image.width, ti.image.height, ti.image.data};
      if (ti.image.type != PixelType::U8 || ti.image.channelCount() != 4) {
        error = "final: expected 8-bit RGBA";
        return false;
      }
      if (!writePng((tmp / "final.png").string(), png, error) || !record(tmp, "final.png", files, error)) return false;
    }
  }
  if (!writeText(tmp / "lights.json", lightsJson(f, meta.sceneData).dump(1) + "\n", error) ||
      !record(tmp, "lights.json", files, error))
    return false;

  uint32_t culled = uint32_t(f.eyeLights.size() - f.visibleLights.size());
  nlohmann::json m = {
      {"format", "gblens-capture"},
      {"format_version", kCaptureFormatVersion},
      {"gblens", {{"version", GBLENS_VERSION}, {"git", gitHash()}}},
      {"created_utc", utcNow()},
      {"command", meta.commandLine},
      {"device", meta.device},
      {"driver", meta.driver},
      {"scene", {{"source", meta.scene}, {"content_sha256", meta.sceneSha256}}},
      {"size", {f.view.width, f.view.height}},
      {"time", f.options.time},
      {"options", optionsJson(f.options)},
      {"view", viewJson(f.view)},
      {"lightClipFromWorld", matrixJson(f.lightClipFromWorld)},
      {"sun", {{"enabled", f.sun.enabled}, {"to_sun", vec3Json(f.sun.toSun)},
               {"color", vec3Json(glm::dvec3(f.sun.color))}, {"eye_direction", vec3Json(f.sunEyeDirection())}}},
      {"sky", {{"zenith", vec3Json(glm::dvec3(f.sky.zenith))}, {"horizon", vec3Json(glm::dvec3(f.sky.horizon))},
               {"ground", vec3Json(glm::dvec3(f.sky.ground))}, {"ambient", vec3Json(glm::dvec3(f.sky.ambient))}}},
      {"lights", {{"file", "lights.json"}, {"sha256", files["lights.json"]["sha256"]},
                  {"count", f.eyeLights.size()}, {"visible", f.visibleLights.size()},
                  {"stencil_class", f.stencilCount}, {"culled", culled}}},
      {"stats", statsJson(meta.stats)},
      {"targets", targets},
      {"skipped", skipped},
      {"files", files}};
  // Written last: a directory without it is never a capture.
  return writeText(tmp / "manifest.json", m.dump(2) + "\n", error);
}

bool writeCapture(const std::string& dirText, const FrameSnapshot& f, const CaptureMeta& meta, std::string& error) {
  fs::path dir = fs::absolute(fs::path(dirText)).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path();
  std::error_code ec;
  if (fs::exists(dir, ec)) {
    if (!fs::is_directory(dir, ec)) {
      error = dirText + ": exists and is not a directory";
      return false;
    }
    if (!fs::is_empty(dir, ec) && !fs::exists(dir / "manifest.json", ec)) {
      error = dirText + ": exists, is not empty and holds no capture (manifest.json); not overwritten";
      return false;
    }
  }
  fs::path parent = dir.parent_path();
  fs::create_directories(parent, ec);
  std::string stamp = std::to_string(getpid()) + "-" +
                      std::to_string(std::chrono::steady_clock::now().time_since_epoch().count());
  fs::path tmp = parent / ("." + dir.filename().string() + ".partial-" + stamp);
  if (!fs::create_directory(tmp, ec)) {
    error = tmp.string() + ": cannot create (" + ec.message() + ")";
    return false;
  }
  if (!writeContents(tmp, f, meta, error)) {
    fs::remove_all(tmp, ec);
    return false;
  }
  // Swap into place: an old capture moves aside first and is deleted only after the rename.
  fs::path old = parent / ("." + dir.filename().string() + ".old-" + stamp);
  bool hadOld = fs::exists(dir, ec);
  if (hadOld) fs::rename(dir, old, ec);
  if (!ec) fs::rename(tmp, dir, ec);
  if (ec) {
    error = dirText + ": cannot move the capture into place (" + ec.message() + ")";
    std::error_code ignore;
    if (hadOld && !fs::exists(dir, ignore)) fs::rename(old, dir, ignore);
    fs::remove_all(tmp, ignore);
    return false;
  }
  if (hadOld) fs::remove_all(old, ec);
  return true;
}

}  // namespace gb
