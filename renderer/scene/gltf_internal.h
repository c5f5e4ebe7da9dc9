// Inside the glTF loader: the parsed document, the limits, and the steps loadGltf runs in order
// (parse -> validate -> decode images -> geometry -> materials -> nodes/cameras/lights).
#pragma once
// tinygltf is configured the same way in every file that includes it (its class layout and
// inline defaults depend on these): no stb, no default file system (see tinygltf_impl.cpp).
#define TINYGLTF_NO_STB_IMAGE
#define TINYGLTF_NO_STB_IMAGE_WRITE
#define TINYGLTF_NO_FS
#include <tiny_gltf.h>
#include <nlohmann/json.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/scene/builtin.h"
#include "renderer/scene/scene.h"

namespace gb::gltf {

// Sizes beyond these are refused before anything is allocated for them. They are far above
// what a debugging session needs and below what a GPU of this class (or lavapipe) can hold.
// The fuzzer builds with smaller ones (GBLENS_FUZZING) so that it spends its time on structure,
// not on allocating and filling a gigabyte of zeros that a 1 kB file may legally ask for.
#ifndef GBLENS_FUZZING
constexpr uint64_t kMaxFileBytes = 1ull << 31;       // a .gltf/.glb/.bin/image file
constexpr uint64_t kMaxVertices = 1ull << 24;        // 16.7M vertices (940 MB as gb::Vertex)
constexpr uint64_t kMaxIndices = 1ull << 26;         // 67M indices (22M triangles)
constexpr uint64_t kMaxAccessorElements = 1ull << 26;
constexpr uint64_t kMaxInstances = 1ull << 20;       // mesh primitives placed by nodes
constexpr uint32_t kMaxTextureSide = 16384;          // maxImageDimension2D of common devices
constexpr uint64_t kMaxTexels = 1ull << 28;          // all decoded textures together (1 GB RGBA8)
#else
constexpr uint64_t kMaxFileBytes = 1ull << 24;
constexpr uint64_t kMaxVertices = 1ull << 16;
constexpr uint64_t kMaxIndices = 1ull << 18;
constexpr uint64_t kMaxAccessorElements = 1ull << 18;
constexpr uint64_t kMaxInstances = 1ull << 12;
constexpr uint32_t kMaxTextureSide = 1024;
constexpr uint64_t kMaxTexels = 1ull << 20;
#endif
constexpr int kMaxJsonDepth = 64;                    // nesting of the JSON document

// The document being loaded and what every step needs to report.
struct Doc {
  std::string file;  // as given by the user: the prefix of every message
  tinygltf::Model model;
  nlohmann::json json;  // the document's JSON as written (the schema step reads it; tinygltf drops mistyped values)
  Scene* scene = nullptr;
  SceneLoadStats* stats = nullptr;
  std::vector<std::vector<uint32_t>> meshPrimitives;  // glTF mesh -> Scene meshes (drawn primitives)
  int defaultMaterial = -1;  // Scene material for primitives without one (added when first needed)
  std::vector<int> dracoPlaceholders;  // accessors given a buffer view only for tinygltf (gltf_draco.cpp)
};

// Throws SceneError "<file>: <element>: <what>".
[[noreturn]] void fail(const Doc& doc, const std::string& element, const std::string& what);
void warn(const Doc& doc, const std::string& message);    // Scene::warnings (printed by the CLI)
void ignored(const Doc& doc, const std::string& feature);  // SceneLoadStats::ignored (gblens info)

// "accessor 3 ('positions')": how messages name an element.
std::string named(const char* kind, size_t index, const std::string& name);

// ---- parse (gltf_parse.cpp): bytes -> tinygltf::Model; version and required extensions ----
void parseDocument(Doc& doc, const uint8_t* data, size_t size, const std::string& baseDir);

// ---- schema (gltf_schema.cpp): the types, ranges, allowed values and required properties of the
// parts gblens draws, and extensions used without being declared. `parsed`: tinygltf read the
// document (else this runs to name what tinygltf refused: every element counts as drawn) ----
void checkSchema(const Doc& doc, const nlohmann::json& j, bool parsed = true);

// ---- KHR_draco_mesh_compression (gltf_draco.cpp): compressed primitives decoded into ordinary
// buffers, views and accessors, before validation ----
void decodeDraco(Doc& doc);
// Before tinygltf parses: when a Draco primitive's index accessor has no buffer view (as the
// extension says), fills `copy` with the document whose such accessors name the bitstream's view,
// records them in Doc::dracoPlaceholders and returns true.
bool prepareDracoIndices(Doc& doc, bool glb, const uint8_t* data, size_t size, std::vector<uint8_t>& copy);

// ---- validate (gltf_validate.cpp): every index and byte range, node graph, sizes ----
void validateDocument(const Doc& doc);

// ---- data rules (gltf_data_rules.cpp): the validator's data classes for the drawn parts (unit
// normals, tangent signs, POSITION bounds, restart indices, UV sets, formats, view targets, node
// matrices, MIME types); after validation ----
void checkDataRules(const Doc& doc);

// ---- parts gblens does not draw (gltf_unrendered.cpp): errors there are warnings ----
// What the drawn parts read: accessors of mesh primitives' indices and drawn attributes, and the
// buffer views of those accessors and of images (1 = read when drawing).
struct DrawnData {
  std::vector<char> accessors, bufferViews;
};
DrawnData drawnData(const Doc& doc);
bool drawnAttribute(const std::string& name);  // POSITION, NORMAL, TANGENT, TEXCOORD_0, TEXCOORD_1
// Animations, skins, morph targets and unread vertex attributes: a warning per error, naming it.
void checkUnrenderedParts(const Doc& doc);

// ---- accessors (gltf_accessor.cpp) ----
int componentCount(int type);       // SCALAR 1 ... MAT4 16; 0 when unknown
int componentBytes(int componentType);  // 0 when unknown
// Bytes between elements in the accessor's buffer view (its byteStride or the element size).
size_t accessorStride(const Doc& doc, const tinygltf::Accessor& a);
// The accessor's elements as floats, `components` per element (normalized integers decoded per the
// spec, sparse substitution applied). Non-finite floats are rejected, naming `what`.
std::vector<float> readFloats(const Doc& doc, int accessor, int components, const std::string& what);
// Index data (unsigned byte/short/int scalars), sparse substitution applied.
std::vector<uint32_t> readIndices(const Doc& doc, int accessor, const std::string& what);

// ---- images (gltf_image.cpp): encoded bytes -> RGBA8 through OpenImageIO, in parallel ----
struct DecodedImage {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba8;
};
// Decodes the images whose `needed` flag is set; the others stay empty.
std::vector<DecodedImage> decodeImages(const Doc& doc, const std::vector<bool>& needed);

// ---- materials (gltf_material.cpp) ----
// Which images the materials sample (base colour, normal, metallic-roughness).
std::vector<bool> imagesNeeded(const Doc& doc);
void buildMaterials(Doc& doc, std::vector<DecodedImage>& images);

// ---- geometry (gltf_geometry.cpp): primitives -> Scene meshes (after buildMaterials) ----
void buildGeometry(Doc& doc);

// ---- nodes (gltf_nodes.cpp): instances, cameras, lights, bounds ----
void buildNodes(Doc& doc, int lightCount);

// ---- small helpers over tinygltf::Value (whose Get() asserts on the wrong type) ----
const tinygltf::Value* member(const tinygltf::Value& object, const char* key);
bool number(const tinygltf::Value* v, double& out);  // finite numbers only
const tinygltf::Value* extension(const tinygltf::ExtensionMap& extensions, const char* name);
// An index glTF stores as int, valid for an array of SIZE elements.
inline bool inRange(int index, size_t size) { return index >= 0 && size_t(index) < size; }

}  // namespace gb::gltf
