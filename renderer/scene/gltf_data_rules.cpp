// The glTF validator's data classes for what gblens draws, after the schema and the index checks:
// unit normals and tangents, tangent handedness, POSITION within its declared bounds, no primitive
// restart index, the UV sets the materials sample, attribute formats, buffer-view targets, offset
// alignment, interleaved views with a stride, node matrices, unit rotations and image MIME types.
// Each error names the element; docs/gltf.md lists the classes and the rule for each.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <map>

#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {

using tinygltf::Model;

// How far from 1 a unit vector's length may be: the validator's threshold for floats; a
// normalized integer's rounding for quantized ones (KHR_mesh_quantization).
double unitTolerance(const tinygltf::Accessor& a) {
  switch (a.componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 2.0 * std::sqrt(3.0) / 127.0;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2.0 * std::sqrt(3.0) / 32767.0;
    default: return 1e-3;
  }
}

bool declared(const Doc& doc, const char* extension) {
  const auto& u = doc.model.extensionsUsed;
  return std::find(u.begin(), u.end(), extension) != u.end();
}

// ACCESSOR_NON_UNIT, ACCESSOR_INVALID_SIGN: NORMAL and TANGENT.xyz of unit length, TANGENT.w +-1.
void checkUnit(const Doc& doc, const std::string& el, const char* name, int accessor) {
  const tinygltf::Accessor& a = doc.model.accessors[size_t(accessor)];
  const bool tangent = std::strcmp(name, "TANGENT") == 0;
  const int components = tangent ? 4 : 3;
  const std::vector<float> v = readFloats(doc, accessor, components, el + " " + name);
  const double tol = unitTolerance(a);
  for (size_t i = 0; i < a.count; ++i) {
    const float* p = &v[i * size_t(components)];
    const double len = std::sqrt(double(p[0]) * p[0] + double(p[1]) * p[1] + double(p[2]) * p[2]);
    if (std::abs(len - 1.0) > tol)
      fail(doc, el, std::string(name) + " " + std::to_string(i) + " has length " + std::to_string(len) +
                        ", not 1 (" + named("accessor", size_t(accessor), a.name) + ")");
    if (tangent && std::abs(std::abs(double(p[3])) - 1.0) > tol)
      fail(doc, el, "TANGENT " + std::to_string(i) + " has w = " + std::to_string(p[3]) + ", not 1 or -1 (" +
                        named("accessor", size_t(accessor), a.name) + ")");
  }
}

// ACCESSOR_MIN_MISMATCH / ACCESSOR_MAX_MISMATCH for POSITION: data outside the declared bounds is
// refused (the bounds are wrong); bounds missing or wider than the data are a warning (gblens
// computes its own from the data).
void checkBounds(const Doc& doc, const std::string& el, int accessor) {
  const tinygltf::Accessor& a = doc.model.accessors[size_t(accessor)];
  const std::string acc = named("accessor", size_t(accessor), a.name);
  if (a.minValues.size() != 3 || a.maxValues.size() != 3) {
    warn(doc, el + ": POSITION " + acc + " has no min/max (the spec requires them; gblens computes its own)");
    return;
  }
  const std::vector<float> v = readFloats(doc, accessor, 3, el + " POSITION");
  for (int k = 0; k < 3; ++k) {
    float lo = INFINITY, hi = -INFINITY;
    for (size_t i = 0; i < a.count; ++i) lo = std::min(lo, v[i * 3 + size_t(k)]), hi = std::max(hi, v[i * 3 + size_t(k)]);
    // The bounds are written from the float data; a few ulps allow for an exporter's printing
    // and for Draco's dequantization at the ends of the range.
    const double min = a.minValues[size_t(k)], max = a.maxValues[size_t(k)];
    const double slack = 1e-6 * std::max({1.0, std::abs(min), std::abs(max)});
    if (lo < min - slack || hi > max + slack)
      fail(doc, el, "POSITION " + acc + ": the data spans " + std::to_string(lo) + ".." + std::to_string(hi) + " in " +
                        "xyz"[k] + ", outside the declared min/max " + std::to_string(a.minValues[size_t(k)]) + ".." +
                        std::to_string(a.maxValues[size_t(k)]));
  }
}

// MESH_PRIMITIVE_ATTRIBUTES_ACCESSOR_INVALID_FORMAT: POSITION, NORMAL, TANGENT float (or, with
// KHR_mesh_quantization declared, its integer forms); TEXCOORD_n float or normalized u8/u16.
void checkFormat(const Doc& doc, const std::string& el, const std::string& name, const tinygltf::Accessor& a) {
  const bool isFloat = a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool unorm = a.normalized && (a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                                      a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT);
  const bool quantization = declared(doc, "KHR_mesh_quantization");
  bool ok = isFloat;
  if (name.rfind("TEXCOORD_", 0) == 0) ok = isFloat || unorm || quantization;
  else if (name == "POSITION" || name == "NORMAL" || name == "TANGENT") ok = isFloat || quantization;
  if (!ok)
    fail(doc, el, "attribute " + name + ": componentType " + std::to_string(a.componentType) +
                      (a.normalized ? " normalized" : "") + " is not allowed for it (KHR_mesh_quantization not declared)");
}

// ACCESSOR_INDEX_PRIMITIVE_RESTART: the largest value of the index type.
void checkRestart(const Doc& doc, const std::string& el, int accessor) {
  const tinygltf::Accessor& a = doc.model.accessors[size_t(accessor)];
  const uint32_t restart = a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE    ? 0xFFu
                           : a.componentType == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ? 0xFFFFu
                                                                                        : 0xFFFFFFFFu;
  const std::vector<uint32_t> indices = readIndices(doc, accessor, el + " indices");
  for (size_t k = 0; k < indices.size(); ++k)
    if (indices[k] == restart)
      fail(doc, el, "index " + std::to_string(k) + " is " + std::to_string(restart) +
                        ", the primitive restart value (not allowed in glTF)");
}

// MESH_PRIMITIVE_TOO_FEW_TEXCOORDS, MESH_PRIMITIVE_INDEXED_SEMANTIC_CONTINUITY: every UV set the
// material samples exists, and TEXCOORD_n only with TEXCOORD_0..n-1.
void checkTexCoords(const Doc& doc, const std::string& el, const tinygltf::Primitive& prim) {
  for (const auto& [name, unused] : prim.attributes)
    if (name.rfind("TEXCOORD_", 0) == 0) {
      const int n = std::atoi(name.c_str() + 9);
      for (int k = 0; k < n; ++k)
        if (!prim.attributes.count("TEXCOORD_" + std::to_string(k)))
          fail(doc, el, name + " without TEXCOORD_" + std::to_string(k) + " (attribute sets must be contiguous)");
    }
  if (prim.material < 0) return;
  const tinygltf::Material& m = doc.model.materials[size_t(prim.material)];
  const auto& pbr = m.pbrMetallicRoughness;
  auto slot = [&](const char* what, int index, int texCoord, const tinygltf::ExtensionMap& ext) {
    if (index < 0) return;
    double uv = texCoord;
    if (const tinygltf::Value* t = extension(ext, "KHR_texture_transform")) number(member(*t, "texCoord"), uv);
    if (!prim.attributes.count("TEXCOORD_" + std::to_string(int(uv))))
      fail(doc, el, std::string(what) + " texture of " + named("material", size_t(prim.material), m.name) +
                        " samples TEXCOORD_" + std::to_string(int(uv)) + ", which the primitive does not have");
  };
  slot("baseColor", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, pbr.baseColorTexture.extensions);
  slot("metallicRoughness", pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
       pbr.metallicRoughnessTexture.extensions);
  slot("normal", m.normalTexture.index, m.normalTexture.texCoord, m.normalTexture.extensions);
}

// BUFFER_VIEW_TARGET_OVERRIDE, ACCESSOR_TOTAL_OFFSET_ALIGNMENT, BUFFER_VIEW_INVALID_BYTE_STRIDE,
// MESH_PRIMITIVE_ACCESSOR_WITHOUT_BYTESTRIDE for the accessors a primitive reads.
void checkView(const Doc& doc, const std::string& el, int accessor, bool indices,
               std::map<int, int>& attributeViewUsers) {
  const Model& m = doc.model;
  const tinygltf::Accessor& a = m.accessors[size_t(accessor)];
  if (a.bufferView < 0) return;
  const tinygltf::BufferView& v = m.bufferViews[size_t(a.bufferView)];
  const std::string acc = named("accessor", size_t(accessor), a.name);
  // The target as written: tinygltf overwrites it with how the primitives use the view.
  const int want = indices ? TINYGLTF_TARGET_ELEMENT_ARRAY_BUFFER : TINYGLTF_TARGET_ARRAY_BUFFER;
  int target = 0;
  if (doc.json.is_object() && doc.json.contains("bufferViews") && doc.json["bufferViews"].is_array() &&
      size_t(a.bufferView) < doc.json["bufferViews"].size()) {
    const nlohmann::json& written = doc.json["bufferViews"][size_t(a.bufferView)];
    if (written.is_object() && written.contains("target") && written["target"].is_number_integer())
      target = written["target"].get<int>();
  }
  if (target != 0 && target != want)
    fail(doc, el, acc + " reads bufferView " + std::to_string(a.bufferView) + " whose target " + std::to_string(target) +
                      " is for " + (indices ? "vertex attributes" : "indices"));
  const size_t bytes = size_t(componentBytes(a.componentType));
  if (bytes && ((a.byteOffset + v.byteOffset) % bytes != 0 || a.byteOffset % bytes != 0))
    fail(doc, el, acc + ": byteOffset " + std::to_string(a.byteOffset) + " (+ the view's " + std::to_string(v.byteOffset) +
                      ") is not a multiple of its component size " + std::to_string(bytes));
  if (v.byteStride % 4 != 0)
    fail(doc, el, "bufferView " + std::to_string(a.bufferView) + ": byteStride " + std::to_string(v.byteStride) +
                      " is not a multiple of 4");
  if (!indices && v.byteStride == 0 && ++attributeViewUsers[a.bufferView] > 1)
    fail(doc, el, "bufferView " + std::to_string(a.bufferView) + " holds several vertex attributes but has no byteStride");
}

// NODE_MATRIX_NON_TRS, ROTATION_NON_UNIT (NODE_MATRIX_TRS: gltf_schema.cpp, on the JSON).
void checkNode(const Doc& doc, size_t i) {
  const tinygltf::Node& n = doc.model.nodes[i];
  const std::string el = named("node", i, n.name);
  if (n.matrix.size() == 16 && (n.matrix[3] != 0.0 || n.matrix[7] != 0.0 || n.matrix[11] != 0.0 || n.matrix[15] != 1.0))
    fail(doc, el, "matrix is not a TRS matrix (its last row is not 0 0 0 1)");
  if (n.rotation.size() == 4) {
    double len = 0.0;
    for (double q : n.rotation) len += q * q;
    if (!(len > 1e-24)) fail(doc, el, "rotation is a zero quaternion");
    if (std::abs(std::sqrt(len) - 1.0) > 1e-3)
      fail(doc, el, "rotation is not a unit quaternion (length " + std::to_string(std::sqrt(len)) + ")");
  }
}

// IMAGE_MIME_TYPE_INVALID: the bytes are what mimeType says (as written: tinygltf replaces it with
// a data URI's type).
void checkImage(const Doc& doc, size_t i) {
  const tinygltf::Image& img = doc.model.images[i];
  const nlohmann::json* images = doc.json.is_object() && doc.json.contains("images") ? &doc.json["images"] : nullptr;
  if (!images || !images->is_array() || i >= images->size() || !(*images)[i].is_object() ||
      !(*images)[i].contains("mimeType") || !(*images)[i]["mimeType"].is_string())
    return;
  const std::string mimeType = (*images)[i]["mimeType"].get<std::string>();
  const uint8_t* p = img.image.data();
  size_t size = img.image.size();
  if (img.bufferView >= 0) {
    const tinygltf::BufferView& v = doc.model.bufferViews[size_t(img.bufferView)];
    p = doc.model.buffers[size_t(v.buffer)].data.data() + v.byteOffset, size = v.byteLength;
  }
  static const uint8_t png[4] = {0x89, 'P', 'N', 'G'}, jpeg[3] = {0xFF, 0xD8, 0xFF};
  const bool isPng = size >= 4 && std::memcmp(p, png, 4) == 0, isJpeg = size >= 3 && std::memcmp(p, jpeg, 3) == 0;
  if ((mimeType == "image/png" && isJpeg) || (mimeType == "image/jpeg" && isPng))
    fail(doc, named("image", i, img.name), "mimeType " + mimeType + " but the data is " + (isPng ? "a PNG" : "a JPEG"));
}

}  // namespace

void checkDataRules(const Doc& doc) {
  const Model& m = doc.model;
  for (size_t i = 0; i < m.meshes.size(); ++i)
    for (size_t p = 0; p < m.meshes[i].primitives.size(); ++p) {
      const tinygltf::Primitive& prim = m.meshes[i].primitives[p];
      const std::string el = named("mesh", i, m.meshes[i].name) + " primitive " + std::to_string(p);
      std::map<int, int> attributeViewUsers;
      for (const auto& [name, accessor] : prim.attributes) {
        if (!drawnAttribute(name)) continue;
        checkFormat(doc, el, name, m.accessors[size_t(accessor)]);
        checkView(doc, el, accessor, false, attributeViewUsers);
        if (name == "NORMAL" || name == "TANGENT") checkUnit(doc, el, name.c_str(), accessor);
        if (name == "POSITION") checkBounds(doc, el, accessor);
      }
      if (prim.indices >= 0) {
        checkView(doc, el, prim.indices, true, attributeViewUsers);
        checkRestart(doc, el, prim.indices);
      }
      checkTexCoords(doc, el, prim);
    }
  for (size_t i = 0; i < m.nodes.size(); ++i) checkNode(doc, i);
  const std::vector<bool> used = imagesNeeded(doc);
  for (size_t i = 0; i < m.images.size(); ++i)
    if (i < used.size() && used[i]) checkImage(doc, i);
}

}  // namespace gb::gltf
