// A scene on the CPU: meshes, materials, textures, instances, cameras, sun, point lights.
// Filled by the built-in temple or the glTF loader; drawn by the renderer and ray cast by the reference.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "renderer/core/camera.h"
#include "renderer/core/light_list.h"
#include "renderer/core/lights.h"
#include "renderer/core/vertex.h"

namespace gb {


struct Texture {
  std::string name;
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> rgba8;  // width*height*4 bytes
  bool srgb = true;            // base colour: sRGB; normal maps: linear
  bool repeat = true;          // wrap mode (false: clamp to edge)
};

enum class AlphaMode : uint32_t { Opaque = 0, Mask = 1, Blend = 2 };  // = kAlpha* in shaders/shared.h

struct MaterialDesc {
  std::string name;
  glm::vec4 baseColor{1.0f};  // linear
  float specular = 0.5f;      // Blinn-Phong intensity stored in albedo_specular.w
  int baseColorTexture = -1;  // index into Scene::textures
  int baseColorUv = 0;        // texCoord set
  int normalTexture = -1;
  int normalUv = 0;
  float normalScale = 1.0f;
  AlphaMode alphaMode = AlphaMode::Opaque;
  float alphaCutoff = 0.5f;
  bool doubleSided = false;
  // KHR_materials_unlit: the base colour is the surface's colour, no light or shadow changes it
  // (the G-buffer stores no normal for it: see encodeUnlit in shaders/gbuffer_codec.glsl).
  bool unlit = false;
  glm::mat3 baseUvTransform{1.0f};  // KHR_texture_transform (applied as uv' = M * (uv, 1))
  glm::mat3 normalUvTransform{1.0f};
};

// A run of triangles (indexed, TRIANGLE_LIST) with one material: a glTF primitive.
struct Mesh {
  std::string name;
  uint32_t firstIndex = 0;
  uint32_t indexCount = 0;
  uint32_t firstVertex = 0;  // indices are relative to this vertex
  uint32_t vertexCount = 0;
  int material = 0;
  glm::vec3 boundsMin{0.0f}, boundsMax{0.0f};  // object space
};

// One placement of a mesh. Transforms are double so a scene far from the origin stays exact
// until the camera-relative eyeFromObject is formed (also in double).
struct Instance {
  uint32_t mesh = 0;
  glm::dmat4 worldFromObject{1.0};
  bool castsShadow = true;
};

struct Bounds {
  glm::dvec3 min{1e300}, max{-1e300};
  bool empty() const { return min.x > max.x; }
  void add(const glm::dvec3& p) {
    min = glm::min(min, p);
    max = glm::max(max, p);
  }
  glm::dvec3 center() const { return (min + max) * 0.5; }
  double radius() const { return empty() ? 0.0 : glm::length(max - min) * 0.5; }
};

struct Scene {
  std::string source;  // "builtin:temple" or the file path
  std::vector<Vertex> vertices;
  std::vector<uint32_t> indices;
  std::vector<Mesh> meshes;
  std::vector<MaterialDesc> materials;  // at least one
  std::vector<Texture> textures;
  std::vector<Instance> instances;
  std::vector<CameraDesc> cameras;  // [0] is the default view
  Sun sun;
  Sky sky;
  LightList lights;  // every non-const access changes lights.generation() (light_list.h)
  bool generatedLights = false;  // lights come from --lights N (regenerated when N changes)
  Bounds bounds;                 // world space, of all instances
  std::vector<std::string> warnings;
};

// Recomputes Scene::bounds and each Mesh's object-space bounds.
void computeBounds(Scene& scene);

// Fills scene.lights with `count` deterministic lights orbiting over the scene bounds
// (used by the built-in scene and by files without lights).
void generateLights(Scene& scene, int count);

// A camera framing the bounds (files without cameras).
CameraDesc autoCamera(const Bounds& bounds);

// The primitive_id of each instance's first triangle (instance order, 1-based: 0 means no
// geometry). Triangle t of instance i has primitive_id firstPrimitiveIds(scene)[i] + t.
std::vector<uint32_t> firstPrimitiveIds(const Scene& scene);

// The sun's orthographic shadow-map clip space, fitted to the scene's bounding sphere (stable as
// the camera moves).
glm::dmat4 shadowClipFromWorld(const Scene& scene);

// SHA-256 over what was loaded: geometry, materials, textures, instances, cameras, sun, sky
// (not the point lights: captures hash them apart, in lights.json).
std::string sceneContentSha256(const Scene& scene);

// Triangle count over all instances (what is drawn).
uint64_t drawnTriangles(const Scene& scene);

}  // namespace gb
