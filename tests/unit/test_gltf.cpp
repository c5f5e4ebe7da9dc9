// The glTF loader against the hand-made corpus in tests/data/gltf (make_corpus.py writes it; its
// README lists every case). Valid files: exact vertex/index data, transforms and winding, checked
// against values worked out by hand from how each file was built. Invalid files: the message names
// the file and the element. (The command line and the GPU: test_gltf_gpu.cpp.)
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <sstream>

#include "renderer/scene/builtin.h"
#include "renderer/scene/gltf.h"

namespace gb {

namespace {

std::string corpus(const std::string& name) { return std::string(GBLENS_SOURCE_DIR) + "/tests/data/gltf/" + name; }
Scene load(const std::string& name, int lights = 0) { return loadScene(corpus(name), lights); }

std::vector<uint32_t> indices(const Scene& s, size_t mesh) {
  const Mesh& m = s.meshes[mesh];
  return {s.indices.begin() + m.firstIndex, s.indices.begin() + m.firstIndex + m.indexCount};
}
const Vertex& vertex(const Scene& s, size_t mesh, uint32_t i) { return s.vertices[s.meshes[mesh].firstVertex + i]; }

bool hasWarning(const Scene& s, const std::string& words) {
  for (const std::string& w : s.warnings)
    if (w.find(words) != std::string::npos) return true;
  return false;
}

void expectVec(glm::dvec3 a, glm::dvec3 b, double tol = 1e-6) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

// Geometric normal z of every triangle of a mesh in the xy plane: > 0 is counter-clockwise.
void expectCounterClockwise(const Scene& s, size_t mesh) {
  std::vector<uint32_t> idx = indices(s, mesh);
  for (size_t t = 0; t + 2 < idx.size(); t += 3) {
    glm::vec3 a = vertex(s, mesh, idx[t]).position, b = vertex(s, mesh, idx[t + 1]).position,
              c = vertex(s, mesh, idx[t + 2]).position;
    EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f) << "triangle " << t / 3;
  }
}

}  // namespace

TEST(Gltf, TriangleWithDefaults) {
  Scene s = load("valid/triangle.gltf", 4);
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].vertexCount, 3u);
  EXPECT_EQ(indices(s, 0), (std::vector<uint32_t>{0, 1, 2}));
  expectVec(vertex(s, 0, 1).position, {1, 0, 0});
  expectVec(vertex(s, 0, 2).normal, {0, 0, 1});
  EXPECT_EQ(vertex(s, 0, 2).uv0, glm::vec2(0.0f));  // no TEXCOORD_0: allowed
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].name, "default");
  ASSERT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.instances[0].worldFromObject, glm::dmat4(1.0));
  ASSERT_EQ(s.cameras.size(), 1u);
  EXPECT_EQ(s.cameras[0].name, "auto");
  EXPECT_TRUE(s.generatedLights);  // no lights in the file: the sun and --lights N
  EXPECT_EQ(s.lights.size(), 4u);
  EXPECT_TRUE(s.sun.enabled);
  expectVec(s.bounds.min, {0, 0, 0});
  expectVec(s.bounds.max, {1, 1, 0});
}

TEST(Gltf, IndexTypesAndFlatNormals) {
  // No normals: de-indexed in index order, so the positions show the decoded indices 0 1 2 0 2 3.
  const glm::vec3 quad[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  for (const char* file : {"valid/indices_u8.gltf", "valid/indices_u32.gltf", "valid/flat_normals.gltf"}) {
    Scene s = load(file);
    ASSERT_EQ(s.meshes.size(), 1u) << file;
    EXPECT_EQ(s.meshes[0].vertexCount, 6u) << file;
    EXPECT_EQ(indices(s, 0), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5})) << file;
    const uint32_t order[6] = {0, 1, 2, 0, 2, 3};
    for (uint32_t k = 0; k < 6; ++k) {
      EXPECT_EQ(vertex(s, 0, k).position, quad[order[k]]) << file << " vertex " << k;
      expectVec(vertex(s, 0, k).normal, {0, 0, 1});
    }
  }
}

TEST(Gltf, NonIndexedStripAndFan) {
  Scene flat = load("valid/non_indexed.gltf");
  EXPECT_EQ(indices(flat, 0), (std::vector<uint32_t>{0, 1, 2, 3, 4, 5}));
  Scene strip = load("valid/strip.gltf");  // spec: {v_i, v_i+(1+i%2), v_i+(2-i%2)}
  EXPECT_EQ(indices(strip, 0), (std::vector<uint32_t>{0, 1, 2, 1, 3, 2, 2, 3, 4}));
  expectCounterClockwise(strip, 0);
  Scene fan = load("valid/fan.gltf");  // spec: {v_i+1, v_i+2, v_0}
  EXPECT_EQ(indices(fan, 0), (std::vector<uint32_t>{1, 2, 0, 2, 3, 0, 3, 4, 0}));
  expectCounterClockwise(fan, 0);
}

TEST(Gltf, PointsAndLinesSkippedWithOneWarning) {
  Scene s = load("valid/points_lines.gltf");
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.instances.size(), 1u);
  EXPECT_EQ(s.warnings.size(), 1u);
  EXPECT_TRUE(hasWarning(s, "2 POINTS/LINES primitive(s) skipped"));
}

TEST(Gltf, InterleavedStridedView) {
  Scene s = load("valid/interleaved.gltf");
  const glm::vec3 quad[4] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0}};
  const glm::vec2 uv[4] = {{0, 1}, {1, 1}, {1, 0}, {0, 0}};
  ASSERT_EQ(s.meshes[0].vertexCount, 4u);
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(vertex(s, 0, i).position, quad[i]);
    EXPECT_EQ(vertex(s, 0, i).normal, glm::vec3(0, 0, 1));
    EXPECT_EQ(vertex(s, 0, i).uv0, uv[i]);
  }
  expectCounterClockwise(s, 0);
}

TEST(Gltf, SparseAccessors) {
  Scene s = load("valid/sparse.gltf");
  const glm::vec3 expected[4] = {{0, 0, 0}, {2, 0, 0}, {1, 1, 0}, {3, 3, 0}};  // quad, elements 1 and 3 replaced
  const glm::vec2 uv[4] = {{0, 0}, {0, 0}, {0.5f, 0.25f}, {0, 0}};  // no bufferView: zeros + substitution
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_EQ(vertex(s, 0, i).position, expected[i]) << i;
    EXPECT_EQ(vertex(s, 0, i).uv0, uv[i]) << i;
  }
}

TEST(Gltf, MeshQuantization) {
  Scene s = load("valid/quantized.gltf");
  EXPECT_EQ(vertex(s, 0, 1).position, glm::vec3(100, 0, 0));  // SHORT, not normalized
  EXPECT_EQ(vertex(s, 0, 0).normal, glm::vec3(0, 0, 1));       // BYTE normalized 127 -> 1
  EXPECT_EQ(vertex(s, 0, 0).tangent, glm::vec4(1, 0, 0, -1));  // -128 -> max(-128/127, -1) = -1
  EXPECT_EQ(vertex(s, 0, 1).uv0, glm::vec2(1, 0));              // USHORT normalized 65535 -> 1
  EXPECT_EQ(vertex(s, 0, 2).uv0, glm::vec2(0, 1));
  expectVec(s.bounds.max, {1, 1, 0}, 1e-7);  // node scale 0.01
}

TEST(Gltf, TwoUvSetsAndGeneratedTangents) {
  Scene s = load("valid/two_uv_sets.gltf");
  ASSERT_EQ(s.materials.size(), 1u);
  EXPECT_EQ(s.materials[0].baseColorUv, 0);
  EXPECT_EQ(s.materials[0].normalUv, 1);
  ASSERT_EQ(s.meshes.size(), 2u);
  EXPECT_EQ(vertex(s, 0, 2).uv0, glm::vec2(0.25f, 0.25f));
  EXPECT_EQ(vertex(s, 0, 2).uv1, glm::vec2(1, 0));  // (x, 1 - y) of (1, 1)
  // glTF's v runs down the image and normal maps keep +Y up: tangent = dP/du, bitangent = -dP/dv,
  // w = the sign that makes cross(N, T) * w the bitangent. uv1 = (x, 1-y): T +X, B +Y, w +1;
  // mirrored in u: T -X, B still +Y = cross(+Z, -X) * -1, w -1.
  for (uint32_t i = 0; i < 4; ++i) {
    EXPECT_NEAR(glm::distance(vertex(s, 0, i).tangent, glm::vec4(1, 0, 0, 1)), 0.0f, 1e-6f) << i;
    EXPECT_NEAR(glm::distance(vertex(s, 1, i).tangent, glm::vec4(-1, 0, 0, -1)), 0.0f, 1e-6f) << i;
  }
}

TEST(Gltf, NodeHierarchyTrsAndMatrix) {
  // Parent T (1,2,3) R 90 deg about +Y S 2, child matrix translating +X by 1:
  // world = T R S M: X -> R(2,0,0) = (0,0,-2), Y -> (0,2,0), Z -> R(0,0,2) = (2,0,0), origin (1,2,1).
  Scene s = load("valid/hierarchy.gltf");
  ASSERT_EQ(s.instances.size(), 1u);
  const glm::dmat4& m = s.instances[0].worldFromObject;
  const glm::dvec4 expected[4] = {{0, 0, -2, 0}, {0, 2, 0, 0}, {2, 0, 0, 0}, {1, 2, 1, 1}};
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) EXPECT_NEAR(m[c][r], expected[c][r], 1e-12) << c << "," << r;
}

TEST(Gltf, MirroredInstanceKeepsIndicesAndHasNegativeDeterminant) {
  Scene s = load("valid/mirrored.gltf");
  ASSERT_EQ(s.instances.size(), 2u);
  EXPECT_LT(glm::determinant(glm::dmat3(s.instances[0].worldFromObject)), 0.0);
  EXPECT_GT(glm::determinant(glm::dmat3(s.instances[1].worldFromObject)), 0.0);
  EXPECT_EQ(indices(s, 0), (std::vector<uint32_t>{0, 1, 2, 0, 2, 3}));  // the renderer flips the front face
}

TEST(Gltf, SceneIndexAndInstancing) {
  Scene one = load("valid/scene_index.gltf");
  ASSERT_EQ(one.instances.size(), 1u);
  EXPECT_EQ(one.instances[0].worldFromObject[3], glm::dvec4(5, 0, 0, 1));
  Scene three = load("valid/instancing.gltf");
  EXPECT_EQ(three.meshes.size(), 1u);
  ASSERT_EQ(three.instances.size(), 3u);
  for (int i = 0; i < 3; ++i) {
    EXPECT_EQ(three.instances[size_t(i)].mesh, 0u);
    EXPECT_EQ(three.instances[size_t(i)].worldFromObject[3], glm::dvec4(2.0 * i, 0, 0, 1));
  }
}

TEST(Gltf, Materials) {
  Scene s = load("valid/materials.gltf");
  ASSERT_EQ(s.materials.size(), 4u);
  const MaterialDesc& masked = s.materials[0];
  EXPECT_EQ(masked.baseColor, glm::vec4(0.5f, 0.25f, 1.0f, 1.0f));
  EXPECT_EQ(masked.alphaMode, AlphaMode::Mask);
  EXPECT_FLOAT_EQ(masked.alphaCutoff, 0.3f);
  EXPECT_TRUE(masked.doubleSided);
  ASSERT_GE(masked.baseColorTexture, 0);
  const Texture& t = s.textures[size_t(masked.baseColorTexture)];
  EXPECT_TRUE(t.srgb);
  ASSERT_EQ(t.width * t.height, 4u);  // the 2x2 PNG, rows from the top: red green / blue white
  EXPECT_EQ(std::vector<uint8_t>(t.rgba8.begin(), t.rgba8.end()),
            (std::vector<uint8_t>{255, 0, 0, 255, 0, 255, 0, 255, 0, 0, 255, 255, 255, 255, 255, 255}));
  // KHR_texture_transform offset (0.5, 0), rotation pi/2, scale 2 on uv (1, 0): S -> (2, 0),
  // R (columns (c, s), (-s, c)) -> (0, 2), T -> (0.5, 2).
  glm::vec3 uv = masked.baseUvTransform * glm::vec3(1, 0, 1);
  EXPECT_NEAR(uv.x, 0.5f, 1e-6f);
  EXPECT_NEAR(uv.y, 2.0f, 1e-6f);

  EXPECT_EQ(s.materials[1].alphaMode, AlphaMode::Blend);
  EXPECT_FLOAT_EQ(s.materials[1].alphaCutoff, 0.5f);
  EXPECT_TRUE(hasWarning(s, "alphaMode BLEND drawn as MASK"));

  const MaterialDesc& rough = s.materials[2];
  ASSERT_GE(rough.normalTexture, 0);
  EXPECT_FALSE(s.textures[size_t(rough.normalTexture)].srgb);  // the same image, linear for normals
  EXPECT_FLOAT_EQ(rough.normalScale, 0.5f);
  // The documented mapping: dielectric F0 0.04, roughness 1 -> n = 0 -> s = 0.04 * 8 / (8 pi).
  EXPECT_NEAR(rough.specular, 0.04 / 3.141592653589793, 1e-6);
  EXPECT_FLOAT_EQ(s.materials[3].specular, 1.0f);  // smooth white metal: clamped
  EXPECT_FALSE(s.materials[3].doubleSided);
}

TEST(Gltf, CamerasListedWithAutoCameraLast) {
  Scene s = load("valid/cameras.gltf");
  ASSERT_EQ(s.cameras.size(), 3u);
  EXPECT_EQ(s.cameras[0].name, "persp");
  EXPECT_EQ(s.cameras[1].name, "ortho");
  EXPECT_EQ(s.cameras[2].name, "auto");
  const CameraDesc& p = s.cameras[0];
  EXPECT_EQ(p.worldFromEye[3], glm::dvec4(0, 0, 10, 1));
  EXPECT_DOUBLE_EQ(p.yfov, 0.5);
  EXPECT_DOUBLE_EQ(p.znear, 0.1);
  EXPECT_NEAR(p.zfar, std::sqrt(102.0) * 1.05, 1e-9);  // no zfar: the farthest bounds corner (1,1,0)
  // Orthographic ymag 1: a camera 20 * ymag behind, seeing the same near/far slab.
  const CameraDesc& o = s.cameras[1];
  EXPECT_NEAR(o.worldFromEye[3].z, 40.0, 1e-9);
  EXPECT_NEAR(std::tan(o.yfov * 0.5) * 20.0, 1.0, 1e-9);
  EXPECT_NEAR(o.znear, 20.1, 1e-9);
  EXPECT_NEAR(o.zfar, 70.0, 1e-9);
  EXPECT_TRUE(hasWarning(s, "orthographic"));
}

TEST(Gltf, DegenerateCameraTransformsBecomeRotations) {
  Scene s = load("valid/degenerate_cameras.gltf");
  ASSERT_EQ(s.cameras.size(), 4u);  // scale 0, mirrored, sheared (two equal axes), auto
  for (const CameraDesc& c : s.cameras) {
    glm::dmat3 r(c.worldFromEye);
    EXPECT_NEAR(glm::determinant(r), 1.0, 1e-12) << c.name;
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) EXPECT_NEAR(glm::dot(r[i], r[j]), i == j ? 1.0 : 0.0, 1e-12) << c.name;
  }
  EXPECT_EQ(s.cameras[0].worldFromEye[3], glm::dvec4(0, 0, 5, 1));
  expectVec(-glm::dvec3(s.cameras[1].worldFromEye[2]), {0, 0, -1}, 1e-12);  // still looks down -Z
}

TEST(Gltf, PunctualLights) {
  Scene s = load("valid/lights.gltf", 8);
  EXPECT_FALSE(s.generatedLights);
  ASSERT_EQ(s.lights.size(), 3u);  // point, point, spot; the directional light is the sun
  EXPECT_TRUE(hasWarning(s, "spot light drawn as a point light"));
  expectVec(s.lights[0].center, {0, 2, 0});
  EXPECT_DOUBLE_EQ(s.lights[0].radius, 3.0);  // range
  EXPECT_EQ(s.lights[0].color, glm::vec3(1.0f, 0.5f, 0.25f));
  // Hand-computed from docs/gltf.md: bounds radius sqrt(200)/2, centre at the origin; reference
  // distances 2 (light 0) and sqrt(8) (lights 1, 2); brightest 10/2^2 = 2.5 -> exposure 0.4.
  // No range: where 0.4 * 4 / d^2 = 1/256, d = 16 sqrt(1.6).
  EXPECT_NEAR(s.lights[1].radius, 16.0 * std::sqrt(1.6), 1e-9);
  EXPECT_NEAR(s.lights[2].radius, 16.0 * std::sqrt(1.6), 1e-9);
  ASSERT_TRUE(s.sun.enabled);
  expectVec(s.sun.toSun, {0, 1, 0}, 1e-12);  // rotated -90 deg about X: shines down -Y
  EXPECT_NEAR(s.sun.color.r, 2.0 * 0.4, 1e-6);
}

TEST(Gltf, ExternalBuffersSpacesPercentEncodingAndGlb) {
  for (const char* file : {"valid/external.gltf", "valid/with space.gltf", "valid/raw space.gltf", "valid/binary.glb"}) {
    Scene s = load(file);
    ASSERT_EQ(s.meshes.size(), 1u) << file;
    EXPECT_EQ(indices(s, 0), (std::vector<uint32_t>{0, 1, 2})) << file;
  }
  Scene glb = load("valid/binary.glb");
  ASSERT_EQ(glb.textures.size(), 1u);  // the image in a buffer view
  EXPECT_EQ(glb.textures[0].rgba8, (std::vector<uint8_t>{10, 20, 30, 255}));
}

TEST(Gltf, SameBytesFromMemoryWithoutExternalFiles) {
  std::ifstream in(corpus("valid/external.gltf"), std::ios::binary);
  std::string text((std::istreambuf_iterator<char>(in)), {});
  try {
    loadGltfMemory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "mem.gltf", "", 0);
    FAIL() << "external file read without a base directory";
  } catch (const SceneError& e) {
    EXPECT_NE(e.message.find("mem.gltf: buffer: file 'external.bin' not found"), std::string::npos) << e.message;
  }
}

// KHR_materials_unlit (required by the file, as the Khronos UnlitTest sample does): accepted; the
// material is unlit with no specular, the other stays lit.
TEST(Gltf, UnlitMaterials) {
  Scene s = load("valid/unlit.gltf");
  ASSERT_EQ(s.materials.size(), 2u);
  EXPECT_TRUE(s.materials[0].unlit);
  EXPECT_EQ(s.materials[0].specular, 0.0f);
  EXPECT_NEAR(s.materials[0].baseColor.g, 0.217637640824031, 1e-7);
  EXPECT_FALSE(s.materials[1].unlit);
  EXPECT_TRUE(s.warnings.empty());
}

// KHR_materials_emissive_strength (required): accepted; emission is not drawn, and `gblens info`
// lists it with the strength applied.
TEST(Gltf, EmissiveStrengthAcceptedAndListed) {
  SceneLoadStats stats;
  Scene s = loadScene(corpus("valid/emissive_strength.gltf"), 0, &stats);
  EXPECT_TRUE(s.warnings.empty());
  bool listed = false;
  for (const std::string& i : stats.ignored) listed |= i.find("(1, 0.5, 0) x emissiveStrength 4") != std::string::npos;
  EXPECT_TRUE(listed);
}

// Errors in parts gblens does not draw: one warning each, naming the part and saying it is ignored;
// the triangle is drawn. The same kind of error in a drawn part is refused (the invalid corpus).
TEST(Gltf, ErrorsInPartsNotDrawnAreWarningsNamingThePart) {
  Scene s = load("valid/ignored_parts.gltf");
  ASSERT_EQ(s.meshes.size(), 1u);
  EXPECT_EQ(s.meshes[0].vertexCount, 3u);
  const std::vector<std::string> expected = {
      "animation 0 ('spin') sampler 0: input accessor 99 does not exist (animations are not drawn: ignored)",
      "animation 0 ('spin') channel 0: target node 7 does not exist (animations are not drawn: ignored)",
      "accessor 4: byteOffset 0 + 100 elements (1200 bytes) runs past the end of bufferView 0 (36 bytes) (not read "
      "by anything gblens draws: ignored)",
      "skin 0: joint node 5 does not exist (skins are not drawn: ignored)",
      "mesh 0 primitive 0: morph target 0 POSITION uses accessor 42, which does not exist (morph targets are not "
      "drawn: ignored)",
      "mesh 0 primitive 0: attribute JOINTS_0 has 2 elements, POSITION has 3 (skins are not drawn: ignored)",
      "material 0: KHR_materials_emissive_strength.emissiveStrength is not a number >= 0 (emission is not drawn: "
      "ignored)"};
  for (const std::string& w : expected) EXPECT_TRUE(hasWarning(s, w)) << w;
  EXPECT_EQ(s.warnings.size(), expected.size());
  for (const std::string& w : s.warnings) EXPECT_EQ(w.rfind(corpus("valid/ignored_parts.gltf") + ": ", 0), 0u) << w;
}

// Every invalid file: rejected with a SceneError naming the file and these words (in order).
TEST(Gltf, InvalidFilesRejectedWithClearMessages) {
  const std::vector<std::pair<const char*, std::vector<const char*>>> cases = {
      {"empty.gltf", {"file", "empty"}},
      {"bad_json.gltf", {"JSON", "parse error", "line 1"}},
      {"not_an_object.gltf", {"not a JSON object"}},
      {"no_asset.gltf", {"asset.version", "missing"}},
      {"gltf1.gltf", {"asset.version", "glTF 1.0", "not supported"}},
      {"deep_json.gltf", {"JSON", "nested deeper than 64"}},
      {"truncated.glb", {"GLB", "truncated"}},
      {"bad_magic.glb", {"GLB"}},
      {"meshopt_required.gltf", {"extensionsRequired", "EXT_meshopt_compression", "not supported"}},
      {"missing_bin.gltf", {"buffer", "nothere.bin", "not found"}},
      {"short_bin.gltf", {"buffer", "short_bin.bin", "byteLength"}},
      {"short_data_uri.gltf", {"buffer", "data: URI", "byteLength"}},
      {"missing_image.gltf", {"image 0", "missing.png", "not found"}},
      {"corrupt_image.gltf", {"image 0", "cannot decode"}},
      {"absurd_image.gltf", {"image 0", "100000x100000", "larger than 16384"}},
      {"not_png.gltf", {"image 0", "not a PNG or JPEG"}},
      {"accessor_out_of_range.gltf", {"accessor 0", "100 elements", "past the end of bufferView 0"}},
      {"accessor_offset.gltf", {"accessor 1", "byteOffset 1099511627776", "past the end"}},
      {"bufferview_out_of_range.gltf", {"bufferView 0", "past the end of buffer 0"}},
      {"index_out_of_range.gltf", {"mesh 0 primitive 0", "index 7", "out of range", "3 vertices"}},
      {"nan_position.gltf", {"POSITION", "accessor 0", "element 1", "NaN"}},
      {"inf_normal.gltf", {"NORMAL", "accessor 1", "element 1", "Inf"}},
      {"transform_overflow.gltf", {"node 1", "world transform overflows"}},
      {"big_number.gltf", {"JSON", "overflow", "1e999"}},
      {"node_cycle.gltf", {"node 1", "node cycle"}},
      {"self_child.gltf", {"node 0", "its own child"}},
      {"two_parents.gltf", {"node 2", "two parents", "nodes 0 and 1"}},
      {"absurd_count.gltf", {"accessor 3", "count 1099511627776", "absurd"}},
      {"bad_component_type.gltf", {"accessor 0", "componentType 5124"}},
      {"float_indices.gltf", {"indices accessor 1", "not unsigned"}},
      {"bad_mode.gltf", {"primitive 0", "mode 9"}},
      {"stride_too_small.gltf", {"accessor 0", "byteStride 8", "smaller than an element"}},
      {"count_mismatch.gltf", {"attribute NORMAL has 2 elements", "POSITION has 3"}},
      {"bad_scene.gltf", {"scene", "5 does not exist"}},
      {"bad_mesh_ref.gltf", {"node 0", "mesh 4 does not exist"}},
      {"bad_material_ref.gltf", {"primitive 0", "material 3 does not exist"}},
      {"not_multiple_of_3.gltf", {"TRIANGLES with 4 indices"}},
      {"bad_alpha_mode.gltf", {"material 0", "alphaMode \"GLASS\""}},
      {"bad_camera.gltf", {"camera 0", "yfov"}},
      {"bad_light.gltf", {"KHR_lights_punctual light 0", "\"area\""}},
      {"sparse_bad_index.gltf", {"accessor 0", "sparse index 9", "out of range"}},
      {"zero_quaternion.gltf", {"node 0", "zero quaternion"}},
      // Indices of 2^32 (tinygltf's int would wrap them to 0, an element that exists).
      {"wrapped_buffer_view.gltf", {"accessor 0", "bufferView 4294967296", "does not exist"}},
      {"wrapped_buffer.gltf", {"bufferView 0", "buffer 4294967296", "does not exist"}},
      {"wrapped_mesh.gltf", {"node 0", "mesh 4294967296", "does not exist"}},
      {"wrapped_position.gltf", {"mesh 0 primitive 0", "attributes.POSITION 4294967296", "does not exist"}},
  };
  for (const auto& [file, words] : cases) {
    std::string path = corpus(std::string("invalid/") + file);
    try {
      loadScene(path, 0);
      ADD_FAILURE() << file << " was accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.message.rfind(path + ": ", 0), 0u) << "the message does not start with the file: " << e.message;
      EXPECT_EQ(e.message.find('\n'), std::string::npos) << file << ": not one line: " << e.message;
      size_t at = 0;
      for (const char* w : words) {
        size_t found = e.message.find(w, at);
        EXPECT_NE(found, std::string::npos) << file << ": '" << w << "' missing in: " << e.message;
        if (found != std::string::npos) at = found;
      }
    }
  }
}

}  // namespace gb
