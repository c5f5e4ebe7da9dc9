// Stress case: degenerate geometry. Zero-area triangles (one point repeated, three collinear
// points), a sliver 1e-6 wide, duplicate vertices, zero-length normals and opposite normals on one
// triangle (their interpolation passes through zero), drawn in code and loaded from a glTF file
// written here (its zero normals made unit, as glTF requires), under every lighting variant and
// normal format: no NaN/Inf in any target.
#include <unistd.h>

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "app/stress/stress.h"
#include "renderer/scene/builtin.h"
#include "renderer/scene/mesh_builder.h"

namespace gb::stress {

namespace {

struct Raw {
  std::vector<glm::vec3> positions, normals;
  std::vector<uint16_t> indices;
  void add(glm::vec3 p, glm::vec3 n) {
    positions.push_back(p);
    normals.push_back(n);
  }
  void tri(uint16_t a, uint16_t b, uint16_t c) { indices.insert(indices.end(), {a, b, c}); }
};

Raw degenerateTriangles() {
  Raw r;
  const glm::vec3 up(0, 1, 0), zero(0.0f);
  auto t = [&r](glm::vec3 a, glm::vec3 b, glm::vec3 c, glm::vec3 na, glm::vec3 nb, glm::vec3 nc) {
    uint16_t i = uint16_t(r.positions.size());
    r.add(a, na);
    r.add(b, nb);
    r.add(c, nc);
    r.tri(i, uint16_t(i + 1), uint16_t(i + 2));
  };
  t({-3, 0.5f, 1}, {-2, 0.5f, 1}, {-3, 0.5f, 0}, up, up, up);                // a proper one
  t({-1, 0.5f, 1}, {-1, 0.5f, 1}, {-1, 0.5f, 1}, up, up, up);                // one point three times
  t({0, 0.5f, 1}, {1, 1.0f, 1}, {2, 1.5f, 1}, up, up, up);                   // collinear
  t({-4, 0.3f, 2}, {4, 0.3f, 2}, {-4, 0.300001f, 2}, up, up, up);            // sliver, 1e-6 high
  t({-4, 0.2f, 2.5f}, {4, 0.2f, 2.5f}, {4, 0.2f, 2.500001f}, up, up, up);    // sliver seen edge-on
  t({-2, 1, -1}, {0, 1, -1}, {-2, 2, -1}, zero, zero, zero);                 // zero-length normals
  t({1, 0.1f, 1}, {3, 0.1f, 1}, {1, 0.1f, -1}, up, -up, up);                 // normals cancel mid-edge
  t({1, 0.6f, -1}, {3, 0.6f, -1}, {1, 0.6f, -3}, up, zero, -up);             // all of it at once
  // Duplicate vertices: a quad whose two triangles use separate copies of the shared corners,
  // plus a triangle naming one index twice.
  uint16_t i = uint16_t(r.positions.size());
  for (glm::vec3 p : {glm::vec3(-1, 0.4f, -2), glm::vec3(0, 0.4f, -2), glm::vec3(0, 0.4f, -3), glm::vec3(-1, 0.4f, -2),
                      glm::vec3(0, 0.4f, -3), glm::vec3(-1, 0.4f, -3)})
    r.add(p, up);
  r.tri(i, uint16_t(i + 1), uint16_t(i + 2));
  r.tri(uint16_t(i + 3), uint16_t(i + 4), uint16_t(i + 5));
  r.tri(i, i, uint16_t(i + 1));
  return r;
}

std::string base64(const std::vector<uint8_t>& data) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  for (size_t i = 0; i < data.size(); i += 3) {
    uint32_t v = uint32_t(data[i]) << 16;
    if (i + 1 < data.size()) v |= uint32_t(data[i + 1]) << 8;
    if (i + 2 < data.size()) v |= data[i + 2];
    out += k[(v >> 18) & 63];
    out += k[(v >> 12) & 63];
    out += i + 1 < data.size() ? k[(v >> 6) & 63] : '=';
    out += i + 2 < data.size() ? k[v & 63] : '=';
  }
  return out;
}

// The triangles as a glTF 2.0 file (one embedded buffer, double-sided material, a floor quad).
std::string writeGltf(const Raw& r, const std::filesystem::path& path) {
  Raw all = r;
  uint16_t i = uint16_t(all.positions.size());
  for (glm::vec3 p : {glm::vec3(-6, 0, 6), glm::vec3(6, 0, 6), glm::vec3(6, 0, -6), glm::vec3(-6, 0, -6)})
    all.add(p, {0, 1, 0});
  all.tri(i, uint16_t(i + 1), uint16_t(i + 2));
  all.tri(i, uint16_t(i + 2), uint16_t(i + 3));
  std::vector<uint8_t> bytes;
  auto put = [&bytes](const void* p, size_t n) {
    const uint8_t* b = static_cast<const uint8_t*>(p);
    bytes.insert(bytes.end(), b, b + n);
  };
  put(all.positions.data(), all.positions.size() * 12);
  size_t normalsAt = bytes.size();
  put(all.normals.data(), all.normals.size() * 12);
  size_t indicesAt = bytes.size();
  put(all.indices.data(), all.indices.size() * 2);
  glm::vec3 lo(1e30f), hi(-1e30f);
  for (glm::vec3 p : all.positions) {
    lo = glm::min(lo, p);
    hi = glm::max(hi, p);
  }
  nlohmann::json j;
  j["asset"] = {{"version", "2.0"}, {"generator", "gblens stress"}};
  j["buffers"] = {{{"byteLength", bytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bytes)}}};
  j["bufferViews"] = {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", normalsAt}},
                      {{"buffer", 0}, {"byteOffset", normalsAt}, {"byteLength", indicesAt - normalsAt}},
                      {{"buffer", 0}, {"byteOffset", indicesAt}, {"byteLength", bytes.size() - indicesAt}}};
  const size_t n = all.positions.size();
  j["accessors"] = {{{"bufferView", 0}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"},
                     {"min", {lo.x, lo.y, lo.z}}, {"max", {hi.x, hi.y, hi.z}}},
                    {{"bufferView", 1}, {"componentType", 5126}, {"count", n}, {"type", "VEC3"}},
                    {{"bufferView", 2}, {"componentType", 5123}, {"count", all.indices.size()}, {"type", "SCALAR"}}};
  j["materials"] = {{{"doubleSided", true}, {"pbrMetallicRoughness", {{"baseColorFactor", {0.6, 0.6, 0.6, 1.0}}}}}};
  j["meshes"] = {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}, {"material", 0}}}}}};
  j["nodes"] = {{{"mesh", 0}}};
  j["scenes"] = {{{"nodes", {0}}}};
  j["scene"] = 0;
  std::ofstream(path) << j.dump();
  return path.string();
}

}  // namespace

void degenerateGeometryCase(Context& c) {
  const uint32_t w = c.quick ? 64 : 256, h = c.quick ? 48 : 192;
  c.state("no NaN/Inf texel in any target, for every lighting variant and normal format, in code and from a file");
  Raw raw = degenerateTriangles();
  // In code: the triangles exactly as given (zero normals stay zero).
  Scene inCode = groundScene(10.0, true);
  {
    MaterialDesc m;
    m.name = "degenerate";
    m.doubleSided = true;
    inCode.materials.push_back(m);
    MeshBuilder b{inCode};
    b.begin("degenerate", int(inCode.materials.size() - 1));
    for (size_t k = 0; k < raw.positions.size(); ++k) b.vertex(raw.positions[k], raw.normals[k], {0, 0});
    for (size_t k = 0; k + 2 < raw.indices.size(); k += 3) b.triangle(raw.indices[k], raw.indices[k + 1], raw.indices[k + 2]);
    b.end();
    inCode.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
    computeBounds(inCode);
    generateLights(inCode, 24);
  }
  // From a file: what the loader makes of the same triangles.
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("gblens-stress-" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  // glTF requires unit normals (the loader refuses others, docs/gltf.md): the file carries the same
  // triangles with the zero normals made unit; the zero normals themselves must be refused.
  Raw unitNormals = raw;
  for (glm::vec3& n : unitNormals.normals)
    if (glm::length(n) == 0.0f) n = glm::vec3(0, 1, 0);
  Scene fromFile;
  try {
    fromFile = loadScene(writeGltf(unitNormals, dir / "degenerate.gltf"), 24);
    c.check("degenerate glTF loads (0 = yes)", 0.0, 0.0);
  } catch (const SceneError& e) {
    c.check("degenerate glTF loads (0 = yes)", 1.0, 0.0, e.message);
  }
  try {
    loadScene(writeGltf(raw, dir / "zero-normals.gltf"), 24);
    c.check("zero-length glTF normals refused (0 = yes)", 1.0, 0.0, "loaded without a word");
  } catch (const SceneError& e) {
    c.check("zero-length glTF normals refused (0 = yes)", e.message.find("NORMAL") == std::string::npos ? 1.0 : 0.0, 0.0,
            e.message);
  }
  std::error_code ec;
  std::filesystem::remove_all(dir, ec);
  std::pair<const char*, Scene*> scenes[] = {{"in code", &inCode}, {"from file", &fromFile}};
  for (auto& [label, scene] : scenes) {
    if (scene->instances.empty()) continue;
    SessionScene sr(*c.session, *scene);
    c.progress(label);
    struct Variant {
      const char* name;
      Method method;
      Path path;
      NormalFormat normal;
    } variants[] = {{"deferred oct-rg16", Method::Deferred, Path::TwoPass, NormalFormat::OctRg16},
                    {"deferred rgba16f", Method::Deferred, Path::TwoPass, NormalFormat::Rgba16f},
                    {"deferred rgba8-snorm", Method::Deferred, Path::TwoPass, NormalFormat::Rgba8Snorm},
                    {"deferred rgb10a2", Method::Deferred, Path::TwoPass, NormalFormat::Rgb10a2},
                    {"single-pass", Method::Deferred, Path::SinglePass, NormalFormat::OctRg16},
                    {"tiled", Method::Tiled, Path::TwoPass, NormalFormat::OctRg16},
                    {"forward", Method::Forward, Path::TwoPass, NormalFormat::OctRg16}};
    for (const Variant& v : variants) {
      RenderOptions o;
      o.width = w;
      o.height = h;
      o.method = v.method;
      o.path = v.path;
      o.normalFormat = v.normal;
      o.coverage = true;
      o.primitiveId = true;
      o.position = PositionSource::Rgba32f;
      addScan(c, scanAfterFrame(*c.session, o), std::string(label) + " " + v.name);
    }
  }
}

}  // namespace gb::stress
