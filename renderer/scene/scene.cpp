// Scene helpers: bounds, light animation and generation, automatic camera.
#include "renderer/scene/scene.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/core/sha256.h"

namespace gb {

void computeBounds(Scene& scene) {
  for (Mesh& m : scene.meshes) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (uint32_t i = 0; i < m.indexCount; ++i) {
      const glm::vec3& p = scene.vertices[m.firstVertex + scene.indices[m.firstIndex + i]].position;
      lo = glm::min(lo, p);
      hi = glm::max(hi, p);
    }
    m.boundsMin = lo;
    m.boundsMax = hi;
  }
  scene.bounds = Bounds{};
  for (const Instance& inst : scene.instances) {
    const Mesh& m = scene.meshes[inst.mesh];
    if (m.indexCount == 0) continue;
    for (int c = 0; c < 8; ++c) {
      glm::dvec3 corner((c & 1) ? m.boundsMax.x : m.boundsMin.x, (c & 2) ? m.boundsMax.y : m.boundsMin.y,
                        (c & 4) ? m.boundsMax.z : m.boundsMin.z);
      scene.bounds.add(glm::dvec3(inst.worldFromObject * glm::dvec4(corner, 1.0)));
    }
  }
}

// splitmix64: a tiny deterministic generator, identical on every machine.
static uint64_t mix(uint64_t x) {
  x += 0x9E3779B97F4A7C15ull;
  x = (x ^ (x >> 30)) * 0xBF58476D1CE4E5B9ull;
  x = (x ^ (x >> 27)) * 0x94D049BB133111EBull;
  return x ^ (x >> 31);
}
static double unit(uint64_t seed, int k) { return double(mix(seed * 8 + k) >> 11) * (1.0 / 9007199254740992.0); }

static glm::vec3 hueColor(double h) {
  glm::dvec3 c = glm::clamp(glm::abs(glm::mod(h * 6.0 + glm::dvec3(0, 4, 2), 6.0) - 3.0) - 1.0, 0.0, 1.0);
  return glm::vec3(glm::mix(glm::dvec3(1.0), c, 0.9));
}

void generateLights(Scene& scene, int count) {
  scene.lights.clear();
  scene.generatedLights = true;
  if (count <= 0 || scene.bounds.empty()) return;
  const Bounds& b = scene.bounds;
  glm::dvec3 extent = b.max - b.min;
  double horizontal = 0.5 * std::max(extent.x, extent.z);
  double size = b.radius();
  for (int i = 0; i < count; ++i) {
    PointLightDesc l;
    l.center = glm::dvec3(b.center().x, b.min.y, b.center().z);
    l.orbitRadius = horizontal * (0.08 + 0.62 * std::sqrt(unit(i, 0)));
    l.center.y += 0.03 * size + extent.y * 0.25 * unit(i, 1);
    l.phase = 6.283185307179586 * unit(i, 2);
    l.orbitSpeed = (unit(i, 3) < 0.5 ? -1.0 : 1.0) * (0.15 + 0.35 * unit(i, 4));
    l.bob = 0.01 * size * unit(i, 5);
    l.radius = size * (0.04 + 0.04 * unit(i, 6));
    l.color = hueColor(unit(i, 7));
    l.intensity = 1.4;
    scene.lights.push_back(l);
  }
}

CameraDesc autoCamera(const Bounds& b) {
  CameraDesc c;
  c.name = "auto";
  double r = std::max(b.radius(), 1e-6);
  c.yfov = 0.8;
  double distance = r / std::sin(c.yfov * 0.5) * 1.05;
  glm::dvec3 dir = glm::normalize(glm::dvec3(0.45, 0.45, 1.0));
  glm::dvec3 eye = b.center() + dir * distance;
  c.worldFromEye = lookAt(eye, b.center());
  c.znear = std::max(distance - r * 1.5, distance * 1e-3);
  c.znear = std::min(c.znear, (distance - r) * 0.9);
  if (c.znear <= 0.0) c.znear = distance * 1e-3;
  c.zfar = distance + r * 1.5;
  return c;
}

std::vector<uint32_t> firstPrimitiveIds(const Scene& scene) {
  std::vector<uint32_t> first(scene.instances.size());
  uint32_t next = 1;
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    first[i] = next;
    next += scene.meshes[scene.instances[i].mesh].indexCount / 3;
  }
  return first;
}

uint64_t drawnTriangles(const Scene& scene) {
  uint64_t n = 0;
  for (const Instance& i : scene.instances) n += scene.meshes[i.mesh].indexCount / 3;
  return n;
}

glm::dmat4 shadowClipFromWorld(const Scene& s) {
  glm::dvec3 centre = s.bounds.center();
  double radius = std::max(s.bounds.radius(), 1e-6);
  glm::dvec3 up = std::abs(s.sun.toSun.y) > 0.99 ? glm::dvec3(1, 0, 0) : glm::dvec3(0, 1, 0);
  glm::dmat4 lightFromWorld = glm::inverse(lookAt(centre + s.sun.toSun * (2.0 * radius), centre, up));
  double n = 0.5 * radius, f = 3.5 * radius;
  glm::dmat4 clipFromLight(1.0);
  clipFromLight[0][0] = 1.0 / radius;
  // Clip y points down, as in the camera's projection: the same counter-clockwise front faces
  // then face the sun, so back-face culling keeps the sun-facing casters. (With y up the winding
  // was mirrored: only faces turned away from the sun were stored, open single-sided casters
  // cast no shadow and closed ones leaked light at contacts.)
  clipFromLight[1][1] = -1.0 / radius;
  clipFromLight[2][2] = -1.0 / (f - n);
  clipFromLight[3][2] = -n / (f - n);
  return clipFromLight * lightFromWorld;
}


std::string sceneContentSha256(const Scene& s) {
  Sha256 h;
  h.addString("gblens-scene-v1");
  h.addValue(uint64_t(s.vertices.size()));
  h.add(s.vertices.data(), s.vertices.size() * sizeof(Vertex));
  h.addValue(uint64_t(s.indices.size()));
  h.add(s.indices.data(), s.indices.size() * sizeof(uint32_t));
  for (const Mesh& m : s.meshes) {
    h.addValue(m.firstIndex), h.addValue(m.indexCount), h.addValue(m.firstVertex), h.addValue(m.material);
  }
  for (const MaterialDesc& m : s.materials) {
    h.addValue(m.baseColor), h.addValue(m.specular), h.addValue(m.baseColorTexture), h.addValue(m.baseColorUv);
    h.addValue(m.normalTexture), h.addValue(m.normalUv), h.addValue(m.normalScale), h.addValue(m.alphaMode);
    h.addValue(m.alphaCutoff), h.addValue(m.doubleSided), h.addValue(m.baseUvTransform), h.addValue(m.normalUvTransform);
  }
  for (const Texture& t : s.textures) {
    h.addValue(t.width), h.addValue(t.height), h.addValue(t.srgb), h.addValue(t.repeat);
    h.add(t.rgba8.data(), t.rgba8.size());
  }
  for (const Instance& i : s.instances) h.addValue(i.mesh), h.addValue(i.worldFromObject), h.addValue(i.castsShadow);
  for (const CameraDesc& c : s.cameras) {
    h.addValue(c.worldFromEye), h.addValue(c.yfov), h.addValue(c.aspect), h.addValue(c.znear), h.addValue(c.zfar);
  }
  h.addValue(s.sun.enabled), h.addValue(s.sun.toSun), h.addValue(s.sun.color);
  h.addValue(s.sky.zenith), h.addValue(s.sky.horizon), h.addValue(s.sky.ground), h.addValue(s.sky.ambient);
  return h.hex();
}

}  // namespace gb
