// KHR_draco_mesh_compression (issue 29): a Box-style cube (24 vertices with normals, 12 triangles)
// is written as OBJ and compressed by Debian's draco_encoder (package draco), then loaded as a glTF
// whose primitive carries the Draco bitstream, and as its uncompressed twin. The two scenes hold the
// same triangles: every triangle of the twin has one in the Draco scene with the same winding whose
// corners lie within Draco's position quantisation bound (half a step of 2^qp - 1 steps over the
// largest extent), and normals within the octahedral bound.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include <draco/compression/decode.h>
#include <nlohmann/json.hpp>

#include "renderer/scene/builtin.h"
#include "renderer/scene/gltf.h"
#include "renderer/scene/scene.h"
#include "tests/support/capture_util.h"
#include "tests/support/scenes.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

constexpr int kPositionBits = 11, kNormalBits = 10;

// The cube of Khronos's Box sample: 1 x 1 x 1 around the origin, four vertices per face.
struct Box {
  std::vector<float> positions, normals;
  std::vector<uint16_t> indices;
};
Box makeBox() {
  Box b;
  const float n[6][3] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (int f = 0; f < 6; ++f) {
    const glm::vec3 normal(n[f][0], n[f][1], n[f][2]);
    const glm::vec3 u = std::abs(normal.x) > 0 ? glm::vec3(0, 1, 0) : glm::vec3(1, 0, 0), v = glm::cross(normal, u);
    for (int k = 0; k < 4; ++k) {
      const glm::vec3 p = 0.5f * normal + (k == 1 || k == 2 ? 0.5f : -0.5f) * u + (k >= 2 ? 0.5f : -0.5f) * v;
      b.positions.insert(b.positions.end(), {p.x, p.y, p.z});
      b.normals.insert(b.normals.end(), {normal.x, normal.y, normal.z});
    }
    const uint16_t o = uint16_t(f * 4);
    b.indices.insert(b.indices.end(), {o, uint16_t(o + 1), uint16_t(o + 2), o, uint16_t(o + 2), uint16_t(o + 3)});
  }
  return b;
}

json gltf(const std::string& bufferBytes, json bufferViews, json accessors, json primitive) {
  return {{"asset", {{"version", "2.0"}}},
          {"buffers", {{{"byteLength", bufferBytes.size()}, {"uri", "data:application/octet-stream;base64," + base64(bufferBytes)}}}},
          {"bufferViews", bufferViews},
          {"accessors", accessors},
          {"meshes", {{{"primitives", {primitive}}}}},
          {"nodes", {{{"mesh", 0}}}},
          {"scenes", {{{"nodes", {0}}}}}};
}

Scene load(const json& doc, const std::string& name) {
  const std::string text = doc.dump();
  return loadGltfMemory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), name, "", 0);
}

Scene loadOrFail(const json& doc, const std::string& name) {
  try {
    return load(doc, name);
  } catch (const SceneError& e) {
    ADD_FAILURE() << e.message;
    return Scene{};
  }
}

struct Corner {
  glm::vec3 p, n;
};
std::vector<std::array<Corner, 3>> triangles(const Scene& s) {
  std::vector<std::array<Corner, 3>> out;
  for (const Mesh& m : s.meshes)
    for (uint32_t i = 0; i + 2 < m.indexCount; i += 3) {
      std::array<Corner, 3> t;
      for (int k = 0; k < 3; ++k) {
        const Vertex& v = s.vertices[m.firstVertex + s.indices[m.firstIndex + i + uint32_t(k)]];
        t[size_t(k)] = {v.position, v.normal};
      }
      out.push_back(t);
    }
  return out;
}

TEST(GltfDraco, ABoxCompressedByDracoEncoderLoadsLikeItsUncompressedTwin) {
  ASSERT_EQ(access("/usr/bin/draco_encoder", X_OK), 0) << "draco_encoder is not installed (package draco: make deps)";
  const std::string dir = freshDir("gltf-draco");
  const Box box = makeBox();
  {
    std::ofstream obj(dir + "/box.obj");
    for (size_t i = 0; i < box.positions.size(); i += 3)
      obj << "v " << box.positions[i] << " " << box.positions[i + 1] << " " << box.positions[i + 2] << "\n";
    for (size_t i = 0; i < box.normals.size(); i += 3)
      obj << "vn " << box.normals[i] << " " << box.normals[i + 1] << " " << box.normals[i + 2] << "\n";
    for (size_t i = 0; i < box.indices.size(); i += 3) {
      obj << "f";
      for (int k = 0; k < 3; ++k) obj << " " << box.indices[i + size_t(k)] + 1 << "//" << box.indices[i + size_t(k)] + 1;
      obj << "\n";
    }
  }
  const RunResult enc = runShell("/usr/bin/draco_encoder -i '" + dir + "/box.obj' -o '" + dir + "/box.drc' -qp " +
                                 std::to_string(kPositionBits) + " -qn " + std::to_string(kNormalBits) + " -cl 7");
  ASSERT_EQ(enc.exitCode, 0) << enc.output;
  const std::string drc = readText(dir + "/box.drc");
  ASSERT_FALSE(drc.empty());
  // The Draco attribute ids the extension names (read from the bitstream's header by libdraco).
  draco::DecoderBuffer buffer;
  buffer.Init(drc.data(), drc.size());
  auto mesh = draco::Decoder().DecodeMeshFromBuffer(&buffer);
  ASSERT_TRUE(mesh.ok());
  const int positionId = int(mesh.value()->GetNamedAttribute(draco::GeometryAttribute::POSITION)->unique_id());
  const int normalId = int(mesh.value()->GetNamedAttribute(draco::GeometryAttribute::NORMAL)->unique_id());

  // The uncompressed twin.
  std::string plain(reinterpret_cast<const char*>(box.positions.data()), box.positions.size() * 4);
  plain.append(reinterpret_cast<const char*>(box.normals.data()), box.normals.size() * 4);
  plain.append(reinterpret_cast<const char*>(box.indices.data()), box.indices.size() * 2);
  const json position = {{"componentType", 5126}, {"count", 24}, {"type", "VEC3"}, {"min", {-0.5, -0.5, -0.5}}, {"max", {0.5, 0.5, 0.5}}};
  const json normal = {{"componentType", 5126}, {"count", 24}, {"type", "VEC3"}};
  const json index = {{"componentType", 5123}, {"count", 36}, {"type", "SCALAR"}};
  auto withView = [](json a, int view) {
    a["bufferView"] = view;
    return a;
  };
  const json twin = gltf(plain,
                         {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", 288}},
                          {{"buffer", 0}, {"byteOffset", 288}, {"byteLength", 288}},
                          {{"buffer", 0}, {"byteOffset", 576}, {"byteLength", 72}}},
                         {withView(position, 0), withView(normal, 1), withView(index, 2)},
                         {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}}, {"indices", 2}});
  // The Draco file: accessors without views, the bitstream in a buffer view the extension names.
  json draco = gltf(drc, {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", drc.size()}}}, {position, normal, index},
                    {{"attributes", {{"POSITION", 0}, {"NORMAL", 1}}},
                     {"indices", 2},
                     {"extensions", {{"KHR_draco_mesh_compression",
                                      {{"bufferView", 0}, {"attributes", {{"POSITION", positionId}, {"NORMAL", normalId}}}}}}}});
  draco["extensionsUsed"] = {"KHR_draco_mesh_compression"};
  draco["extensionsRequired"] = {"KHR_draco_mesh_compression"};

  const Scene a = loadOrFail(twin, "twin.gltf"), b = loadOrFail(draco, "draco.gltf");
  EXPECT_TRUE(b.warnings.empty()) << b.warnings[0];
  const auto ta = triangles(a), tb = triangles(b);
  ASSERT_EQ(ta.size(), 12u);
  ASSERT_EQ(tb.size(), ta.size());
  // Draco quantises positions to 2^qp - 1 steps over the largest extent (1 here): half a step,
  // plus float rounding. Normals: octahedral with qn bits, a bound of a few steps of 2 / (2^qn - 1).
  const float positionBound = 0.5f / float((1 << kPositionBits) - 1) + 1e-6f;
  const float normalBound = 4.0f / float((1 << kNormalBits) - 1);
  std::vector<char> used(tb.size(), 0);
  for (const auto& t : ta) {
    bool found = false;
    for (size_t j = 0; j < tb.size() && !found; ++j)
      for (int r = 0; r < 3 && !found && !used[j]; ++r) {  // the same winding: a rotation of the corners
        bool same = true;
        for (int k = 0; k < 3; ++k) {
          const Corner &x = t[size_t(k)], &y = tb[j][size_t((k + r) % 3)];
          for (int c = 0; c < 3; ++c)
            same = same && std::abs(x.p[c] - y.p[c]) <= positionBound && std::abs(x.n[c] - y.n[c]) <= normalBound;
        }
        if (same) found = true, used[j] = 1;
      }
    EXPECT_TRUE(found) << "no Draco triangle matches (" << t[0].p.x << "," << t[0].p.y << "," << t[0].p.z << ") ...";
  }
  // A bitstream that is not Draco: one line naming the primitive.
  json broken = draco;
  broken["buffers"][0]["uri"] = "data:application/octet-stream;base64," + base64(std::string(drc.size(), 'x'));
  try {
    load(broken, "broken.gltf");
    ADD_FAILURE() << "accepted";
  } catch (const SceneError& e) {
    EXPECT_NE(e.message.find("broken.gltf: mesh 0 primitive 0: KHR_draco_mesh_compression: cannot decode"), std::string::npos)
        << e.message;
  }
}

}  // namespace
}  // namespace gb
