// KHR_draco_mesh_compression through Debian's libdraco: each compressed primitive's bitstream is
// decoded before validation into a new buffer, buffer views and accessors (float attributes, u32
// indices), and the primitive is pointed at them. From then on it is an ordinary primitive: the
// validate, geometry and node steps read it exactly as an uncompressed one.
#include <draco/compression/decode.h>

#include <cmath>
#include <cstring>

#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {

const char kDraco[] = "KHR_draco_mesh_compression";

// Appends `bytes` as a buffer view of a new buffer and an accessor over it; returns the accessor.
int addAccessor(Doc& doc, std::vector<unsigned char> bytes, const tinygltf::Accessor& like, int componentType,
                size_t count) {
  tinygltf::Model& m = doc.model;
  tinygltf::Buffer buffer;
  buffer.name = "KHR_draco_mesh_compression (decoded)";
  buffer.data = std::move(bytes);
  m.buffers.push_back(std::move(buffer));
  tinygltf::BufferView view;
  view.buffer = int(m.buffers.size() - 1);
  view.byteLength = m.buffers.back().data.size();
  m.bufferViews.push_back(view);
  tinygltf::Accessor a;
  a.name = like.name;
  a.bufferView = int(m.bufferViews.size() - 1);
  a.componentType = componentType;
  a.type = like.type;
  a.count = count;
  a.minValues = like.minValues;
  a.maxValues = like.maxValues;
  m.accessors.push_back(a);
  return int(m.accessors.size() - 1);
}

void decodePrimitive(Doc& doc, tinygltf::Primitive& prim, const tinygltf::Value& ext, const std::string& el) {
  tinygltf::Model& m = doc.model;
  const tinygltf::Value* viewValue = member(ext, "bufferView");
  const tinygltf::Value* attributes = member(ext, "attributes");
  if (!viewValue || !viewValue->IsInt() || !inRange(viewValue->GetNumberAsInt(), m.bufferViews.size()))
    fail(doc, el, std::string(kDraco) + ".bufferView does not name an existing buffer view");
  if (!attributes || !attributes->IsObject()) fail(doc, el, std::string(kDraco) + ".attributes: expected an object");
  const tinygltf::BufferView& view = m.bufferViews[size_t(viewValue->GetNumberAsInt())];
  if (!inRange(view.buffer, m.buffers.size()) || view.byteOffset > m.buffers[size_t(view.buffer)].data.size() ||
      view.byteLength > m.buffers[size_t(view.buffer)].data.size() - view.byteOffset)
    fail(doc, el, std::string(kDraco) + ": its buffer view runs past its buffer");

  draco::DecoderBuffer bytes;
  bytes.Init(reinterpret_cast<const char*>(m.buffers[size_t(view.buffer)].data.data() + view.byteOffset),
             view.byteLength);
  draco::Decoder decoder;
  auto decoded = decoder.DecodeMeshFromBuffer(&bytes);
  if (!decoded.ok()) fail(doc, el, std::string(kDraco) + ": cannot decode (" + decoded.status().error_msg_string() + ")");
  const std::unique_ptr<draco::Mesh> mesh = std::move(decoded).value();
  const size_t points = mesh->num_points(), faces = mesh->num_faces();
  if (points > kMaxVertices || faces * 3 > kMaxIndices)
    fail(doc, el, std::string(kDraco) + ": " + std::to_string(points) + " points, " + std::to_string(faces) +
                      " faces: more than gblens loads");
  if (prim.mode != TINYGLTF_MODE_TRIANGLES) fail(doc, el, std::string(kDraco) + ": only TRIANGLES primitives are decoded");

  // Indices: the faces' points, in order (the spec: the indices accessor describes them).
  if (prim.indices != -1) {
    if (!inRange(prim.indices, m.accessors.size())) fail(doc, el, "indices accessor does not exist");
    std::vector<unsigned char> data(faces * 3 * 4);
    for (size_t f = 0; f < faces; ++f) {
      const draco::Mesh::Face& face = mesh->face(draco::FaceIndex(uint32_t(f)));
      for (int k = 0; k < 3; ++k) {
        const uint32_t index = face[size_t(k)].value();
        std::memcpy(&data[(f * 3 + size_t(k)) * 4], &index, 4);
      }
    }
    const tinygltf::Accessor like = m.accessors[size_t(prim.indices)];
    prim.indices = addAccessor(doc, std::move(data), like, TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT, faces * 3);
  } else if (faces) {
    fail(doc, el, std::string(kDraco) + ": a compressed triangle mesh needs an indices accessor");
  }

  // Attributes: each glTF attribute names a Draco attribute by its unique id; decoded to floats
  // (normalized integers per their Draco attribute's normalized flag), one value per point.
  for (const std::string& name : attributes->Keys()) {
    auto it = prim.attributes.find(name);
    const tinygltf::Value& id = attributes->Get(name);
    if (it == prim.attributes.end() || !inRange(it->second, m.accessors.size()))
      fail(doc, el, std::string(kDraco) + ".attributes." + name + ": the primitive has no such attribute accessor");
    const draco::PointAttribute* att =
        id.IsInt() && id.GetNumberAsInt() >= 0 ? mesh->GetAttributeByUniqueId(uint32_t(id.GetNumberAsInt())) : nullptr;
    if (!att) fail(doc, el, std::string(kDraco) + ".attributes." + name + ": no Draco attribute of that id");
    const tinygltf::Accessor like = m.accessors[size_t(it->second)];
    const int components = componentCount(like.type);
    if (components == 0 || att->num_components() != components)
      fail(doc, el, std::string(kDraco) + ".attributes." + name + ": the Draco attribute has " +
                        std::to_string(att->num_components()) + " components, the accessor " + std::to_string(components));
    std::vector<unsigned char> data(points * size_t(components) * 4);
    float value[16];
    for (size_t p = 0; p < points; ++p) {
      if (!att->ConvertValue<float>(att->mapped_index(draco::PointIndex(uint32_t(p))), int8_t(components), value))
        fail(doc, el, std::string(kDraco) + ".attributes." + name + ": a value does not convert to float");
      std::memcpy(&data[p * size_t(components) * 4], value, size_t(components) * 4);
    }
    it->second = addAccessor(doc, std::move(data), like, TINYGLTF_COMPONENT_TYPE_FLOAT, points);
  }
  prim.extensions.erase(kDraco);
}

}  // namespace

bool prepareDracoIndices(Doc& doc, bool glb, const uint8_t* data, size_t size, std::vector<uint8_t>& copy) {
  nlohmann::json& j = doc.json;
  if (!j.is_object() || !j.contains("meshes") || !j["meshes"].is_array() || !j.contains("accessors") ||
      !j["accessors"].is_array())
    return false;
  nlohmann::json edited = j;
  nlohmann::json& accessors = edited["accessors"];
  for (const nlohmann::json& mesh : j["meshes"]) {
    if (!mesh.is_object() || !mesh.contains("primitives") || !mesh["primitives"].is_array()) continue;
    for (const nlohmann::json& prim : mesh["primitives"]) {
      if (!prim.is_object() || !prim.contains("extensions") || !prim["extensions"].is_object()) continue;
      auto ext = prim["extensions"].find(kDraco);
      if (ext == prim["extensions"].end() || !ext->is_object() || !ext->contains("bufferView") || !prim.contains("indices"))
        continue;
      const nlohmann::json& index = prim["indices"];
      if (!index.is_number_unsigned() || index.get<uint64_t>() >= accessors.size()) continue;
      nlohmann::json& a = accessors[size_t(index.get<uint64_t>())];
      if (!a.is_object() || a.contains("bufferView")) continue;
      a["bufferView"] = (*ext)["bufferView"];
      doc.dracoPlaceholders.push_back(int(index.get<uint64_t>()));
    }
  }
  if (doc.dracoPlaceholders.empty()) return false;
  const std::string text = edited.dump();
  if (!glb) {
    copy.assign(text.begin(), text.end());
    return true;
  }
  // GLB: header, the new JSON chunk (padded with spaces to 4 bytes), then the chunks after the old one.
  uint32_t oldLength = 0;
  std::memcpy(&oldLength, data + 12, 4);
  const size_t rest = 20 + size_t(oldLength);
  std::string chunk = text;
  chunk.resize((chunk.size() + 3) / 4 * 4, ' ');
  const uint32_t chunkLength = uint32_t(chunk.size()), total = uint32_t(12 + 8 + chunk.size() + (size - rest));
  copy.assign(data, data + 12);
  std::memcpy(copy.data() + 8, &total, 4);
  copy.insert(copy.end(), reinterpret_cast<const uint8_t*>(&chunkLength), reinterpret_cast<const uint8_t*>(&chunkLength) + 4);
  copy.insert(copy.end(), data + 16, data + 20);  // "JSON"
  copy.insert(copy.end(), chunk.begin(), chunk.end());
  copy.insert(copy.end(), data + rest, data + size);
  return true;
}

void decodeDraco(Doc& doc) {
  // The placeholders back as written (the decoded accessors replace them in the primitives).
  for (int a : doc.dracoPlaceholders)
    if (inRange(a, doc.model.accessors.size())) doc.model.accessors[size_t(a)].bufferView = -1;
  for (size_t i = 0; i < doc.model.meshes.size(); ++i) {
    tinygltf::Mesh& mesh = doc.model.meshes[i];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      tinygltf::Primitive& prim = mesh.primitives[p];
      auto ext = prim.extensions.find(kDraco);
      if (ext == prim.extensions.end()) continue;
      decodePrimitive(doc, prim, ext->second, named("mesh", i, mesh.name) + " primitive " + std::to_string(p));
    }
  }
}

}  // namespace gb::gltf
