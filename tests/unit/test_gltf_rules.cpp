// The glTF validator's error classes that touch what gblens draws (docs/gltf.md lists them): one
// fixture per class, made here from a small valid document (a textured triangle with normals,
// tangents, UVs, a camera and a light) by one edit the validator reports as that class. Each must be
// refused with a message naming the element; undeclared extensions gblens does not draw only warn.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>

#include <OpenImageIO/imageio.h>

#include <cstring>
#include <fstream>
#include <functional>
#include <nlohmann/json.hpp>

#include "renderer/scene/builtin.h"
#include "renderer/scene/gltf.h"
#include "renderer/scene/scene.h"
#include "tests/support/scenes.h"

namespace gb {
namespace {

using json = nlohmann::json;

template <class T>
void append(std::string& s, std::initializer_list<T> values) {
  for (T v : values) s.append(reinterpret_cast<const char*>(&v), sizeof(T));
}

std::string png1x1() {
  // A file of this process's own: ctest runs the tests of this file in parallel processes.
  const std::string path = "/tmp/gblens-rules-1x1-" + std::to_string(::getpid()) + ".png";
  const uint8_t rgba[4] = {200, 100, 50, 255};
  auto out = OIIO::ImageOutput::create(path);
  OIIO::ImageSpec spec(1, 1, 4, OIIO::TypeDesc::UINT8);
  out->open(path, spec), out->write_image(OIIO::TypeDesc::UINT8, rgba), out->close();
  std::ifstream in(path, std::ios::binary);
  std::string bytes((std::istreambuf_iterator<char>(in)), {});
  std::remove(path.c_str());
  return bytes;
}

// The buffer: positions (0..35), normals (36..71), tangents (72..119), UVs (120..143), indices (144..149).
json validDocument() {
  std::string b;
  append<float>(b, {0, 0, 0, 1, 0, 0, 0, 1, 0});
  append<float>(b, {0, 0, 1, 0, 0, 1, 0, 0, 1});
  append<float>(b, {1, 0, 0, 1, 1, 0, 0, 1, 1, 0, 0, 1});
  append<float>(b, {0, 0, 1, 0, 0, 1});
  append<uint16_t>(b, {0, 1, 2, 0});
  auto view = [](int offset, int length, int target) {
    return json{{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}};
  };
  auto accessor = [](int view, int count, const char* type, int component) {
    return json{{"bufferView", view}, {"componentType", component}, {"count", count}, {"type", type}};
  };
  json pos = accessor(0, 3, "VEC3", 5126);
  pos["min"] = {0, 0, 0}, pos["max"] = {1, 1, 0};
  return {{"asset", {{"version", "2.0"}}},
          {"extensionsUsed", {"KHR_texture_transform", "KHR_lights_punctual"}},
          {"buffers", {{{"byteLength", b.size()}, {"uri", "data:application/octet-stream;base64," + base64(b)}}}},
          {"bufferViews", {view(0, 36, 34962), view(36, 36, 34962), view(72, 48, 34962), view(120, 24, 34962), view(144, 6, 34963)}},
          {"accessors", {pos, accessor(1, 3, "VEC3", 5126), accessor(2, 3, "VEC4", 5126), accessor(3, 3, "VEC2", 5126),
                         accessor(4, 3, "SCALAR", 5123)}},
          {"images", {{{"uri", "data:image/png;base64," + base64(png1x1())}, {"mimeType", "image/png"}}}},
          {"samplers", {{{"magFilter", 9729}}}},
          {"textures", {{{"source", 0}, {"sampler", 0}}}},
          {"materials", {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}, {"metallicFactor", 0.5}}}}}},
          {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"NORMAL", 1}, {"TANGENT", 2}, {"TEXCOORD_0", 3}}},
                                        {"indices", 4}, {"material", 0}}}}}}},
          {"cameras", {{{"type", "perspective"}, {"perspective", {{"yfov", 0.8}, {"znear", 0.1}}}}}},
          {"extensions", {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 2}}}}}}}},
          {"nodes", {{{"mesh", 0}}, {{"camera", 0}, {"translation", {0, 0, 3}}},
                     {{"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}}}},
          {"scenes", {{{"nodes", {0, 1, 2}}}}},
          {"scene", 0}};
}

Scene loadText(const json& doc) {
  const std::string text = doc.dump();
  return loadGltfMemory(reinterpret_cast<const uint8_t*>(text.data()), text.size(), "rules.gltf", "", 0);
}

// Replaces bytes of the buffer at `offset` (re-encoding the data URI).
template <class T>
void setValue(json& doc, size_t offset, T v) {
  std::string uri = doc["buffers"][0]["uri"];
  const std::string prefix = "data:application/octet-stream;base64,";
  std::string b64 = uri.substr(prefix.size()), bytes;
  auto val = [](char c) { return c >= 'A' && c <= 'Z' ? c - 'A' : c >= 'a' && c <= 'z' ? c - 'a' + 26 : c >= '0' && c <= '9' ? c - '0' + 52 : c == '+' ? 62 : 63; };
  for (size_t i = 0; i + 3 < b64.size(); i += 4) {
    uint32_t v = uint32_t(val(b64[i])) << 18 | uint32_t(val(b64[i + 1])) << 12 | uint32_t(b64[i + 2] == '=' ? 0 : val(b64[i + 2])) << 6 |
                 uint32_t(b64[i + 3] == '=' ? 0 : val(b64[i + 3]));
    bytes += char(v >> 16);
    if (b64[i + 2] != '=') bytes += char(v >> 8 & 255);
    if (b64[i + 3] != '=') bytes += char(v & 255);
  }
  std::memcpy(&bytes[offset], &v, sizeof(T));
  doc["buffers"][0]["uri"] = prefix + base64(bytes);
}

struct Case {
  const char* validatorClass;
  std::function<void(json&)> edit;
  std::vector<std::string> words;
};

TEST(GltfRules, TheValidDocumentLoadsWithoutWarnings) {
  const Scene s = loadText(validDocument());
  EXPECT_EQ(s.meshes.size(), 1u);
  EXPECT_TRUE(s.warnings.empty()) << s.warnings[0];
}

TEST(GltfRules, EveryRejectedValidatorClassIsRefusedNamingTheElement) {
  const std::vector<Case> cases = {
      {"TYPE_MISMATCH", [](json& d) { d["materials"][0]["pbrMetallicRoughness"] = json::array(); },
       {"material 0", "pbrMetallicRoughness", "expected an object"}},
      {"TYPE_MISMATCH (extension)",
       [](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["extensions"] = {{"KHR_texture_transform", "x"}}; },
       {"material 0", "KHR_texture_transform", "expected an object"}},
      {"INVALID_INDEX", [](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["index"] = -1; },
       {"material 0", "baseColorTexture.index", "out of range"}},
      {"VALUE_NOT_IN_RANGE", [](json& d) { d["materials"][0]["pbrMetallicRoughness"]["metallicFactor"] = 2; },
       {"material 0", "metallicFactor"}},
      {"VALUE_NOT_IN_LIST", [](json& d) { d["samplers"][0]["magFilter"] = 1234; }, {"sampler 0", "magFilter", "not one of"}},
      {"ARRAY_LENGTH_NOT_IN_LIST", [](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorFactor"] = {1, 1, 1}; },
       {"material 0", "baseColorFactor", "length"}},
      {"UNDEFINED_PROPERTY", [](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"].erase("index"); },
       {"material 0", "baseColorTexture.index", "missing"}},
      {"UNDECLARED_EXTENSION", [](json& d) { d["materials"][0]["extensions"] = {{"KHR_materials_unlit", json::object()}}; },
       {"KHR_materials_unlit", "not declared"}},
      {"UNRESOLVED_REFERENCE", [](json& d) { d["meshes"][0]["primitives"][0]["material"] = 5; }, {"mesh 0 primitive 0", "material 5"}},
      {"ACCESSOR_NON_UNIT", [](json& d) { setValue(d, 36 + 8, 2.0f); }, {"mesh 0 primitive 0", "NORMAL 0", "length"}},
      {"ACCESSOR_INVALID_SIGN", [](json& d) { setValue(d, 72 + 12, 0.5f); }, {"mesh 0 primitive 0", "TANGENT 0", "w"}},
      {"ACCESSOR_MAX_MISMATCH", [](json& d) { d["accessors"][0]["max"] = {0.5, 1, 0}; },
       {"mesh 0 primitive 0", "POSITION", "outside the declared min/max"}},
      {"ACCESSOR_INDEX_PRIMITIVE_RESTART", [](json& d) { setValue<uint16_t>(d, 148, 65535); },
       {"mesh 0 primitive 0", "primitive restart"}},
      {"ACCESSOR_INDEX_OOB", [](json& d) { setValue<uint16_t>(d, 148, 7); }, {"mesh 0 primitive 0", "index 7", "out of range"}},
      {"MESH_PRIMITIVE_TOO_FEW_TEXCOORDS", [](json& d) { d["materials"][0]["pbrMetallicRoughness"]["baseColorTexture"]["texCoord"] = 1; },
       {"mesh 0 primitive 0", "TEXCOORD_1"}},
      {"MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY",
       [](json& d) { auto& a = d["meshes"][0]["primitives"][0]["attributes"]; a["TEXCOORD_1"] = 3; a.erase("TEXCOORD_0"); },
       {"mesh 0 primitive 0", "TEXCOORD_1 without TEXCOORD_0"}},
      {"MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT",
       [](json& d) { d["accessors"][3]["componentType"] = 5123, d["accessors"][3]["count"] = 3; },
       {"mesh 0 primitive 0", "TEXCOORD_0", "not allowed"}},
      {"MESH_PRIMITIVE_UNEQUAL_ACCESSOR_COUNT", [](json& d) { d["accessors"][1]["count"] = 2; }, {"mesh 0 primitive 0", "NORMAL"}},
      {"BUFFER_VIEW_TARGET_OVERRIDE", [](json& d) { d["bufferViews"][0]["target"] = 34963; }, {"mesh 0 primitive 0", "target"}},
      {"ACCESSOR_TOTAL_OFFSET_ALIGNMENT", [](json& d) { d["bufferViews"][0]["byteOffset"] = 2; },
       {"mesh 0 primitive 0", "multiple of its component size"}},
      {"VALUE_MULTIPLE_OF (byteStride)", [](json& d) { d["bufferViews"][0]["byteLength"] = 40, d["bufferViews"][0]["byteStride"] = 13; },
       {"bufferView 0", "byteStride 13", "multiple of 4"}},
      {"MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE",
       [](json& d) { d["bufferViews"][0]["byteLength"] = 72, d["accessors"][1]["bufferView"] = 0, d["accessors"][1]["byteOffset"] = 36; },
       {"mesh 0 primitive 0", "no byteStride"}},
      {"NODE_MATRIX_TRS", [](json& d) { d["nodes"][1]["matrix"] = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 3, 1}; },
       {"node 1", "both matrix"}},
      {"NODE_MATRIX_NON_TRS", [](json& d) { d["nodes"][0]["matrix"] = {1, 0, 0, 1, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}; },
       {"node 0", "not a TRS matrix"}},
      {"ROTATION_NON_UNIT", [](json& d) { d["nodes"][0]["rotation"] = {0, 0, 0.5, 0.5}; }, {"node 0", "unit quaternion"}},
      {"IMAGE_MIME_TYPE_INVALID", [](json& d) { d["images"][0]["mimeType"] = "image/jpeg"; }, {"image 0", "mimeType"}},
      {"CAMERA_ZFAR_LEQUAL_ZNEAR", [](json& d) { d["cameras"][0]["perspective"]["zfar"] = 0.05; }, {"camera 0", "zfar"}},
      {"VALUE_NOT_IN_RANGE (light)", [](json& d) { d["extensions"]["KHR_lights_punctual"]["lights"][0]["color"] = {2, 0, 0}; },
       {"light 0", "color"}},
  };
  ASSERT_NO_THROW(loadText(validDocument()));
  for (const Case& c : cases) {
    SCOPED_TRACE(c.validatorClass);
    json doc = validDocument();
    c.edit(doc);
    try {
      loadText(doc);
      ADD_FAILURE() << "accepted";
    } catch (const SceneError& e) {
      EXPECT_EQ(e.message.rfind("rules.gltf: ", 0), 0u) << e.message;
      for (const std::string& w : c.words) EXPECT_NE(e.message.find(w), std::string::npos) << "'" << w << "' not in: " << e.message;
    }
  }
}

TEST(GltfRules, UndeclaredExtensionsGblensDoesNotDrawOnlyWarn) {
  json doc = validDocument();
  doc["materials"][0]["extensions"] = {{"EXT_made_up", json::object()}};
  const Scene s = loadText(doc);
  ASSERT_EQ(s.warnings.size(), 1u);
  EXPECT_NE(s.warnings[0].find("EXT_made_up is used but not declared"), std::string::npos) << s.warnings[0];
}

}  // namespace
}  // namespace gb
