// Reading a manifest and lights.json into a FrameSnapshot's description (see manifest_check.h),
// every value through JsonIn: its errors are one line naming the file, the path and the type.
#include "views/capture/manifest_check.h"

#include <filesystem>
#include <set>

#include "renderer/core/file_name.h"
#include "renderer/core/json_read.h"
#include "renderer/core/layout_json.h"
#include "views/capture/capture.h"
#include "views/capture/exr.h"
#include "views/capture/report.h"

namespace gb {

namespace {

// OpenEXR's longest channel name: longer ones are cut, and two cut alike would merge.
constexpr size_t kMaxExrChannelName = 255;

template <class E, size_t N>
bool parseName(const std::string& text, E& out, const char* (*nameOf)(E)) {
  for (size_t i = 0; i < N; ++i)
    if (text == nameOf(E(i))) {
      out = E(i);
      return true;
    }
  return false;
}

glm::dmat4 matrixIn(const JsonIn& j) {
  if (j.size() != 16) j.fail("expected 16 numbers, got " + std::to_string(j.size()));
  glm::dmat4 m(1.0);
  for (size_t i = 0; i < 16; ++i) m[int(i / 4)][int(i % 4)] = j[i].number();
  return m;
}

void cameraIn(const JsonIn& j, Camera& v) {
  v.width = uint32_t(j["width"].integer(1, 65536));
  v.height = uint32_t(j["height"].integer(1, 65536));
  v.yfov = j["yfov"].number();
  v.aspect = j["aspect"].number();
  v.znear = j["znear"].number();
  v.zfar = j["zfar"].number();
  v.reversedZ = j["reversed_z"].boolean();
  v.clipFromEye = matrixIn(j["clipFromEye"]);
  v.eyeFromClip = matrixIn(j["eyeFromClip"]);
  v.eyeFromWorld = matrixIn(j["eyeFromWorld"]);
  v.worldFromEye = matrixIn(j["worldFromEye"]);
  v.clipFromWorld = matrixIn(j["clipFromWorld"]);
}

void lightsIn(const JsonIn& j, FrameSnapshot& f) {
  if (!j.has("format") || j["format"].string() != "gblens-lights") j.fail("not a gblens lights file");
  const JsonIn lights = j["lights"];
  for (size_t i = 0; i < lights.size(); ++i) {
    gpu::PointLight p{};
    p.eyePositionRadius = glm::vec4(glm::vec3(lights[i]["eye_position"].vec3()), float(lights[i]["radius"].number()));
    p.color = glm::vec4(glm::vec3(lights[i]["color"].vec3()), 0.0f);
    f.eyeLights.push_back(p);
    // The scene's description of the light (its animation), which a re-saved capture writes back: kept,
    // so that Frame.save and a capture re-written compare equal (the writer gives it to the first lights).
    if (lights[i].has("desc") && f.lightDescs.size() == i) {
      const JsonIn d = lights[i]["desc"];
      PointLightDesc desc;
      desc.center = d["center"].vec3();
      desc.orbitRadius = d["orbit_radius"].number();
      desc.orbitSpeed = d["orbit_speed"].number();
      desc.phase = d["phase"].number();
      desc.bob = d["bob"].number();
      desc.radius = d["radius"].number();
      desc.color = glm::vec3(d["color"].vec3());
      desc.intensity = d["intensity"].number();
      f.lightDescs.push_back(desc);
    }
  }
  f.visibleLights = j["visible"].u32s();
  f.stencilCount = j["stencil_count"].u32();
  if (j.has("layer_starts")) f.layerStarts = j["layer_starts"].u32s();  // captures before layers: none
  for (size_t k = 0; k < f.layerStarts.size(); ++k)
    if (f.layerStarts[k] > f.stencilCount || (k && f.layerStarts[k] < f.layerStarts[k - 1]))
      j["layer_starts"].fail("out of order or beyond stencil_count");
  if (f.stencilCount > f.visibleLights.size()) j["stencil_count"].fail("beyond the visible lights");
  for (uint32_t i : f.visibleLights)
    if (i >= f.eyeLights.size()) j["visible"].fail("light index " + std::to_string(i) + " out of range");
}

// The layout the manifest embeds (manifests before layouts: gblens's own for the options), and
// every target's EXR channel names: distinct and within OpenEXR's length.
void layoutIn(const JsonIn& m, const std::string& file, FrameSnapshot& f) {
  if (!m.has("layout")) {
    f.setLayout(nativeLayout(f.options));
    return;
  }
  Layout l;
  std::string error;
  if (!parseLayout(m["layout"].json(), file + ": layout", l, error)) throw JsonError(error);
  for (const LayoutTarget& t : l.targets) {
    CpuImage described;
    describeImage(t, described);
    std::set<std::string> names;
    for (const ExrChannel& c : exrChannels(described)) {
      if (c.name.size() > kMaxExrChannelName || !names.insert(c.name).second)
        m["layout"].fail("target \"" + t.name + "\": EXR channel \"" + c.name.substr(0, 80) + "\" is " +
                         (c.name.size() > kMaxExrChannelName ? "longer than OpenEXR's 255 characters" : "named twice"));
    }
  }
  f.setLayout(std::move(l));
}

// What the frame's source did not say ("unknown": {FIELD: WHY}); those fields may be absent.
void unknownIn(const JsonIn& m, FrameSnapshot& f) {
  if (!m.has("unknown")) return;
  const JsonIn u = m["unknown"];
  for (const std::string& field : u.keys()) f.unknown[field] = u[field.c_str()].string();
  if (f.unknown.count("options") && m.has("options")) f.statedOptions = m["options"].keys();  // what it did state
}

// Whether `field` may be absent: the manifest says its source did not state it (or all of `section`).
bool unstated(const FrameSnapshot& f, const std::string& section, const std::string& field = "") {
  return f.unknown.count(section) || (!field.empty() && f.unknown.count(section + "." + field));
}

void sunAndSkyIn(const JsonIn& m, FrameSnapshot& f) {
  if (!m.has("lightClipFromWorld") && unstated(f, "lightClipFromWorld")) f.lightClipFromWorld = glm::dmat4(1.0);
  else f.lightClipFromWorld = matrixIn(m["lightClipFromWorld"]);
  if (!m.has("sun") && unstated(f, "sun")) {
    f.sun.enabled = false;  // no sun the frame's lighting would use
  } else {
    const JsonIn sun = m["sun"];
    f.sun.enabled = sun["enabled"].boolean();
    f.sun.toSun = sun["to_sun"].vec3();
    f.sun.color = glm::vec3(sun["color"].vec3());
  }
  const bool anySky = m.has("sky");
  const JsonIn sky = anySky ? m["sky"] : m;
  std::pair<const char*, glm::vec3*> fields[] = {
      {"zenith", &f.sky.zenith}, {"horizon", &f.sky.horizon}, {"ground", &f.sky.ground}, {"ambient", &f.sky.ambient}};
  for (auto& [key, value] : fields) {
    if ((!anySky || !sky.has(key)) && unstated(f, "sky", key)) {
      if (std::string(key) == "ambient") *value = glm::vec3(0.0f);  // no ambient term said: none applied
      continue;
    }
    *value = glm::vec3((anySky ? sky : m["sky"])[key].vec3());
  }
}

void targetsIn(const JsonIn& m, FrameSnapshot& f, std::vector<ManifestTarget>& out) {
  const JsonIn skipped = m["skipped"];
  for (size_t i = 0; i < skipped.size(); ++i)
    if (int t = f.indexOf(skipped[i]["name"].string()); t >= 0)
      f.absences[size_t(t)] = absentFromText(skipped[i]["reason"].string());
  const JsonIn files = m["files"], targets = m["targets"];
  for (size_t k = 0; k < targets.size(); ++k) {
    const JsonIn e = targets[k];
    const std::string nameText = e["name"].string();
    ManifestTarget t;
    t.index = f.indexOf(nameText);
    if (t.index < 0) e["name"].fail(jsonBrief(nameText) + " is not in the capture's layout");
    CpuImage& img = t.image;
    describeImage(f.layout.targets[size_t(t.index)], img);
    const std::string type = e["type"].string(), encoding = e["encoding"].string();
    PixelType storedType;
    Encoding storedEncoding;
    if (!parseName<PixelType, 7>(type, storedType, name) || !parseName<Encoding, 7>(encoding, storedEncoding, name) ||
        storedType != img.type || storedEncoding != img.encoding)
      e.fail("type " + type + " / encoding " + encoding + " is not what its layout format " +
             f.layout.targets[size_t(t.index)].format.name + " stores");
    if (e["channels"].strings() != img.channels)
      e["channels"].fail(jsonBrief(e["channels"].json()) + " differ from its layout's " + jsonBrief(nlohmann::json(img.channels)));
    t.file = e["file"].string();
    if (!files.has(t.file.c_str())) e["file"].fail(t.file + " has no checksum in the file list");
    if (e.has("sample_files")) {
      t.sampleFiles = e["sample_files"].strings();
      if (t.sampleFiles.size() < 2 || t.sampleFiles.size() > 64 || t.sampleFiles[0] != t.file)
        e["sample_files"].fail("is not 2 to 64 files, the first of them \"" + t.file + "\"");
      for (const std::string& sf : t.sampleFiles)
        if (!files.has(sf.c_str())) e["sample_files"].fail(sf + " has no checksum in the file list");
    }
    img.width = uint32_t(e["width"].integer(1, 65536));
    img.height = uint32_t(e["height"].integer(1, 65536));
    if (uint64_t(img.width) * img.height > kMaxCaptureTexels)
      e.fail(std::to_string(img.width) + "x" + std::to_string(img.height) + " is more than a capture holds");
    out.push_back(std::move(t));
  }
}

}  // namespace

bool checkManifestFormat(const nlohmann::json& m, const std::string& file, std::string& error) {
  if (!m.is_object() || !m.contains("format") || m["format"] != "gblens-capture") {
    error = file + ": not a gblens capture manifest";
    return false;
  }
  int64_t version = 0;
  if (!m.contains("format_version") || !jsonInteger(m["format_version"], 1, kCaptureFormatVersion, version)) {
    error = file + ": capture format version " + (m.contains("format_version") ? jsonBrief(m["format_version"]) : "missing") +
            " (this gblens reads 1.." + std::to_string(kCaptureFormatVersion) + ")";
    return false;
  }
  return true;
}

bool manifestFiles(const nlohmann::json& m, const std::string& file, std::vector<ManifestFile>& out, std::string& error) {
  out.clear();
  try {
    const JsonIn files = JsonIn(m, file)["files"];
    const std::vector<std::string> names = files.keys();
    if (names.empty()) files.fail("no file list");
    for (const std::string& n : names) {
      std::string why;
      if (!safeFileName(n, why)) files.fail(jsonBrief(n) + ": not a file of the capture folder (" + why + ")");
      const JsonIn entry = files[n.c_str()];
      out.push_back({n, entry["sha256"].string(), uint64_t(entry["bytes"].integer(0, INT64_MAX))});
    }
  } catch (const JsonError& e) {
    error = e.what();
    return false;
  }
  return true;
}

bool frameFromManifest(const nlohmann::json& mj, const nlohmann::json& lights, const std::string& file,
                       const std::string& lightsFile, FrameSnapshot& f, std::vector<ManifestTarget>& targets,
                       std::string& error) {
  targets.clear();
  try {
    const JsonIn m(mj, file);
    if (!m["files"].has("lights.json")) m["files"].fail("lights.json has no checksum in the file list");
    // Another renderer's G-buffer has no gblens render options: the defaults at the frame's size.
    if (m.has("options")) {
      m["options"].object();
      if (!optionsFromJson(mj["options"], f.options, error)) throw JsonError(file + ": " + error);
    } else if (m.has("size")) {
      f.options.width = m["size"][size_t(0)].u32();
      f.options.height = m["size"][size_t(1)].u32();
    }
    // "camera" (earlier manifests: "view").
    cameraIn(m.has("camera") ? m["camera"] : m["view"], f.camera);
    layoutIn(m, file, f);
    lightsIn(JsonIn(lights, lightsFile), f);
    // The method that ran, from the frame's statistics (manifests before issue 16 have none), and
    // clustered with the cluster grid (manifests before it: the occupied clusters).
    if (auto stats = m.find("stats")) {
      if (auto method = stats->find("method"); method && method->has("ran")) parse((*method)["ran"].string(), f.method);
      if (auto assign = stats->find("cluster_assign"); assign && assign->has("ran"))
        f.clusterGrid = (*assign)["ran"].string() == "cpu";
    }
    // The scene it was rendered from (probe --reference loads it; the viewer shows it).
    if (auto scene = m.find("scene")) {
      scene->object();
      for (const char* key : {"source", "content_sha256"})
        if (scene->has(key)) (*scene)[key].string();
    }
    unknownIn(m, f);
    sunAndSkyIn(m, f);
    targetsIn(m, f, targets);
    checkManifestConsistency(m, JsonIn(lights, lightsFile), f, targets);
  } catch (const JsonError& e) {
    error = e.what();
    return false;
  }
  return true;
}

bool checkWrittenManifest(const std::string& dir, std::string& error) {
  // Read from disk, as a reader will: a value JSON cannot hold (NaN, Inf) was written as null.
  std::string manifestText, lightsText;
  nlohmann::json m, lights;
  FrameSnapshot f;
  std::vector<ManifestTarget> targets;
  std::vector<ManifestFile> files;
  if (!readRegularFile((std::filesystem::path(dir) / "manifest.json").string(), manifestText, error, kMaxJsonBytes) ||
      !readRegularFile((std::filesystem::path(dir) / "lights.json").string(), lightsText, error, kMaxJsonBytes) ||
      !parseJson(manifestText, "manifest.json", m, error) || !parseJson(lightsText, "lights.json", lights, error) ||
      !checkManifestFormat(m, "manifest.json", error) || !manifestFiles(m, "manifest.json", files, error) ||
      !frameFromManifest(m, lights, "manifest.json", "lights.json", f, targets, error))
    return false;
  return true;
}

}  // namespace gb

namespace gb {

bool matrixFromJson(const nlohmann::json& j, glm::dmat4& m) {
  try {
    m = matrixIn(JsonIn(j, "matrix"));
  } catch (const JsonError&) {
    return false;
  }
  return true;
}

bool cameraFromJson(const nlohmann::json& j, Camera& v, std::string& error) {
  try {
    cameraIn(JsonIn(j, "camera"), v);
  } catch (const JsonError& e) {
    error = e.what();
    return false;
  }
  return true;
}

}  // namespace gb
