// The parts of a glTF file gblens does not draw: animations, skins, morph targets, and vertex
// attributes other than POSITION, NORMAL, TANGENT, TEXCOORD_0/1 (colours, joints, weights...).
// An error in one of them is a warning naming the part and saying it is ignored, never a refusal:
// the file still draws what gblens draws. An error in a part gblens draws is refused
// (gltf_validate.cpp). Which accessors and buffer views the drawn parts read decides which rule
// applies to them.
#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {


void warnIgnored(const Doc& doc, const std::string& part, const std::string& what, const char* kind) {
  warn(doc, part + ": " + what + " (" + kind + " are not drawn: ignored)");
}

void checkAnimations(const Doc& doc) {
  const tinygltf::Model& m = doc.model;
  for (size_t i = 0; i < m.animations.size(); ++i) {
    const tinygltf::Animation& a = m.animations[i];
    const std::string el = named("animation", i, a.name);
    for (size_t s = 0; s < a.samplers.size(); ++s) {
      const tinygltf::AnimationSampler& sampler = a.samplers[s];
      const std::string part = el + " sampler " + std::to_string(s);
      if (!inRange(sampler.input, m.accessors.size()))
        warnIgnored(doc, part, "input accessor " + std::to_string(sampler.input) + " does not exist", "animations");
      if (!inRange(sampler.output, m.accessors.size()))
        warnIgnored(doc, part, "output accessor " + std::to_string(sampler.output) + " does not exist", "animations");
    }
    for (size_t c = 0; c < a.channels.size(); ++c) {
      const tinygltf::AnimationChannel& ch = a.channels[c];
      const std::string part = el + " channel " + std::to_string(c);
      if (!inRange(ch.sampler, a.samplers.size()))
        warnIgnored(doc, part, "sampler " + std::to_string(ch.sampler) + " does not exist", "animations");
      if (ch.target_node != -1 && !inRange(ch.target_node, m.nodes.size()))
        warnIgnored(doc, part, "target node " + std::to_string(ch.target_node) + " does not exist", "animations");
      if (ch.target_path != "translation" && ch.target_path != "rotation" && ch.target_path != "scale" &&
          ch.target_path != "weights" && ch.target_path != "pointer")
        warnIgnored(doc, part, "target path \"" + ch.target_path + "\" is not a glTF path", "animations");
    }
  }
}

void checkSkins(const Doc& doc) {
  const tinygltf::Model& m = doc.model;
  for (size_t i = 0; i < m.skins.size(); ++i) {
    const tinygltf::Skin& s = m.skins[i];
    const std::string el = named("skin", i, s.name);
    if (s.joints.empty()) warnIgnored(doc, el, "has no joints", "skins");
    for (int j : s.joints)
      if (!inRange(j, m.nodes.size())) warnIgnored(doc, el, "joint node " + std::to_string(j) + " does not exist", "skins");
    if (s.skeleton != -1 && !inRange(s.skeleton, m.nodes.size()))
      warnIgnored(doc, el, "skeleton node " + std::to_string(s.skeleton) + " does not exist", "skins");
    if (s.inverseBindMatrices != -1) {
      if (!inRange(s.inverseBindMatrices, m.accessors.size())) {
        warnIgnored(doc, el, "inverseBindMatrices accessor " + std::to_string(s.inverseBindMatrices) + " does not exist",
                    "skins");
      } else {
        const tinygltf::Accessor& a = m.accessors[size_t(s.inverseBindMatrices)];
        if (a.type != TINYGLTF_TYPE_MAT4 || a.componentType != TINYGLTF_COMPONENT_TYPE_FLOAT)
          warnIgnored(doc, el, "inverseBindMatrices accessor is not float MAT4", "skins");
        else if (a.count < s.joints.size())
          warnIgnored(doc, el, "inverseBindMatrices has " + std::to_string(a.count) + " matrices for " +
                                   std::to_string(s.joints.size()) + " joints", "skins");
      }
    }
  }
  for (size_t i = 0; i < m.nodes.size(); ++i)
    if (m.nodes[i].skin != -1 && !inRange(m.nodes[i].skin, m.skins.size()))
      warnIgnored(doc, named("node", i, m.nodes[i].name), "skin " + std::to_string(m.nodes[i].skin) + " does not exist",
                  "skins");
}

// Morph targets and the attributes gblens does not read: their accessors must exist and match
// POSITION's count to be usable, but gblens uses neither.
void checkPrimitiveParts(const Doc& doc) {
  const tinygltf::Model& m = doc.model;
  for (size_t i = 0; i < m.meshes.size(); ++i)
    for (size_t p = 0; p < m.meshes[i].primitives.size(); ++p) {
      const tinygltf::Primitive& prim = m.meshes[i].primitives[p];
      const std::string el = named("mesh", i, m.meshes[i].name) + " primitive " + std::to_string(p);
      auto position = prim.attributes.find("POSITION");
      const size_t count = position != prim.attributes.end() && inRange(position->second, m.accessors.size())
                               ? m.accessors[size_t(position->second)].count
                               : 0;
      auto check = [&](const std::string& part, int accessor, const char* kind) {
        if (!inRange(accessor, m.accessors.size()))
          warnIgnored(doc, el, part + " uses accessor " + std::to_string(accessor) + ", which does not exist", kind);
        else if (count && m.accessors[size_t(accessor)].count != count)
          warnIgnored(doc, el, part + " has " + std::to_string(m.accessors[size_t(accessor)].count) +
                                   " elements, POSITION has " + std::to_string(count), kind);
      };
      for (size_t t = 0; t < prim.targets.size(); ++t)
        for (const auto& [name, accessor] : prim.targets[t])
          check("morph target " + std::to_string(t) + " " + name, accessor, "morph targets");
      for (const auto& [name, accessor] : prim.attributes)
        if (!drawnAttribute(name))
          check("attribute " + name, accessor,
                name.rfind("JOINTS_", 0) == 0 || name.rfind("WEIGHTS_", 0) == 0 ? "skins" : "these attributes");
    }
}

}  // namespace

bool drawnAttribute(const std::string& name) {
  return name == "POSITION" || name == "NORMAL" || name == "TANGENT" || name == "TEXCOORD_0" || name == "TEXCOORD_1";
}

DrawnData drawnData(const Doc& doc) {
  const tinygltf::Model& m = doc.model;
  DrawnData d;
  d.accessors.assign(m.accessors.size(), 0);
  d.bufferViews.assign(m.bufferViews.size(), 0);
  auto accessor = [&](int a) {
    if (inRange(a, m.accessors.size())) d.accessors[size_t(a)] = 1;
  };
  for (const tinygltf::Mesh& mesh : m.meshes)
    for (const tinygltf::Primitive& prim : mesh.primitives) {
      accessor(prim.indices);
      for (const auto& [name, a] : prim.attributes)
        if (drawnAttribute(name)) accessor(a);
    }
  auto view = [&](int v) {
    if (inRange(v, m.bufferViews.size())) d.bufferViews[size_t(v)] = 1;
  };
  for (size_t a = 0; a < m.accessors.size(); ++a) {
    if (!d.accessors[a]) continue;
    view(m.accessors[a].bufferView);
    if (m.accessors[a].sparse.isSparse) {
      view(m.accessors[a].sparse.indices.bufferView);
      view(m.accessors[a].sparse.values.bufferView);
    }
  }
  for (const tinygltf::Image& img : m.images) view(img.bufferView);
  return d;
}

void checkUnrenderedParts(const Doc& doc) {
  checkAnimations(doc);
  checkSkins(doc);
  checkPrimitiveParts(doc);
}

}  // namespace gb::gltf
