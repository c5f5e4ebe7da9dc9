// Parse step: bytes -> tinygltf::Model. tinygltf reads the JSON/GLB structure and the external
// files (through our file callbacks: no shell expansion, no fallback to the working directory,
// a size limit); images are kept encoded (our image callback) and decoded later through
// OpenImageIO. The version and required extensions are checked here, before anything else.
#include <cstring>
#include <filesystem>
#include <fstream>

#include "renderer/core/json_read.h"
#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {

struct FileAccess {
  std::string baseDir;  // absolute, without trailing '/'; empty: external files refused
};

bool fileExists(const std::string& path, void* user) {
  const auto* access = static_cast<const FileAccess*>(user);
  // tinygltf tries "<baseDir>/<uri>" and then "./<uri>"; only the first is the file's own folder.
  if (access->baseDir.empty()) return false;
  const std::string prefix = access->baseDir.back() == '/' ? access->baseDir : access->baseDir + "/";
  if (path.compare(0, prefix.size(), prefix) != 0) return false;
  std::error_code ec;
  return std::filesystem::is_regular_file(path, ec);
}

std::string expandFilePath(const std::string& path, void*) { return path; }

bool readWholeFile(std::vector<unsigned char>* out, std::string* err, const std::string& path, void*) {
  std::error_code ec;
  uintmax_t size = std::filesystem::file_size(path, ec);
  if (ec || size > kMaxFileBytes) {
    if (err) *err += ec ? "cannot read" : "larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  out->resize(size_t(size));
  if (!in || (size && !in.read(reinterpret_cast<char*>(out->data()), std::streamsize(size)))) {
    if (err) *err += "cannot read";
    return false;
  }
  return true;
}

bool writeWholeFile(std::string*, const std::string&, const std::vector<unsigned char>&, void*) { return false; }

// Images stay encoded here: tinygltf's own stb decoding is not used. Images in a buffer view are
// not touched at all (their view is validated first, then read by decodeImages).
bool keepEncoded(tinygltf::Image* image, const int, std::string*, std::string*, int, int, const unsigned char* bytes,
                 int size, void*) {
  if (image->bufferView >= 0) return true;
  if (bytes && size > 0) image->image.assign(bytes, bytes + size);
  image->as_is = true;
  return true;
}

// tinygltf and nlohmann-json recurse over nested values (extras, extensions): refuse documents
// nested deeper than any real glTF before they get there.
void checkJsonDepth(const Doc& doc, const uint8_t* json, size_t size) {
  if (!jsonDepthWithin(std::string_view(reinterpret_cast<const char*>(json), size), kMaxJsonDepth))
    fail(doc, "JSON", "nested deeper than " + std::to_string(kMaxJsonDepth) + " levels");
}

std::string firstLines(std::string text) {
  // nlohmann's "[json.exception.parse_error.101] " prefix says nothing to a user.
  if (text.rfind("[json.exception.", 0) == 0) {
    size_t end = text.find("] ");
    if (end != std::string::npos) text = text.substr(end + 2);
  }
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  for (char& c : text)
    if (c == '\n') c = ';';
  if (text.size() > 400) text = text.substr(0, 400) + "...";
  return text.empty() ? "cannot be parsed" : text;
}

void checkVersion(const Doc& doc, bool parsed, const std::string& error) {
  // tinygltf fails without an asset.version string (and leaves the default "2.0" in the model).
  if (!parsed && error.find("\"asset\" object not found") != std::string::npos)
    fail(doc, "asset.version", "missing: not a glTF 2.0 file");
  const std::string& v = doc.model.asset.version;
  if (v.rfind("2.", 0) != 0) {
    if (v.rfind("1.", 0) == 0 || v == "1")
      fail(doc, "asset.version", "\"" + v + "\": glTF 1.0 files are not supported (convert to glTF 2.0)");
    fail(doc, "asset.version", "\"" + v + "\": only glTF 2.x is supported");
  }
  const std::string& minVersion = doc.model.asset.minVersion;
  if (!minVersion.empty() && minVersion != "2.0")
    fail(doc, "asset.minVersion", "\"" + minVersion + "\": this file needs a newer glTF reader than 2.0");
}

// Extensions gblens draws. A required extension not listed here (Draco, meshopt, KTX2...) makes
// the file unreadable for us: say which one.
const char* const kSupported[] = {"KHR_mesh_quantization", "KHR_texture_transform", "KHR_lights_punctual",
                                  "KHR_materials_unlit", "KHR_materials_emissive_strength",
                                  "KHR_draco_mesh_compression"};

bool supported(const std::string& name) {
  for (const char* s : kSupported)
    if (name == s) return true;
  return false;
}

void checkExtensions(const Doc& doc) {
  std::string list;
  for (const char* s : kSupported) list += (list.empty() ? "" : ", ") + std::string(s);
  for (const std::string& e : doc.model.extensionsRequired)
    if (!supported(e)) fail(doc, "extensionsRequired", "\"" + e + "\" is not supported by gblens (supported: " + list + ")");
  for (const std::string& e : doc.model.extensionsUsed)
    if (!supported(e)) ignored(doc, "extension " + e);
}

}  // namespace

void parseDocument(Doc& doc, const uint8_t* data, size_t size, const std::string& baseDir) {
  if (size == 0) fail(doc, "file", "empty");
  if (size > kMaxFileBytes) fail(doc, "file", "larger than " + std::to_string(kMaxFileBytes >> 20) + " MiB");
  const bool glb = size >= 4 && std::memcmp(data, "glTF", 4) == 0;
  if (glb) {
    // The JSON chunk, when the header is sane (tinygltf reports a broken header itself).
    uint32_t jsonLength = 0;
    if (size >= 20) std::memcpy(&jsonLength, data + 12, 4);
    if (size >= 20 && uint64_t(jsonLength) + 20 <= size) checkJsonDepth(doc, data + 20, jsonLength);
  } else {
    checkJsonDepth(doc, data, size);
  }

  FileAccess access;
  if (!baseDir.empty()) {
    std::error_code ec;
    access.baseDir = std::filesystem::absolute(baseDir, ec).lexically_normal().string();
    while (access.baseDir.size() > 1 && access.baseDir.back() == '/') access.baseDir.pop_back();
  }
  // The JSON as written, for the schema step (its nesting was bounded above). When tinygltf refuses
  // the document, the schema names the element and property it stumbled on, if it can.
  uint32_t jsonLength = 0;
  if (glb && size >= 20) std::memcpy(&jsonLength, data + 12, 4);
  if (!glb || uint64_t(jsonLength) + 20 <= size) {
    const char* text = reinterpret_cast<const char*>(data) + (glb ? 20 : 0);
    doc.json = nlohmann::json::parse(text, text + (glb ? jsonLength : size), nullptr, false);
    if (doc.json.is_discarded()) doc.json = nullptr;
  }
  // tinygltf refuses the index accessors of Draco primitives (they have no buffer view): it reads
  // a copy where they name a placeholder view (gltf_draco.cpp puts them back).
  std::vector<uint8_t> dracoCopy;
  if (prepareDracoIndices(doc, glb, data, size, dracoCopy)) data = dracoCopy.data(), size = dracoCopy.size();

  tinygltf::TinyGLTF loader;
  loader.SetImageLoader(keepEncoded, nullptr);
  loader.SetFsCallbacks({fileExists, expandFilePath, readWholeFile, writeWholeFile, &access});
  std::string err, warnings;
  bool ok = false;
  try {
    ok = glb ? loader.LoadBinaryFromMemory(&doc.model, &err, &warnings, data, unsigned(size), access.baseDir)
             : loader.LoadASCIIFromString(&doc.model, &err, &warnings, reinterpret_cast<const char*>(data),
                                          unsigned(size), access.baseDir);
  } catch (const std::exception& e) {
    ok = false;
    err = e.what();
  }
  if (err.empty()) err = warnings;
  // A glTF 1.0 file or a required extension explains every later error: report those first.
  checkVersion(doc, ok, err);
  checkExtensions(doc);
  if (ok) return;
  checkSchema(doc, doc.json, false);
  // tinygltf's messages for the common cases, reworded to name the element.
  const std::string notFound = "File not found : ", mismatch = "File size mismatch : ";
  if (err.rfind(notFound, 0) == 0)
    fail(doc, "buffer", "file '" + firstLines(err.substr(notFound.size())) + "' not found");
  if (err.rfind(mismatch, 0) == 0) {
    // "File size mismatch : PATH, requestedBytes N, but got M"
    std::string rest = firstLines(err.substr(mismatch.size()));
    size_t comma = rest.rfind(", requestedBytes ");
    std::string file = std::filesystem::path(rest.substr(0, comma)).filename().string();
    fail(doc, "buffer", "file '" + file + "' does not hold byteLength bytes (" +
                            (comma == std::string::npos ? rest : rest.substr(comma + 2)) + ")");
  }
  if (err.find("Failed to decode 'uri'") != std::string::npos && err.find("in Buffer") != std::string::npos)
    fail(doc, "buffer", "its data: URI is not base64 of exactly byteLength bytes");
  if (err.find("Invalid glTF binary") != std::string::npos)
    fail(doc, "GLB", "the header's length or the JSON chunk's length does not fit the file (truncated or corrupt)");
  if (err.find("[json.exception.") != std::string::npos) fail(doc, "JSON", firstLines(err));
  // tinygltf's warnings, when it gave both, folded into the one line.
  const bool alsoWarned = !warnings.empty() && warnings != err;
  fail(doc, glb ? "GLB" : "glTF", firstLines(err) + (alsoWarned ? " (tinygltf also warned: " + firstLines(warnings) + ")" : ""));
}

}  // namespace gb::gltf
