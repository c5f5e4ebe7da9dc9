// A scene on the CPU: meshes, materials, textures, instances, cameras, sun, point lights.
// Filled by the built-in temple or the glTF loader; drawn by the renderer and ray cast by the reference.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gb {

struct Vertex {
  glm::vec3 position{0.0f};  // object space
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec2 uv0{0.0f};
  glm::vec2 uv1{0.0f};
  glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w bitangent sign
};

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

struct CameraDesc {
  std::string name;
  glm::dmat4 worldFromEye{1.0};  // eye looks down -Z, +Y up (glTF convention)
  double yfov = 0.8;             // radians
  double aspect = 0.0;           // 0: from the output size
  double znear = 0.1, zfar = 100.0;
};

struct Sun {
  bool enabled = true;
  glm::dvec3 toSun{0.3, 0.8, 0.5};  // world space, unit vector toward the sun
  glm::vec3 color{3.0f, 2.8f, 2.5f};  // radiance (rgb * intensity)
};

struct Sky {
  glm::vec3 zenith{0.20f, 0.38f, 0.85f};
  glm::vec3 horizon{0.75f, 0.82f, 0.95f};
  glm::vec3 ground{0.30f, 0.27f, 0.24f};
  glm::vec3 ambient{0.10f, 0.11f, 0.14f};  // ambient light on geometry
};

// A point light. Generated lights orbit `center` (orbitRadius > 0); file lights are static.
struct PointLightDesc {
  glm::dvec3 center{0.0};
  double orbitRadius = 0.0;
  double orbitSpeed = 0.0;  // radians per second
  double phase = 0.0;
  double bob = 0.0;         // vertical amplitude
  double radius = 1.0;      // attenuation reaches exactly zero here
  glm::vec3 color{1.0f};
  double intensity = 1.0;
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
  std::vector<PointLightDesc> lights;
  bool generatedLights = false;  // lights come from --lights N (regenerated when N changes)
  Bounds bounds;                 // world space, of all instances
  std::vector<std::string> warnings;
};

// World-space position of a light at animation time `time` (seconds).
glm::dvec3 lightPosition(const PointLightDesc& light, double time);

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

// Triangle count over all instances (what is drawn).
uint64_t drawnTriangles(const Scene& scene);

}  // namespace gb
