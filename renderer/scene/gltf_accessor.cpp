// Accessor reading: any component type, strided or packed views, normalized integers decoded as
// the spec (and KHR_mesh_quantization) say, sparse substitution. Ranges were checked by
// validateDocument; values (NaN/Inf, sparse index order) are checked here as they are read.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

int componentCount(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    case TINYGLTF_TYPE_MAT2: return 4;
    case TINYGLTF_TYPE_MAT3: return 9;
    case TINYGLTF_TYPE_MAT4: return 16;
    default: return 0;
  }
}

int componentBytes(int componentType) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

size_t accessorStride(const Doc& doc, const tinygltf::Accessor& a) {
  size_t element = size_t(componentCount(a.type)) * size_t(componentBytes(a.componentType));
  if (a.bufferView < 0) return element;
  size_t stride = doc.model.bufferViews[size_t(a.bufferView)].byteStride;
  return stride ? stride : element;
}

namespace {

const char* typeName(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return "SCALAR";
    case TINYGLTF_TYPE_VEC2: return "VEC2";
    case TINYGLTF_TYPE_VEC3: return "VEC3";
    case TINYGLTF_TYPE_VEC4: return "VEC4";
    default: return "a matrix";
  }
}

const uint8_t* viewData(const Doc& doc, int view, size_t offset) {
  const tinygltf::BufferView& v = doc.model.bufferViews[size_t(view)];
  return doc.model.buffers[size_t(v.buffer)].data.data() + v.byteOffset + offset;
}

// One component, converted: floats as stored, integers as values or (normalized) per the spec:
// signed c/max clamped at -1, unsigned c/max.
template <class In, class Out>
Out convert(const uint8_t* p, bool normalized) {
  In v;
  std::memcpy(&v, p, sizeof(In));
  if constexpr (std::is_same_v<Out, float>) {
    if constexpr (std::is_integral_v<In>) {
      if (normalized) {
        float f = float(v) / float(std::numeric_limits<In>::max());
        return std::is_signed_v<In> ? std::max(f, -1.0f) : f;
      }
    }
    return float(v);
  } else {
    return Out(v);
  }
}

template <class In, class Out>
void gatherTyped(const uint8_t* base, size_t count, size_t stride, int components, bool normalized, Out* out) {
  for (size_t i = 0; i < count; ++i) {
    const uint8_t* p = base + i * stride;
    for (int c = 0; c < components; ++c) out[i * size_t(components) + size_t(c)] = convert<In, Out>(p + c * sizeof(In), normalized);
  }
}

template <class Out>
void gather(int componentType, const uint8_t* base, size_t count, size_t stride, int components, bool normalized,
            Out* out) {
  switch (componentType) {
    case TINYGLTF_COMPONENT_TYPE_BYTE: return gatherTyped<int8_t>(base, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return gatherTyped<uint8_t>(base, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_SHORT: return gatherTyped<int16_t>(base, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return gatherTyped<uint16_t>(base, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: return gatherTyped<uint32_t>(base, count, stride, components, normalized, out);
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return gatherTyped<float>(base, count, stride, components, normalized, out);
    default: break;
  }
}

template <class Out>
std::vector<Out> read(const Doc& doc, int index, int components, const std::string& what) {
  const tinygltf::Accessor& a = doc.model.accessors[size_t(index)];
  const std::string el = what + " (" + named("accessor", size_t(index), a.name) + ")";
  if (componentCount(a.type) != components)
    fail(doc, el, std::string("is ") + typeName(a.type) + ", expected " +
                      (components == 1 ? "SCALAR" : "VEC" + std::to_string(components)));
  std::vector<Out> out(a.count * size_t(components), Out(0));  // no bufferView: zeros (spec)
  if (a.bufferView >= 0)
    gather(a.componentType, viewData(doc, a.bufferView, a.byteOffset), a.count, accessorStride(doc, a), components,
           a.normalized, out.data());
  if (a.sparse.isSparse) {
    const auto& s = a.sparse;
    const size_t n = size_t(s.count);
    std::vector<uint32_t> at(n);
    size_t indexBytes = size_t(componentBytes(s.indices.componentType));
    gather(s.indices.componentType, viewData(doc, s.indices.bufferView, size_t(s.indices.byteOffset)), n, indexBytes, 1,
           false, at.data());
    std::vector<Out> values(n * size_t(components));
    size_t elementBytes = size_t(components) * size_t(componentBytes(a.componentType));
    gather(a.componentType, viewData(doc, s.values.bufferView, size_t(s.values.byteOffset)), n, elementBytes,
           components, a.normalized, values.data());
    for (size_t k = 0; k < n; ++k) {
      if (at[k] >= a.count)
        fail(doc, el, "sparse index " + std::to_string(at[k]) + " is out of range (count " + std::to_string(a.count) + ")");
      if (k > 0 && at[k] <= at[k - 1]) fail(doc, el, "sparse indices are not strictly increasing");
      std::memcpy(&out[size_t(at[k]) * size_t(components)], &values[k * size_t(components)], sizeof(Out) * size_t(components));
    }
  }
  if constexpr (std::is_same_v<Out, float>) {
    if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT)
      for (size_t i = 0; i < out.size(); ++i)
        if (!std::isfinite(out[i]))
          fail(doc, el, "element " + std::to_string(i / size_t(components)) + " holds NaN or Inf");
  }
  return out;
}

}  // namespace

std::vector<float> readFloats(const Doc& doc, int accessor, int components, const std::string& what) {
  return read<float>(doc, accessor, components, what);
}

std::vector<uint32_t> readIndices(const Doc& doc, int accessor, const std::string& what) {
  const tinygltf::Accessor& a = doc.model.accessors[size_t(accessor)];
  if (a.componentType == TINYGLTF_COMPONENT_TYPE_FLOAT || a.componentType == TINYGLTF_COMPONENT_TYPE_BYTE ||
      a.componentType == TINYGLTF_COMPONENT_TYPE_SHORT)
    fail(doc, what + " (" + named("accessor", size_t(accessor), a.name) + ")", "indices must be unsigned integers");
  return read<uint32_t>(doc, accessor, 1, what);
}

}  // namespace gb::gltf
