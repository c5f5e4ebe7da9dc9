// Loading captures: every file checked (present, size, SHA-256) before it is parsed; the
// manifest rebuilds the options, the camera, the sun and the lights; the EXRs the images.
#include <filesystem>
#include <fstream>
#include <sstream>

#include "renderer/core/sha256.h"
#include "views/capture/capture.h"

#include "renderer/core/layout_json.h"
#include "views/capture/exr.h"
#include "views/capture/report.h"

namespace gb {

namespace fs = std::filesystem;

nlohmann::json matrixJson(const glm::dmat4& m) {
  nlohmann::json j = nlohmann::json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) j.push_back(m[c][r]);
  return j;
}

bool matrixFromJson(const nlohmann::json& j, glm::dmat4& m) {
  if (!j.is_array() || j.size() != 16) return false;
  for (int i = 0; i < 16; ++i) {
    if (!j[size_t(i)].is_number()) return false;
    m[i / 4][i % 4] = j[size_t(i)].get<double>();
  }
  return true;
}

nlohmann::json cameraJson(const Camera& v) {
  return {{"width", v.width},   {"height", v.height}, {"yfov", v.yfov},
          {"aspect", v.aspect}, {"znear", v.znear},   {"zfar", v.zfar},
          {"reversed_z", v.reversedZ},
          {"clipFromEye", matrixJson(v.clipFromEye)},     {"eyeFromClip", matrixJson(v.eyeFromClip)},
          {"eyeFromWorld", matrixJson(v.eyeFromWorld)},   {"worldFromEye", matrixJson(v.worldFromEye)},
          {"clipFromWorld", matrixJson(v.clipFromWorld)}};
}

bool cameraFromJson(const nlohmann::json& j, Camera& v, std::string& error) {
  try {
    v.width = j.at("width").get<uint32_t>();
    v.height = j.at("height").get<uint32_t>();
    v.yfov = j.at("yfov").get<double>();
    v.aspect = j.at("aspect").get<double>();
    v.znear = j.at("znear").get<double>();
    v.zfar = j.at("zfar").get<double>();
    v.reversedZ = j.at("reversed_z").get<bool>();
    for (auto [key, m] : {std::pair{"clipFromEye", &v.clipFromEye}, {"eyeFromClip", &v.eyeFromClip},
                          {"eyeFromWorld", &v.eyeFromWorld}, {"worldFromEye", &v.worldFromEye},
                          {"clipFromWorld", &v.clipFromWorld}})
      if (!matrixFromJson(j.at(key), *m)) {
        error = std::string("camera.") + key + ": expected 16 numbers";
        return false;
      }
  } catch (const nlohmann::json::exception& e) {
    error = std::string("camera: ") + e.what();
    return false;
  }
  return true;
}

static glm::dvec3 vec3(const nlohmann::json& j) {
  if (!j.is_array() || j.size() != 3) throw std::runtime_error("expected 3 numbers, got " + j.dump());
  return {j[0].get<double>(), j[1].get<double>(), j[2].get<double>()};
}

static bool readFile(const fs::path& p, std::string& text) {
  std::ifstream in(p, std::ios::binary);
  if (!in) return false;
  std::ostringstream s;
  s << in.rdbuf();
  text = s.str();
  return true;
}

template <class E, size_t N>
static bool parseName(const std::string& text, E& out, const char* (*nameOf)(E)) {
  for (size_t i = 0; i < N; ++i)
    if (text == nameOf(E(i))) {
      out = E(i);
      return true;
    }
  return false;
}

// Every listed file: present, the recorded size, the recorded digest.
static bool checkFiles(const fs::path& dir, const nlohmann::json& files, std::string& error, CaptureProblem& problem) {
  if (!files.is_object() || files.empty()) {
    problem = CaptureProblem::Corrupt;
    error = "manifest.json: no file list";
    return false;
  }
  for (auto& [file, entry] : files.items()) {
    fs::path p = dir / file;
    std::error_code ec;
    if (file.find('/') != std::string::npos || !fs::is_regular_file(p, ec)) {
      problem = CaptureProblem::Missing;
      error = p.string() + ": missing (listed in manifest.json)";
      return false;
    }
    uint64_t bytes = fs::file_size(p, ec), expected = entry.value("bytes", uint64_t(0));
    if (bytes != expected) {
      problem = bytes < expected ? CaptureProblem::Truncated : CaptureProblem::Corrupt;
      error = p.string() + ": " + (bytes < expected ? "truncated: " : "wrong size: ") + std::to_string(bytes) +
              " bytes, manifest.json says " + std::to_string(expected);
      return false;
    }
    std::string hex;
    if (!sha256File(p.string(), hex, error)) {
      problem = CaptureProblem::Missing;
      return false;
    }
    if (hex != entry.value("sha256", "")) {
      problem = CaptureProblem::Checksum;
      error = p.string() + ": checksum mismatch: SHA-256 " + hex + ", manifest.json says " + entry.value("sha256", "?");
      return false;
    }
  }
  return true;
}

static bool loadLights(const fs::path& dir, FrameSnapshot& f, std::string& error) {
  std::string text;
  if (!readFile(dir / "lights.json", text)) {
    error = (dir / "lights.json").string() + ": cannot read";
    return false;
  }
  nlohmann::json j = nlohmann::json::parse(text, nullptr, false);
  if (j.is_discarded() || j.value("format", "") != "gblens-lights") {
    error = (dir / "lights.json").string() + ": not a gblens lights file";
    return false;
  }
  for (const nlohmann::json& l : j.at("lights")) {
    gpu::PointLight p{};
    p.eyePositionRadius = glm::vec4(glm::vec3(vec3(l.at("eye_position"))), l.at("radius").get<float>());
    p.color = glm::vec4(glm::vec3(vec3(l.at("color"))), 0.0f);
    f.eyeLights.push_back(p);
  }
  f.visibleLights = j.at("visible").get<std::vector<uint32_t>>();
  f.stencilCount = j.at("stencil_count").get<uint32_t>();
  f.layerStarts = j.value("layer_starts", std::vector<uint32_t>{});  // captures before layers: none
  for (size_t k = 0; k < f.layerStarts.size(); ++k)
    if (f.layerStarts[k] > f.stencilCount || (k && f.layerStarts[k] < f.layerStarts[k - 1])) {
      error = (dir / "lights.json").string() + ": layer_starts out of order or beyond stencil_count";
      return false;
    }
  for (uint32_t i : f.visibleLights)
    if (i >= f.eyeLights.size() || f.stencilCount > f.visibleLights.size()) {
      error = (dir / "lights.json").string() + ": visible light index out of range";
      return false;
    }
  return true;
}

// The layout the manifest embeds; manifests before layouts: gblens's own for the options.
static bool layoutFromManifest(const nlohmann::json& m, FrameSnapshot& f, std::string& error) {
  auto it = m.find("layout");
  if (it == m.end()) {
    f.setLayout(nativeLayout(f.options));
    return true;
  }
  Layout l;
  if (!parseLayout(*it, "manifest.json: layout", l, error)) return false;
  f.setLayout(std::move(l));
  return true;
}

static bool loadTargets(const fs::path& dir, const nlohmann::json& m, FrameSnapshot& f, std::string& error) {
  for (const nlohmann::json& s : m.at("skipped"))
    if (int i = f.indexOf(s.at("name").get<std::string>()); i >= 0)
      f.absences[size_t(i)] = absentFromText(s.at("reason").get<std::string>());
  for (const nlohmann::json& e : m.at("targets")) {
    std::string nameText = e.at("name").get<std::string>();
    const int index = f.indexOf(nameText);
    if (index < 0) {
      error = "manifest.json: target \"" + nameText + "\" is not in the capture's layout";
      return false;
    }
    CpuImage img;
    describeImage(f.layout.targets[size_t(index)], img);
    std::string type = e.at("type").get<std::string>(), encoding = e.at("encoding").get<std::string>();
    PixelType storedType;
    Encoding storedEncoding;
    if (!parseName<PixelType, 7>(type, storedType, name) || !parseName<Encoding, 7>(encoding, storedEncoding, name) ||
        storedType != img.type || storedEncoding != img.encoding) {
      error = "manifest.json: target " + nameText + ": type " + type + " / encoding " + encoding + " is not what its layout format " +
              f.layout.targets[size_t(index)].format.name + " stores";
      return false;
    }
    if (e.at("channels").get<std::vector<std::string>>() != img.channels) {
      error = "manifest.json: target " + nameText + ": channels " + e.at("channels").dump() +
              " differ from its layout's " + nlohmann::json(img.channels).dump();
      return false;
    }
    std::string file = e.at("file").get<std::string>();
    if (!m.at("files").contains(file)) {
      error = "manifest.json: target " + nameText + ": " + file + " has no checksum in the file list";
      return false;
    }
    img.width = e.at("width").get<uint32_t>();
    img.height = e.at("height").get<uint32_t>();
    if (!readExr((dir / file).string(), img, error)) return false;
    TargetImage& ti = f.images[size_t(index)];
    ti.image = std::move(img);
    ti.targetWidth = ti.image.width;
    ti.targetHeight = ti.image.height;
    f.absences[size_t(index)] = Absent::No;
  }
  return true;
}

bool loadCapture(const std::string& dirText, Capture& out, std::string& error, CaptureProblem* problemOut) {
  CaptureProblem problem = CaptureProblem::None;
  auto fail = [&](CaptureProblem p, const std::string& message) {
    if (problem == CaptureProblem::None) problem = p;
    if (problemOut) *problemOut = problem;
    error = message;
    return false;
  };
  fs::path dir(dirText);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return fail(CaptureProblem::Missing, dirText + ": no such capture directory");
  std::string text;
  if (!readFile(dir / "manifest.json", text))
    return fail(CaptureProblem::Missing, dirText + ": no manifest.json (not a capture, or an interrupted one)");
  nlohmann::json m = nlohmann::json::parse(text, nullptr, false);
  if (m.is_discarded() || !m.is_object())
    return fail(CaptureProblem::Corrupt, (dir / "manifest.json").string() + ": not valid JSON");
  if (m.value("format", "") != "gblens-capture")
    return fail(CaptureProblem::Corrupt, (dir / "manifest.json").string() + ": not a gblens capture manifest");
  if (m.value("format_version", 0) < 1 || m.value("format_version", 0) > kCaptureFormatVersion)
    return fail(CaptureProblem::Corrupt, (dir / "manifest.json").string() + ": capture format version " +
                                             m.value("format_version", nlohmann::json(nullptr)).dump() +
                                             " (this gblens reads 1.." + std::to_string(kCaptureFormatVersion) + ")");
  try {
    if (!checkFiles(dir, m.value("files", nlohmann::json()), error, problem)) return fail(problem, dirText + ": " + error);
  } catch (const std::exception& e) {
    return fail(CaptureProblem::Corrupt, (dir / "manifest.json").string() + ": files: " + e.what());
  }

  Capture c;
  c.dir = dirText;
  FrameSnapshot& f = c.frame;
  try {
    if (!m.at("files").contains("lights.json"))
      return fail(CaptureProblem::Corrupt, dirText + ": manifest.json: lights.json has no checksum in the file list");
    // "camera" (earlier manifests: "view").
    const nlohmann::json& camera = m.contains("camera") ? m.at("camera") : m.at("view");
    // Another renderer's G-buffer has no gblens render options: the defaults at the frame's size.
    if (m.contains("options") && !optionsFromJson(m.at("options"), f.options, error))
      return fail(CaptureProblem::Corrupt, dirText + ": " + error);
    if (!m.contains("options") && m.contains("size")) {
      f.options.width = m.at("size").at(0).get<uint32_t>();
      f.options.height = m.at("size").at(1).get<uint32_t>();
    }
    if (!cameraFromJson(camera, f.camera, error) ||
        !layoutFromManifest(m, f, error) ||
        !loadLights(dir, f, error))
      return fail(CaptureProblem::Corrupt, dirText + ": " + error);
    // The method that ran, from the frame's statistics (manifests before issue 16 have none).
    if (m.contains("stats") && m.at("stats").contains("method") && m.at("stats").at("method").contains("ran"))
      parse(m.at("stats").at("method").at("ran").get<std::string>(), f.method);
    // Clustered with the cluster grid (manifests before it: the occupied clusters).
    if (m.contains("stats") && m.at("stats").contains("cluster_assign"))
      f.clusterGrid = m.at("stats").at("cluster_assign").value("ran", "") == "cpu";
    if (!matrixFromJson(m.at("lightClipFromWorld"), f.lightClipFromWorld))
      return fail(CaptureProblem::Corrupt, dirText + ": manifest.json: lightClipFromWorld: expected 16 numbers");
    const nlohmann::json& sun = m.at("sun");
    f.sun.enabled = sun.at("enabled").get<bool>();
    f.sun.toSun = vec3(sun.at("to_sun"));
    f.sun.color = glm::vec3(vec3(sun.at("color")));
    const nlohmann::json& sky = m.at("sky");
    f.sky.zenith = glm::vec3(vec3(sky.at("zenith")));
    f.sky.horizon = glm::vec3(vec3(sky.at("horizon")));
    f.sky.ground = glm::vec3(vec3(sky.at("ground")));
    f.sky.ambient = glm::vec3(vec3(sky.at("ambient")));
    if (!loadTargets(dir, m, f, error)) return fail(CaptureProblem::Corrupt, dirText + ": " + error);
  } catch (const std::exception& e) {
    return fail(CaptureProblem::Corrupt, dirText + ": manifest.json: " + e.what());
  }
  c.manifest = std::move(m);
  out = std::move(c);
  if (problemOut) *problemOut = CaptureProblem::None;
  return true;
}

}  // namespace gb
