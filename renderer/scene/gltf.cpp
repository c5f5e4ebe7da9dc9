// glTF loading, top to bottom: parse -> validate -> decode images -> materials -> geometry ->
// nodes (instances, cameras, lights). Each step lives in its own gltf_*.cpp file; this one times
// them and holds the helpers they share.
#include "renderer/scene/gltf.h"

#include <chrono>
#include <cmath>
#include <filesystem>
#include <fstream>

#include "renderer/core/json_read.h"
#include "renderer/scene/gltf_internal.h"

namespace gb {

namespace gltf {

void fail(const Doc& doc, const std::string& element, const std::string& what) {
  // One line, whatever a library's words held (OpenImageIO's PNG errors span two).
  std::string line = what;
  for (size_t at; (at = line.find('\n')) != std::string::npos;) line.replace(at, 1, "; ");
  throw SceneError{doc.file + ": " + element + ": " + line};
}

void warn(const Doc& doc, const std::string& message) { doc.scene->warnings.push_back(doc.file + ": " + message); }

void ignored(const Doc& doc, const std::string& feature) {
  if (!doc.stats) return;
  for (const std::string& s : doc.stats->ignored)
    if (s == feature) return;
  doc.stats->ignored.push_back(feature);
}

std::string named(const char* kind, size_t index, const std::string& name) {
  std::string s = std::string(kind) + " " + std::to_string(index);
  if (!name.empty()) s += " ('" + (name.size() > 60 ? name.substr(0, 60) + "..." : name) + "')";
  return s;
}

const tinygltf::Value* member(const tinygltf::Value& object, const char* key) {
  if (!object.IsObject() || !object.Has(key)) return nullptr;
  return &object.Get(key);
}

bool number(const tinygltf::Value* v, double& out) {
  if (!v || !v->IsNumber()) return false;
  double d = v->GetNumberAsDouble();
  if (!std::isfinite(d)) return false;
  out = d;
  return true;
}

const tinygltf::Value* extension(const tinygltf::ExtensionMap& extensions, const char* name) {
  auto it = extensions.find(name);
  return it == extensions.end() ? nullptr : &it->second;
}

}  // namespace gltf

using Clock = std::chrono::steady_clock;
static double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

static Scene loadSteps(gltf::Doc& doc, const uint8_t* data, size_t size, const std::string& baseDir, int lightCount,
                       SceneLoadStats* stats);

Scene loadGltfMemory(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                     int lightCount, SceneLoadStats* stats) {
  SceneLoadStats local;
  if (!stats) stats = &local;
  Scene scene;
  scene.source = name;
  gltf::Doc doc;
  doc.file = name;
  doc.scene = &scene;
  doc.stats = stats;

  // Bad input ends in a SceneError; anything else escaping the steps (memory) becomes one too,
  // so that no file can end the program with an uncaught exception.
  try {
    return loadSteps(doc, data, size, baseDir, lightCount, stats);
  } catch (const SceneError&) {
    throw;
  } catch (const std::bad_alloc&) {
    throw SceneError{name + ": out of memory while loading"};
  } catch (const std::exception& e) {
    throw SceneError{name + ": " + e.what()};
  }
}

static Scene loadSteps(gltf::Doc& doc, const uint8_t* data, size_t size, const std::string& baseDir, int lightCount,
                       SceneLoadStats* stats) {
  Scene& scene = *doc.scene;
  auto t = Clock::now();
  gltf::parseDocument(doc, data, size, baseDir);
  gltf::checkSchema(doc, doc.json);
  gltf::decodeDraco(doc);
  gltf::validateDocument(doc);
  gltf::checkDataRules(doc);
  gltf::checkUnrenderedParts(doc);
  stats->parseMs += msSince(t);

  t = Clock::now();
  std::vector<gltf::DecodedImage> images = gltf::decodeImages(doc, gltf::imagesNeeded(doc));
  stats->decodeMs = msSince(t);

  t = Clock::now();
  gltf::buildMaterials(doc, images);
  images.clear();
  gltf::buildGeometry(doc);
  gltf::buildNodes(doc, lightCount);
  stats->buildMs = msSince(t);
  stats->fileMeshes = uint32_t(doc.model.meshes.size());
  stats->fileNodes = uint32_t(doc.model.nodes.size());
  stats->fileImages = uint32_t(doc.model.images.size());
  for (const tinygltf::Mesh& m : doc.model.meshes) stats->filePrimitives += uint32_t(m.primitives.size());
  return std::move(scene);
}

Scene loadGltf(const std::string& path, int lightCount, SceneLoadStats* stats) {
  auto t = Clock::now();
  std::string notAFile;  // a directory, FIFO or device is refused before it is opened (a FIFO would block)
  if (!isRegularFile(path, notAFile)) throw SceneError{notAFile};
  std::ifstream in(path, std::ios::binary | std::ios::ate);
  if (!in) throw SceneError{path + ": cannot open"};
  std::streamoff size = in.tellg();
  if (size < 0) throw SceneError{path + ": cannot read"};
  if (uint64_t(size) > gltf::kMaxFileBytes)
    throw SceneError{path + ": larger than " + std::to_string(gltf::kMaxFileBytes >> 20) + " MiB"};
  std::vector<uint8_t> bytes(static_cast<size_t>(size));
  in.seekg(0);
  if (size && !in.read(reinterpret_cast<char*>(bytes.data()), size)) throw SceneError{path + ": cannot read"};
  std::string dir = std::filesystem::path(path).parent_path().string();
  SceneLoadStats local;
  if (!stats) stats = &local;
  stats->parseMs = msSince(t);  // reading the file counts as parsing
  return loadGltfMemory(bytes.data(), bytes.size(), path, dir.empty() ? "." : dir, lightCount, stats);
}

}  // namespace gb
