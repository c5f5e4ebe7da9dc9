// The glTF 2.0 schema's rules for the properties gblens draws, checked on the document's JSON (as
// the Khronos validator does: TYPE_MISMATCH, VALUE_NOT_IN_RANGE, VALUE_NOT_IN_LIST,
// ARRAY_LENGTH_NOT_IN_LIST, UNDEFINED_PROPERTY, INVALID_INDEX, VALUE_MULTIPLE_OF,
// UNDECLARED_EXTENSION). tinygltf skips a property of the wrong type without a word (a
// pbrMetallicRoughness given as an array becomes the default material): here it is refused, naming
// the element and the property. docs/gltf.md lists the classes and the rule for each.
#include <algorithm>
#include <cmath>
#include <set>

#include "renderer/scene/gltf_internal.h"

namespace gb::gltf {

namespace {

using json = nlohmann::json;

enum class Kind { Index, Int, Number, Bool, String, Numbers, Indices, IndexMap, IndexMaps, Object, Objects };

// tinygltf holds indices (and texCoord) in an int: 2^32 would wrap to 0 and name an element that
// exists. No collection holds more than this, so a larger index names none (the validator's
// UNRESOLVED_REFERENCE).
constexpr double kMaxIndex = 2147483647.0;

// One property: its kind, range [lo, hi], allowed values (ints or strings), array lengths, the
// schema of an object (or of each object of an array), whether it is required.
struct Rule {
  const char* key;
  Kind kind;
  double lo = -INFINITY, hi = INFINITY;
  std::vector<double> ints = {};
  std::vector<const char*> strings = {};
  std::vector<size_t> lengths = {};
  const char* schema = nullptr;
  bool required = false;
  double multipleOf = 0.0;
};

struct Schema {
  const char* name;
  std::vector<Rule> rules;
};

const std::vector<Schema>& schemas() {
  static const std::vector<Schema> s = {
      {"accessor",
       {{"bufferView", Kind::Index},
        {"byteOffset", Kind::Int, 0},
        {"componentType", Kind::Int, -INFINITY, INFINITY, {5120, 5121, 5122, 5123, 5125, 5126}, {}, {}, nullptr, true},
        {"normalized", Kind::Bool},
        {"count", Kind::Int, 1, INFINITY, {}, {}, {}, nullptr, true},
        {"type", Kind::String, 0, 0, {}, {"SCALAR", "VEC2", "VEC3", "VEC4", "MAT2", "MAT3", "MAT4"}, {}, nullptr, true},
        {"max", Kind::Numbers, -INFINITY, INFINITY, {}, {}, {1, 2, 3, 4, 9, 16}},
        {"min", Kind::Numbers, -INFINITY, INFINITY, {}, {}, {1, 2, 3, 4, 9, 16}},
        {"sparse", Kind::Object}}},
      {"bufferView",
       {{"buffer", Kind::Index, 0, INFINITY, {}, {}, {}, nullptr, true},
        {"byteOffset", Kind::Int, 0},
        {"byteLength", Kind::Int, 1, INFINITY, {}, {}, {}, nullptr, true},
        {"byteStride", Kind::Int, 4, 252, {}, {}, {}, nullptr, false, 4},
        {"target", Kind::Int, -INFINITY, INFINITY, {34962, 34963}}}},
      {"buffer", {{"uri", Kind::String}, {"byteLength", Kind::Int, 1, INFINITY, {}, {}, {}, nullptr, true}}},
      {"image", {{"uri", Kind::String}, {"mimeType", Kind::String, 0, 0, {}, {"image/jpeg", "image/png"}}, {"bufferView", Kind::Index}}},
      {"texture", {{"sampler", Kind::Index}, {"source", Kind::Index}}},
      {"sampler",
       {{"magFilter", Kind::Int, -INFINITY, INFINITY, {9728, 9729}},
        {"minFilter", Kind::Int, -INFINITY, INFINITY, {9728, 9729, 9984, 9985, 9986, 9987}},
        {"wrapS", Kind::Int, -INFINITY, INFINITY, {33071, 33648, 10497}},
        {"wrapT", Kind::Int, -INFINITY, INFINITY, {33071, 33648, 10497}}}},
      {"material",
       {{"pbrMetallicRoughness", Kind::Object, 0, 0, {}, {}, {}, "pbrMetallicRoughness"},
        {"normalTexture", Kind::Object, 0, 0, {}, {}, {}, "normalTextureInfo"},
        {"occlusionTexture", Kind::Object, 0, 0, {}, {}, {}, "occlusionTextureInfo"},
        {"emissiveTexture", Kind::Object, 0, 0, {}, {}, {}, "textureInfo"},
        {"emissiveFactor", Kind::Numbers, 0, 1, {}, {}, {3}},
        {"alphaMode", Kind::String, 0, 0, {}, {"OPAQUE", "MASK", "BLEND"}},
        {"alphaCutoff", Kind::Number, 0},
        {"doubleSided", Kind::Bool}}},
      {"pbrMetallicRoughness",
       {{"baseColorFactor", Kind::Numbers, 0, 1, {}, {}, {4}},
        {"baseColorTexture", Kind::Object, 0, 0, {}, {}, {}, "textureInfo"},
        {"metallicFactor", Kind::Number, 0, 1},
        {"roughnessFactor", Kind::Number, 0, 1},
        {"metallicRoughnessTexture", Kind::Object, 0, 0, {}, {}, {}, "textureInfo"}}},
      {"textureInfo", {{"index", Kind::Index, 0, INFINITY, {}, {}, {}, nullptr, true}, {"texCoord", Kind::Int, 0, kMaxIndex}}},
      {"normalTextureInfo",
       {{"index", Kind::Index, 0, INFINITY, {}, {}, {}, nullptr, true}, {"texCoord", Kind::Int, 0, kMaxIndex}, {"scale", Kind::Number}}},
      {"occlusionTextureInfo",
       {{"index", Kind::Index, 0, INFINITY, {}, {}, {}, nullptr, true}, {"texCoord", Kind::Int, 0, kMaxIndex}, {"strength", Kind::Number, 0, 1}}},
      {"KHR_texture_transform",
       {{"offset", Kind::Numbers, -INFINITY, INFINITY, {}, {}, {2}},
        {"rotation", Kind::Number},
        {"scale", Kind::Numbers, -INFINITY, INFINITY, {}, {}, {2}},
        {"texCoord", Kind::Int, 0, kMaxIndex}}},
      {"mesh", {{"primitives", Kind::Objects, 0, 0, {}, {}, {}, "primitive", true}, {"weights", Kind::Numbers}}},
      {"primitive",
       {{"attributes", Kind::IndexMap, 0, 0, {}, {}, {}, nullptr, true},
        {"indices", Kind::Index},
        {"material", Kind::Index},
        {"mode", Kind::Int, -INFINITY, INFINITY, {0, 1, 2, 3, 4, 5, 6}},
        {"targets", Kind::IndexMaps}}},
      {"node",
       {{"camera", Kind::Index},
        {"children", Kind::Indices},
        {"skin", Kind::Index},
        {"matrix", Kind::Numbers, -INFINITY, INFINITY, {}, {}, {16}},
        {"mesh", Kind::Index},
        {"rotation", Kind::Numbers, -1, 1, {}, {}, {4}},
        {"scale", Kind::Numbers, -INFINITY, INFINITY, {}, {}, {3}},
        {"translation", Kind::Numbers, -INFINITY, INFINITY, {}, {}, {3}},
        {"weights", Kind::Numbers}}},
      {"scene", {{"nodes", Kind::Indices}}},
      {"camera",
       {{"type", Kind::String, 0, 0, {}, {"perspective", "orthographic"}, {}, nullptr, true},
        {"perspective", Kind::Object, 0, 0, {}, {}, {}, "perspective"},
        {"orthographic", Kind::Object, 0, 0, {}, {}, {}, "orthographic"}}},
      {"perspective",
       {{"aspectRatio", Kind::Number, 1e-300},
        {"yfov", Kind::Number, 1e-300, INFINITY, {}, {}, {}, nullptr, true},
        {"zfar", Kind::Number, 1e-300},
        {"znear", Kind::Number, 1e-300, INFINITY, {}, {}, {}, nullptr, true}}},
      {"orthographic",
       {{"xmag", Kind::Number, -INFINITY, INFINITY, {}, {}, {}, nullptr, true},
        {"ymag", Kind::Number, -INFINITY, INFINITY, {}, {}, {}, nullptr, true},
        {"zfar", Kind::Number, 1e-300, INFINITY, {}, {}, {}, nullptr, true},
        {"znear", Kind::Number, 0, INFINITY, {}, {}, {}, nullptr, true}}},
      // Extensions whose members are indices (checked where the extension sits).
      {"KHR_lights_punctual", {{"light", Kind::Index, 0, INFINITY, {}, {}, {}, nullptr, true}}},
      {"KHR_draco_mesh_compression",
       {{"bufferView", Kind::Index, 0, INFINITY, {}, {}, {}, nullptr, true},
        {"attributes", Kind::IndexMap, 0, 0, {}, {}, {}, nullptr, true}}},
      {"light",
       {{"type", Kind::String, 0, 0, {}, {"point", "spot", "directional"}, {}, nullptr, true},
        {"color", Kind::Numbers, 0, 1, {}, {}, {3}},
        {"intensity", Kind::Number, 0},
        {"range", Kind::Number, 1e-300},
        {"spot", Kind::Object}}},
  };
  return s;
}

const Schema* schemaNamed(const std::string& name) {
  for (const Schema& s : schemas())
    if (name == s.name) return &s;
  return nullptr;
}

// Extensions gblens draws: used without being declared in extensionsUsed, they are refused (the
// file says it needs nothing gblens would then draw); any other undeclared one is a warning.
const char* const kDrawn[] = {"KHR_texture_transform", "KHR_lights_punctual", "KHR_materials_unlit",
                              "KHR_materials_emissive_strength", "KHR_mesh_quantization", "KHR_draco_mesh_compression"};

struct Checker {
  const Doc& doc;
  std::set<std::string> used;
  std::vector<std::pair<std::string, std::string>> problems;  // element, what (the first wins)
  std::vector<std::string> warnings;

  void problem(const std::string& el, const std::string& what) { problems.emplace_back(el, what); }

  std::string brief(const json& v) {
    std::string t = v.dump(-1, ' ', false, json::error_handler_t::replace);
    return t.size() > 40 ? t.substr(0, 37) + "..." : t;
  }

  bool inList(const Rule& r, const json& v) {
    if (!r.ints.empty()) {
      const double d = v.get<double>();
      return std::find(r.ints.begin(), r.ints.end(), d) != r.ints.end();
    }
    if (!r.strings.empty())
      return std::any_of(r.strings.begin(), r.strings.end(), [&](const char* s) { return v.get<std::string>() == s; });
    return true;
  }

  bool integral(const json& v) { return v.is_number_integer() || v.is_number_unsigned(); }

  void unresolved(const std::string& el, const std::string& path, const json& v) {
    problem(el, path + " " + brief(v) + " does not exist (an index beyond any collection)");
  }

  void checkValue(const Rule& r, const json& v, const std::string& el, const std::string& path) {
    auto mismatch = [&](const char* expected) { problem(el, path + ": expected " + expected + ", got " + brief(v)); };
    switch (r.kind) {
      case Kind::Index:
      case Kind::Int:
        if (!integral(v)) return mismatch(r.kind == Kind::Index ? "an index (an integer >= 0)" : "an integer");
        if (r.kind == Kind::Index && v.get<double>() > kMaxIndex) return unresolved(el, path, v);
        if (v.get<double>() < (r.kind == Kind::Index ? 0.0 : r.lo) || v.get<double>() > r.hi)
          return problem(el, path + " " + brief(v) + " is out of range");
        if (!inList(r, v)) return problem(el, path + " " + brief(v) + " is not one of the values glTF allows");
        if (r.multipleOf && std::fmod(v.get<double>(), r.multipleOf) != 0.0)
          return problem(el, path + " " + brief(v) + " is not a multiple of " + std::to_string(int(r.multipleOf)));
        return;
      case Kind::Number:
        if (!v.is_number()) return mismatch("a number");
        if (v.get<double>() < r.lo || v.get<double>() > r.hi) problem(el, path + " " + brief(v) + " is out of range");
        return;
      case Kind::Bool:
        if (!v.is_boolean()) mismatch("true or false");
        return;
      case Kind::String:
        if (!v.is_string()) return mismatch("a string");
        if (!inList(r, v)) problem(el, path + " " + brief(v) + " is not one of the values glTF allows");
        return;
      case Kind::Numbers:
        if (!v.is_array()) return mismatch("an array of numbers");
        if (!r.lengths.empty() && std::find(r.lengths.begin(), r.lengths.end(), v.size()) == r.lengths.end())
          return problem(el, path + ": " + std::to_string(v.size()) + " elements is not a length glTF allows");
        for (const json& e : v)
          if (!e.is_number()) return mismatch("an array of numbers");
          else if (e.get<double>() < r.lo || e.get<double>() > r.hi)
            return problem(el, path + " " + brief(e) + " is out of range");
        return;
      case Kind::Indices:
        if (!v.is_array()) return mismatch("an array of indices");
        for (const json& e : v)
          if (!integral(e) || e.get<double>() < 0) return mismatch("an array of indices");
          else if (e.get<double>() > kMaxIndex) return unresolved(el, path, e);
        return;
      case Kind::IndexMap:  // {"POSITION": 0, ...}: every member an accessor index
        if (!v.is_object()) return mismatch("an object");
        for (auto& [name, e] : v.items())
          if (!integral(e) || e.get<double>() < 0) return problem(el, path + "." + name + ": expected an index, got " + brief(e));
          else if (e.get<double>() > kMaxIndex) return unresolved(el, path + "." + name, e);
        return;
      case Kind::IndexMaps:  // morph targets: an array of such objects
        if (!v.is_array() || v.empty()) return mismatch("a non-empty array of objects");
        for (size_t i = 0; i < v.size(); ++i)
          checkValue({r.key, Kind::IndexMap}, v[i], el, path + "[" + std::to_string(i) + "]");
        return;
      case Kind::Object:
        if (!v.is_object()) return mismatch("an object");
        if (r.schema) checkObject(*schemaNamed(r.schema), v, el, path + ".");
        return;
      case Kind::Objects:
        if (!v.is_array() || v.empty()) return mismatch("a non-empty array of objects");
        for (size_t i = 0; i < v.size(); ++i) {
          // Elements with a schema are named as elements ("mesh 0 primitive 1"); others by path.
          const std::string at = r.schema ? el + " " + r.schema + " " + std::to_string(i) : el;
          const std::string where = r.schema ? "" : path + "[" + std::to_string(i) + "]";
          if (!v[i].is_object()) problem(at, (where.empty() ? "" : where + ": ") + "expected an object, got " + brief(v[i]));
          else if (r.schema) checkObject(*schemaNamed(r.schema), v[i], at, "");
        }
        return;
    }
  }

  void checkObject(const Schema& s, const json& o, const std::string& el, const std::string& prefix) {
    // NODE_MATRIX_TRS: tinygltf keeps one of the two silently.
    if (std::string(s.name) == "node" && o.contains("matrix") &&
        (o.contains("translation") || o.contains("rotation") || o.contains("scale")))
      problem(el, "has both matrix and translation/rotation/scale");
    for (const Rule& r : s.rules) {
      auto it = o.find(r.key);
      if (it == o.end()) {
        if (r.required) problem(el, prefix + r.key + ": missing (required)");
        continue;
      }
      checkValue(r, *it, el, prefix + r.key);
    }
    if (auto ext = o.find("extensions"); ext != o.end()) {
      if (!ext->is_object()) return problem(el, prefix + "extensions: expected an object, got " + brief(*ext));
      // Each extension where it belongs: texture infos, nodes (a light), primitives (Draco).
      const char* own = std::string(s.name) == "node"        ? "KHR_lights_punctual"
                        : std::string(s.name) == "primitive" ? "KHR_draco_mesh_compression"
                                                             : "KHR_texture_transform";
      if (auto t = ext->find(own); t != ext->end()) {
        if (!t->is_object())
          problem(el, prefix + "extensions." + own + ": expected an object, got " + brief(*t));
        else
          checkObject(*schemaNamed(own), *t, el, prefix + "extensions." + own + ".");
      }
    }
  }

  // UNDECLARED_EXTENSION, anywhere in the document (depth is bounded by the parse step).
  void checkExtensionsDeclared(const json& v, const std::string& where) {
    if (v.is_object()) {
      if (auto ext = v.find("extensions"); ext != v.end() && ext->is_object())
        for (auto& item : ext->items()) {
          const std::string& name = item.key();  // (clang-14 cannot capture a structured binding)
          if (used.count(name)) continue;
          const bool drawn = std::any_of(std::begin(kDrawn), std::end(kDrawn), [&](const char* d) { return name == d; });
          const std::string what = "extension " + name + " is used but not declared in extensionsUsed";
          if (drawn)
            problem(where.empty() ? "extensionsUsed" : where, what);
          else
            warnings.push_back((where.empty() ? "" : where + ": ") + what + " (ignored)");
        }
      for (auto& [k, e] : v.items())
        if (k != "extras") checkExtensionsDeclared(e, where.empty() ? k : where + "." + k);
    } else if (v.is_array()) {
      for (size_t i = 0; i < v.size(); ++i) checkExtensionsDeclared(v[i], where + "[" + std::to_string(i) + "]");
    }
  }
};

const char* const kCollections[][2] = {{"accessors", "accessor"}, {"bufferViews", "bufferView"}, {"buffers", "buffer"},
                                       {"images", "image"},       {"textures", "texture"},       {"samplers", "sampler"},
                                       {"materials", "material"}, {"meshes", "mesh"},            {"nodes", "node"},
                                       {"scenes", "scene"},       {"cameras", "camera"}};

}  // namespace

void checkSchema(const Doc& doc, const nlohmann::json& j, bool parsed) {
  if (!j.is_object()) return;  // not JSON: the parse step says so
  Checker c{doc, {}, {}, {}};
  if (auto u = j.find("extensionsUsed"); u != j.end() && u->is_array())
    for (const json& e : *u)
      if (e.is_string()) c.used.insert(e.get<std::string>());
  const DrawnData drawn = drawnData(doc);
  for (const auto& [key, kind] : kCollections) {
    auto it = j.find(key);
    if (it == j.end()) continue;
    if (!it->is_array()) {
      c.problem(key, "expected an array, got " + c.brief(*it));
      continue;
    }
    const std::string k = key;
    for (size_t i = 0; i < it->size(); ++i) {
      const json& o = (*it)[i];
      const std::string el = named(kind, i, o.is_object() && o.contains("name") && o["name"].is_string() ? o["name"].get<std::string>() : "");
      const size_t before = c.problems.size();
      if (!o.is_object())
        c.problem(el, "expected an object, got " + c.brief(o));
      else
        c.checkObject(*schemaNamed(kind), o, el, "");
      // An accessor or buffer view only undrawn parts read (animations, skins): a warning.
      const std::vector<char>* d = k == "accessors" ? &drawn.accessors : k == "bufferViews" ? &drawn.bufferViews : nullptr;
      if (parsed && d && c.problems.size() > before && (i >= d->size() || !(*d)[i])) {
        for (size_t p = before; p < c.problems.size(); ++p)
          c.warnings.push_back(c.problems[p].first + ": " + c.problems[p].second + " (not read by anything gblens draws: ignored)");
        c.problems.resize(before);
      }
    }
  }
  if (auto ext = j.find("extensions"); ext != j.end() && ext->is_object())
    if (auto lights = ext->find("KHR_lights_punctual"); lights != ext->end() && lights->is_object())
      if (auto list = lights->find("lights"); list != lights->end() && list->is_array())
        for (size_t i = 0; i < list->size(); ++i) {
          const std::string el = "KHR_lights_punctual " + named("light", i, "");
          if (!(*list)[i].is_object())
            c.problem(el, "expected an object");
          else
            c.checkObject(*schemaNamed("light"), (*list)[i], el, "");
        }
  c.checkExtensionsDeclared(j, "");
  if (parsed)
    for (const std::string& w : c.warnings) warn(doc, w);
  if (!c.problems.empty()) fail(doc, c.problems[0].first, c.problems[0].second);
}

}  // namespace gb::gltf
