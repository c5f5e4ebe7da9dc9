// Validate step: every index the document holds points at something that exists, every byte
// range lies inside its buffer, the node graph is a forest, and the numbers that place things are
// finite. tinygltf checks little of this; after this step the builders can index without checks.
#include <cmath>

#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {

using tinygltf::Model;


// offset + length <= limit without overflow.
bool fits(uint64_t offset, uint64_t length, uint64_t limit) { return offset <= limit && length <= limit - offset; }

void checkBufferView(const Doc& doc, size_t i) {
  const Model& m = doc.model;
  const tinygltf::BufferView& v = m.bufferViews[i];
  std::string el = named("bufferView", i, v.name);
  if (!inRange(v.buffer, m.buffers.size())) fail(doc, el, "buffer " + std::to_string(v.buffer) + " does not exist");
  uint64_t size = m.buffers[size_t(v.buffer)].data.size();
  if (!fits(v.byteOffset, v.byteLength, size))
    fail(doc, el, "byteOffset " + std::to_string(v.byteOffset) + " + byteLength " + std::to_string(v.byteLength) +
                      " runs past the end of buffer " + std::to_string(v.buffer) + " (" + std::to_string(size) +
                      " bytes)");
  if (v.byteStride != 0 && v.byteStride < 4) fail(doc, el, "byteStride " + std::to_string(v.byteStride) + " < 4");
}

// Runs a check of element i: an error in an element the drawn parts read is refused; in one only
// the parts gblens does not draw read (animations, skins, morph targets...), it is a warning.
template <class Check>
void checkEach(const Doc& doc, size_t count, const std::vector<char>& drawn, Check check) {
  for (size_t i = 0; i < count; ++i) {
    if (drawn[i]) {
      check(doc, i);
      continue;
    }
    try {
      check(doc, i);
    } catch (const SceneError& e) {
      const std::string prefix = doc.file + ": ";
      std::string what = e.message.rfind(prefix, 0) == 0 ? e.message.substr(prefix.size()) : e.message;
      warn(doc, what + " (not read by anything gblens draws: ignored)");
    }
  }
}

bool validComponentType(int t) {
  return t == TINYGLTF_COMPONENT_TYPE_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
         t == TINYGLTF_COMPONENT_TYPE_SHORT || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT || t == TINYGLTF_COMPONENT_TYPE_FLOAT;
}

bool indexComponentType(int t) {
  return t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE || t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT ||
         t == TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT;
}

// `count` elements of `elementBytes`, `stride` apart, from `offset` in buffer view `view`.
void checkRange(const Doc& doc, const std::string& el, int view, uint64_t offset, uint64_t count, uint64_t stride,
                uint64_t elementBytes) {
  const Model& m = doc.model;
  if (!inRange(view, m.bufferViews.size())) fail(doc, el, "bufferView " + std::to_string(view) + " does not exist");
  uint64_t length = m.bufferViews[size_t(view)].byteLength;
  uint64_t span = (count - 1) * stride + elementBytes;  // count <= kMaxAccessorElements, stride <= 252: no overflow
  if (!fits(offset, span, length))
    fail(doc, el, "byteOffset " + std::to_string(offset) + " + " + std::to_string(count) + " elements (" +
                      std::to_string(span) + " bytes) runs past the end of bufferView " + std::to_string(view) + " (" +
                      std::to_string(length) + " bytes)");
}

void checkAccessor(const Doc& doc, size_t i) {
  const Model& m = doc.model;
  const tinygltf::Accessor& a = m.accessors[i];
  std::string el = named("accessor", i, a.name);
  if (!validComponentType(a.componentType))
    fail(doc, el, "componentType " + std::to_string(a.componentType) + " is not a glTF 2.0 component type");
  if (componentCount(a.type) == 0) fail(doc, el, "unknown type");
  if (a.count == 0) fail(doc, el, "count is 0");
  if (a.count > kMaxAccessorElements)
    fail(doc, el, "count " + std::to_string(a.count) + " is absurd (more than " + std::to_string(kMaxAccessorElements) +
                      " elements)");
  uint64_t elementBytes = uint64_t(componentCount(a.type)) * uint64_t(componentBytes(a.componentType));
  if (a.bufferView >= 0) {
    if (!inRange(a.bufferView, m.bufferViews.size()))
      fail(doc, el, "bufferView " + std::to_string(a.bufferView) + " does not exist");
    size_t stride = m.bufferViews[size_t(a.bufferView)].byteStride;
    if (stride != 0 && stride < elementBytes)
      fail(doc, el, "byteStride " + std::to_string(stride) + " of bufferView " + std::to_string(a.bufferView) +
                        " is smaller than an element (" + std::to_string(elementBytes) + " bytes)");
    checkRange(doc, el, a.bufferView, a.byteOffset, a.count, stride ? stride : elementBytes, elementBytes);
  } else if (a.bufferView != -1) {
    fail(doc, el, "bufferView " + std::to_string(a.bufferView) + " does not exist");
  }
  if (!a.sparse.isSparse) return;
  const auto& s = a.sparse;
  if (s.count < 1 || uint64_t(s.count) > a.count)
    fail(doc, el, "sparse.count " + std::to_string(s.count) + " is not in 1.." + std::to_string(a.count));
  if (!indexComponentType(s.indices.componentType))
    fail(doc, el, "sparse.indices.componentType " + std::to_string(s.indices.componentType) + " is not unsigned");
  if (s.indices.byteOffset < 0 || s.values.byteOffset < 0) fail(doc, el, "negative sparse byteOffset");
  uint64_t indexBytes = uint64_t(componentBytes(s.indices.componentType));
  checkRange(doc, el + " sparse.indices", s.indices.bufferView, uint64_t(s.indices.byteOffset), uint64_t(s.count),
             indexBytes, indexBytes);
  checkRange(doc, el + " sparse.values", s.values.bufferView, uint64_t(s.values.byteOffset), uint64_t(s.count),
             elementBytes, elementBytes);
}

void checkMeshes(const Doc& doc) {
  const Model& m = doc.model;
  for (size_t i = 0; i < m.meshes.size(); ++i) {
    const tinygltf::Mesh& mesh = m.meshes[i];
    for (size_t p = 0; p < mesh.primitives.size(); ++p) {
      const tinygltf::Primitive& prim = mesh.primitives[p];
      std::string el = named("mesh", i, mesh.name) + " primitive " + std::to_string(p);
      // Attributes gblens does not read and morph targets: gltf_unrendered.cpp (warnings).
      for (const auto& [name, accessor] : prim.attributes)
        if (drawnAttribute(name) && !inRange(accessor, m.accessors.size()))
          fail(doc, el, "attribute " + name + " uses accessor " + std::to_string(accessor) + ", which does not exist");
      if (prim.indices != -1) {
        if (!inRange(prim.indices, m.accessors.size()))
          fail(doc, el, "indices accessor " + std::to_string(prim.indices) + " does not exist");
        const tinygltf::Accessor& a = m.accessors[size_t(prim.indices)];
        if (a.type != TINYGLTF_TYPE_SCALAR || !indexComponentType(a.componentType))
          fail(doc, el, "indices accessor " + std::to_string(prim.indices) + " is not unsigned byte/short/int SCALAR");
      }
      if (prim.material != -1 && !inRange(prim.material, m.materials.size()))
        fail(doc, el, "material " + std::to_string(prim.material) + " does not exist");
      if (prim.mode < 0 || prim.mode > 6) fail(doc, el, "mode " + std::to_string(prim.mode) + " is not a glTF mode");
    }
  }
}

void checkTextureRef(const Doc& doc, const std::string& el, const char* slot, int texture, int texCoord) {
  if (texture == -1) return;
  if (!inRange(texture, doc.model.textures.size()))
    fail(doc, el, std::string(slot) + " texture " + std::to_string(texture) + " does not exist");
  if (texCoord < 0) fail(doc, el, std::string(slot) + " texCoord " + std::to_string(texCoord) + " is negative");
}

void checkMaterials(const Doc& doc) {
  const Model& m = doc.model;
  for (size_t i = 0; i < m.images.size(); ++i) {
    const tinygltf::Image& img = m.images[i];
    std::string el = named("image", i, img.name);
    if (img.bufferView >= 0) {
      if (!inRange(img.bufferView, m.bufferViews.size()))
        fail(doc, el, "bufferView " + std::to_string(img.bufferView) + " does not exist");
    } else if (img.image.empty()) {
      fail(doc, el, img.uri.empty() ? "no image data" : "file '" + img.uri + "' not found or empty");
    }
  }
  for (size_t i = 0; i < m.textures.size(); ++i) {
    const tinygltf::Texture& t = m.textures[i];
    std::string el = named("texture", i, t.name);
    if (t.source != -1 && !inRange(t.source, m.images.size()))
      fail(doc, el, "source image " + std::to_string(t.source) + " does not exist");
    if (t.sampler != -1 && !inRange(t.sampler, m.samplers.size()))
      fail(doc, el, "sampler " + std::to_string(t.sampler) + " does not exist");
  }
  for (size_t i = 0; i < m.materials.size(); ++i) {
    const tinygltf::Material& mat = m.materials[i];
    const auto& pbr = mat.pbrMetallicRoughness;
    std::string el = named("material", i, mat.name);
    checkTextureRef(doc, el, "baseColor", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord);
    checkTextureRef(doc, el, "metallicRoughness", pbr.metallicRoughnessTexture.index,
                    pbr.metallicRoughnessTexture.texCoord);
    checkTextureRef(doc, el, "normal", mat.normalTexture.index, mat.normalTexture.texCoord);
    checkTextureRef(doc, el, "occlusion", mat.occlusionTexture.index, mat.occlusionTexture.texCoord);
    checkTextureRef(doc, el, "emissive", mat.emissiveTexture.index, mat.emissiveTexture.texCoord);
    if (mat.alphaMode != "OPAQUE" && mat.alphaMode != "MASK" && mat.alphaMode != "BLEND")
      fail(doc, el, "alphaMode \"" + mat.alphaMode + "\" is not OPAQUE, MASK or BLEND");
    if (pbr.baseColorFactor.size() != 4) fail(doc, el, "baseColorFactor needs 4 numbers");
    for (double f : pbr.baseColorFactor)
      if (!std::isfinite(f)) fail(doc, el, "baseColorFactor is not finite");
    if (!std::isfinite(mat.alphaCutoff) || mat.alphaCutoff < 0.0) fail(doc, el, "alphaCutoff must be >= 0");
  }
}

void checkCamerasAndLights(const Doc& doc) {
  const Model& m = doc.model;
  for (size_t i = 0; i < m.cameras.size(); ++i) {
    const tinygltf::Camera& c = m.cameras[i];
    std::string el = named("camera", i, c.name);
    if (c.type == "perspective") {
      const auto& p = c.perspective;
      if (!(p.yfov > 0.0 && p.yfov < 3.14159)) fail(doc, el, "yfov must be in (0, pi)");
      if (!(p.znear > 0.0 && std::isfinite(p.znear))) fail(doc, el, "znear must be > 0");
      if (p.zfar != 0.0 && !(p.zfar > p.znear && std::isfinite(p.zfar))) fail(doc, el, "zfar must be > znear");
      if (!(p.aspectRatio >= 0.0 && std::isfinite(p.aspectRatio))) fail(doc, el, "aspectRatio must be > 0");
    } else if (c.type == "orthographic") {
      const auto& o = c.orthographic;
      if (!(std::isfinite(o.xmag) && std::isfinite(o.ymag) && o.xmag != 0.0 && o.ymag != 0.0))
        fail(doc, el, "xmag and ymag must be finite and non-zero");
      if (!(o.znear >= 0.0 && o.zfar > o.znear && std::isfinite(o.zfar))) fail(doc, el, "needs 0 <= znear < zfar");
    } else {
      fail(doc, el, "type \"" + c.type + "\" is not perspective or orthographic");
    }
  }
  for (size_t i = 0; i < m.lights.size(); ++i) {
    const tinygltf::Light& l = m.lights[i];
    std::string el = "KHR_lights_punctual " + named("light", i, l.name);
    if (l.type != "point" && l.type != "spot" && l.type != "directional")
      fail(doc, el, "type \"" + l.type + "\" is not point, spot or directional");
    if (!(l.intensity >= 0.0 && std::isfinite(l.intensity))) fail(doc, el, "intensity must be finite and >= 0");
    if (!l.color.empty() && l.color.size() != 3) fail(doc, el, "color needs 3 numbers");
    for (double c : l.color)
      if (!(c >= 0.0 && std::isfinite(c))) fail(doc, el, "color must be finite and >= 0");
    if (!(l.range >= 0.0 && std::isfinite(l.range))) fail(doc, el, "range must be > 0");
  }
}

void checkTransform(const Doc& doc, const std::string& el, const tinygltf::Node& n) {
  auto finite = [&](const std::vector<double>& v, size_t size, const char* what) {
    if (!v.empty() && v.size() != size)
      fail(doc, el, std::string(what) + " needs " + std::to_string(size) + " numbers, has " + std::to_string(v.size()));
    for (double d : v)
      if (!std::isfinite(d)) fail(doc, el, std::string(what) + " holds NaN or Inf");
  };
  finite(n.matrix, 16, "matrix");
  finite(n.translation, 3, "translation");
  finite(n.rotation, 4, "rotation");
  finite(n.scale, 3, "scale");
}

// The nodes must form a forest: every child exists, no node has two parents, no node is its own
// ancestor (a cycle would hang or blow up a naive traversal), and the scene's roots are roots.
void checkNodes(const Doc& doc) {
  const Model& m = doc.model;
  const size_t n = m.nodes.size();
  std::vector<int> parent(n, -1);
  for (size_t i = 0; i < n; ++i) {
    const tinygltf::Node& node = m.nodes[i];
    std::string el = named("node", i, node.name);
    if (node.mesh != -1 && !inRange(node.mesh, m.meshes.size()))
      fail(doc, el, "mesh " + std::to_string(node.mesh) + " does not exist");
    if (node.camera != -1 && !inRange(node.camera, m.cameras.size()))
      fail(doc, el, "camera " + std::to_string(node.camera) + " does not exist");
    if (const tinygltf::Value* ext = extension(node.extensions, "KHR_lights_punctual")) {
      const tinygltf::Value* light = member(*ext, "light");
      if (!light || !light->IsInt() || !inRange(light->GetNumberAsInt(), m.lights.size()))
        fail(doc, el, "KHR_lights_punctual.light does not name an existing light");
    }
    checkTransform(doc, el, node);
    for (int child : node.children) {
      if (!inRange(child, n)) fail(doc, el, "child " + std::to_string(child) + " does not exist");
      if (size_t(child) == i) fail(doc, el, "is its own child (node cycle)");
      if (parent[size_t(child)] != -1)
        fail(doc, named("node", size_t(child), m.nodes[size_t(child)].name),
             "has two parents (nodes " + std::to_string(parent[size_t(child)]) + " and " + std::to_string(i) +
                 "): glTF nodes form trees");
      parent[size_t(child)] = int(i);
    }
  }
  // With one parent each, a node that no root reaches lies on (or under) a cycle.
  std::vector<char> reached(n, 0);
  std::vector<size_t> stack;
  for (size_t i = 0; i < n; ++i)
    if (parent[i] == -1) stack.push_back(i);
  while (!stack.empty()) {
    size_t i = stack.back();
    stack.pop_back();
    reached[i] = 1;
    for (int c : m.nodes[i].children) stack.push_back(size_t(c));
  }
  for (size_t i = 0; i < n; ++i)
    if (!reached[i]) fail(doc, named("node", i, m.nodes[i].name), "is part of a node cycle (its ancestors loop back to it)");

  for (size_t s = 0; s < m.scenes.size(); ++s) {
    std::string el = named("scene", s, m.scenes[s].name);
    std::vector<char> listed(n, 0);
    for (int root : m.scenes[s].nodes) {
      if (!inRange(root, n)) fail(doc, el, "node " + std::to_string(root) + " does not exist");
      if (parent[size_t(root)] != -1)
        fail(doc, el, "lists node " + std::to_string(root) + " as a root, but it is a child of node " +
                          std::to_string(parent[size_t(root)]));
      if (listed[size_t(root)]) fail(doc, el, "lists node " + std::to_string(root) + " twice");
      listed[size_t(root)] = 1;
    }
  }
  if (m.defaultScene != -1 && !inRange(m.defaultScene, m.scenes.size()))
    fail(doc, "scene", std::to_string(m.defaultScene) + " does not exist (" + std::to_string(m.scenes.size()) +
                           " scenes)");
}

}  // namespace

void validateDocument(const Doc& doc) {
  const DrawnData drawn = drawnData(doc);
  checkEach(doc, doc.model.bufferViews.size(), drawn.bufferViews, checkBufferView);
  checkEach(doc, doc.model.accessors.size(), drawn.accessors, checkAccessor);
  checkMeshes(doc);
  checkMaterials(doc);
  checkCamerasAndLights(doc);
  checkNodes(doc);
}

}  // namespace gb::gltf
