// builtin:temple, a procedural scene in the spirit of the Apple sample's temple: floor, steps, a ring
// of columns with capitals and lintels, spheres and tori, alpha-tested foliage cards, sun and sky.
// Everything is generated from integer hashes, so the same command gives the same pixels.
#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/scene/builtin.h"
#include "renderer/scene/mesh_builder.h"

namespace gb {

static uint32_t hash2(uint32_t x, uint32_t y, uint32_t seed) {
  uint32_t h = x * 0x8da6b343u ^ y * 0xd8163841u ^ seed * 0xcb1ab31fu;
  h ^= h >> 13;
  h *= 0x5bd1e995u;
  return h ^ (h >> 15);
}

// Smooth value noise in [0,1] (bilinear over a hashed lattice), deterministic across machines.
static float valueNoise(float x, float y, uint32_t seed) {
  int xi = int(std::floor(x)), yi = int(std::floor(y));
  float fx = x - float(xi), fy = y - float(yi);
  auto h = [&](int a, int b) { return float(hash2(uint32_t(a), uint32_t(b), seed) & 0xFFFF) / 65535.0f; };
  float sx = fx * fx * (3 - 2 * fx), sy = fy * fy * (3 - 2 * fy);
  float top = h(xi, yi) + (h(xi + 1, yi) - h(xi, yi)) * sx;
  float bottom = h(xi, yi + 1) + (h(xi + 1, yi + 1) - h(xi, yi + 1)) * sx;
  return top + (bottom - top) * sy;
}

static uint8_t toByte(float v) { return uint8_t(std::lround(std::fmin(std::fmax(v, 0.0f), 1.0f) * 255.0f)); }

// Floor tiles: light stone with dark grout and a little veining (sRGB texture, repeat).
static Texture floorTexture() {
  Texture t;
  t.name = "temple_floor";
  t.width = t.height = 256;
  t.rgba8.resize(256 * 256 * 4);
  for (uint32_t y = 0; y < 256; ++y)
    for (uint32_t x = 0; x < 256; ++x) {
      uint32_t tile = (x / 64) + 4 * (y / 64);
      bool grout = (x % 64) < 2 || (y % 64) < 2;
      float n = valueNoise(x / 16.0f, y / 16.0f, 7) * 0.6f + valueNoise(x / 5.0f, y / 5.0f, 9) * 0.4f;
      float tone = 0.78f + 0.08f * float(hash2(tile, 0, 3) & 0xFF) / 255.0f;
      float v = grout ? 0.32f : tone * (0.9f + 0.1f * n);
      uint8_t* p = &t.rgba8[(y * 256 + x) * 4];
      p[0] = toByte(v);
      p[1] = toByte(v * 0.95f);
      p[2] = toByte(v * 0.86f);
      p[3] = 255;
    }
  return t;
}

// Foliage: a fan of leaves in the alpha channel (cut out at 0.5), green shades in colour.
static Texture leafTexture() {
  Texture t;
  t.name = "temple_leaves";
  t.width = t.height = 128;
  t.repeat = false;
  t.rgba8.resize(128 * 128 * 4);
  for (uint32_t y = 0; y < 128; ++y)
    for (uint32_t x = 0; x < 128; ++x) {
      float u = (x + 0.5f) / 128.0f * 2.0f - 1.0f;  // -1..1
      float v = 1.0f - (y + 0.5f) / 128.0f;           // 0 at the bottom, 1 at the top
      float alpha = 0.0f;
      for (int leaf = 0; leaf < 7; ++leaf) {
        float angle = (float(leaf) - 3.0f) * 0.32f;
        // Leaf axis from the stem at (0, 0), rotated by `angle`.
        float ax = std::sin(angle), ay = std::cos(angle);
        float along = u * ax + v * ay, across = -u * ay + v * ax;
        float len = 0.75f + 0.2f * float(hash2(uint32_t(leaf), 1, 5) & 0xFF) / 255.0f;
        float s = along / len;
        if (s > 0.0f && s < 1.0f && std::abs(across) < 0.16f * std::sin(3.14159f * s)) alpha = 1.0f;
      }
      float shade = 0.55f + 0.45f * valueNoise(x / 9.0f, y / 9.0f, 11);
      uint8_t* p = &t.rgba8[(y * 128 + x) * 4];
      p[0] = toByte(0.18f * shade);
      p[1] = toByte(0.55f * shade);
      p[2] = toByte(0.16f * shade);
      p[3] = toByte(alpha);
    }
  return t;
}

static int addMaterial(Scene& s, const char* name, glm::vec3 albedo, float specular, int texture = -1) {
  MaterialDesc m;
  m.name = name;
  m.baseColor = glm::vec4(albedo, 1.0f);
  m.specular = specular;
  m.baseColorTexture = texture;
  s.materials.push_back(m);
  return int(s.materials.size()) - 1;
}

static void place(Scene& s, uint32_t mesh, const glm::dmat4& worldFromObject = glm::dmat4(1.0)) {
  Instance i;
  i.mesh = mesh;
  i.worldFromObject = worldFromObject;
  s.instances.push_back(i);
}

// The temple's materials, by role.
namespace {
struct TempleMaterials {
  int floor, stone, marble, bronze, terracotta, leaves;
};
}  // namespace

// Stone, marble, bronze and terracotta, the tiled floor, and alpha-tested double-sided leaves
// (textures 0 and 1).
static TempleMaterials addMaterials(Scene& s) {
  s.textures.push_back(floorTexture());
  s.textures.push_back(leafTexture());
  TempleMaterials m;
  m.floor = addMaterial(s, "floor", {1.0f, 1.0f, 1.0f}, 0.25f, 0);
  m.stone = addMaterial(s, "stone", {0.80f, 0.76f, 0.68f}, 0.15f);
  m.marble = addMaterial(s, "marble", {0.92f, 0.92f, 0.90f}, 0.6f);
  m.bronze = addMaterial(s, "bronze", {0.70f, 0.45f, 0.20f}, 0.9f);
  m.terracotta = addMaterial(s, "terracotta", {0.75f, 0.35f, 0.22f}, 0.3f);
  m.leaves = addMaterial(s, "leaves", {1.0f, 1.0f, 1.0f}, 0.1f, 1);
  s.materials[m.leaves].alphaMode = AlphaMode::Mask;
  s.materials[m.leaves].alphaCutoff = 0.5f;
  s.materials[m.leaves].doubleSided = true;
  return m;
}

// The platform's top (three steps of 0.3) and the columns' shaft height.
constexpr float kTop = 0.9f, kShaft = 4.6f;

// The floor and the three steps of the platform.
static void addPlatform(Scene& s, MeshBuilder& b, const TempleMaterials& mat) {
  b.begin("floor", mat.floor);
  b.quad({-20, 0, 20}, {40, 0, 0}, {0, 0, -40}, {10, 10});
  b.end();
  place(s, b.meshIndex);

  b.begin("steps", mat.stone);
  for (int i = 0; i < 3; ++i) {
    float h = 0.3f * float(i), half = 8.0f - 1.0f * float(i);
    b.box({-half, h, -half}, {half, h + 0.3f, half}, 0.5f);
  }
  b.end();
  place(s, b.meshIndex);
}

// One column (base, shaft, capital) instanced around a ring (exercises instancing), and the
// lintels joining neighbouring capitals: they cast the long shadows across the platform.
static void addColonnade(Scene& s, MeshBuilder& b, const TempleMaterials& mat) {
  uint32_t column = b.begin("column", mat.marble);
  b.box({-0.55f, 0.0f, -0.55f}, {0.55f, 0.25f, 0.55f});
  b.cylinder({0, 0.25f, 0}, 0.38f, kShaft, 24, false);
  b.box({-0.6f, 0.25f + kShaft, -0.6f}, {0.6f, 0.6f + kShaft, 0.6f});
  b.end();
  const int columns = 12;
  const double ringRadius = 5.5;
  for (int i = 0; i < columns; ++i) {
    double a = 2.0 * 3.141592653589793 * i / columns;
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(std::cos(a) * ringRadius, kTop, std::sin(a) * ringRadius, 1.0);
    place(s, column, m);
  }
  b.begin("lintels", mat.stone);
  for (int i = 0; i < columns; ++i) {
    double a0 = 2.0 * 3.141592653589793 * i / columns, a1 = 2.0 * 3.141592653589793 * (i + 1) / columns;
    glm::vec3 p0(std::cos(a0) * ringRadius, 0, std::sin(a0) * ringRadius);
    glm::vec3 p1(std::cos(a1) * ringRadius, 0, std::sin(a1) * ringRadius);
    glm::vec3 mid = (p0 + p1) * 0.5f, along = glm::normalize(p1 - p0);
    glm::vec3 out = glm::normalize(mid);
    float len = glm::length(p1 - p0) * 0.5f + 0.6f, y0 = kTop + 0.6f + kShaft, y1 = y0 + 0.55f;
    glm::vec3 A = mid - along * len - out * 0.5f, B = mid + along * len - out * 0.5f;
    glm::vec3 C = mid + along * len + out * 0.5f, D = mid - along * len + out * 0.5f;
    glm::vec3 up(0, y1 - y0, 0), lift(0, y0, 0);
    b.quad(D + lift, A - D, up);  // four sides, each counter-clockwise seen from outside
    b.quad(A + lift, B - A, up);
    b.quad(B + lift, C - B, up);
    b.quad(C + lift, D - C, up);
    b.quad(A + lift + up, B - A, D - A);  // top
    b.quad(A + lift, D - A, B - A);       // bottom
  }
  b.end();
  place(s, b.meshIndex);
}

// The bronze orb on its pedestal, two terracotta tori and four marble spheres.
static void addOrnaments(Scene& s, MeshBuilder& b, const TempleMaterials& mat) {
  b.begin("pedestal", mat.stone);
  b.cylinder({0, kTop, 0}, 0.8f, 1.0f, 32);
  b.end();
  place(s, b.meshIndex);
  b.begin("orb", mat.bronze);
  b.sphere({0, kTop + 1.0f + 1.1f, 0}, 1.1f, 48, 24);
  b.end();
  place(s, b.meshIndex);
  b.begin("torus", mat.terracotta);
  b.torus({0, 0, 0}, 0.9f, 0.28f, 48, 16);
  b.end();
  uint32_t torus = b.meshIndex;
  for (int i = 0; i < 2; ++i) {
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(i ? 3.0 : -3.0, kTop + 0.28, 1.5, 1.0);
    place(s, torus, m);
  }
  b.begin("small_sphere", mat.marble);
  b.sphere({0, 0, 0}, 0.45f, 24, 12);
  b.end();
  uint32_t small = b.meshIndex;
  for (int i = 0; i < 4; ++i) {
    double a = 0.8 + 1.5708 * i;
    glm::dmat4 m(1.0);
    m[3] = glm::dvec4(std::cos(a) * 10.5, 0.45, std::sin(a) * 10.5, 1.0);
    place(s, small, m);
  }
}

// Foliage: two crossed double-sided cards per plant, alpha-tested, ten plants around the platform.
static void addFoliage(Scene& s, MeshBuilder& b, const TempleMaterials& mat) {
  uint32_t plant = b.begin("foliage", mat.leaves);
  b.quad({-1.2f, 0, 0}, {2.4f, 0, 0}, {0, 2.4f, 0});
  b.quad({0, 0, 1.2f}, {0, 0, -2.4f}, {0, 2.4f, 0});
  b.end();
  for (int i = 0; i < 10; ++i) {
    double a = 0.3 + 2.0 * 3.141592653589793 * i / 10;
    glm::dmat4 m(1.0);
    m[0] = glm::dvec4(std::cos(a * 3), 0, std::sin(a * 3), 0);
    m[2] = glm::dvec4(-std::sin(a * 3), 0, std::cos(a * 3), 0);
    m[3] = glm::dvec4(std::cos(a) * 12.5, 0.0, std::sin(a) * 12.5, 1.0);
    place(s, plant, m);
  }
}

// The camera, and late evening as the sample's temple: a low warm sun, a dusk sky, and the
// point lights carrying most of the light.
static void addCameraAndLight(Scene& s, int lightCount) {
  CameraDesc cam;
  cam.name = "temple";
  cam.worldFromEye = lookAt({2.0, 7.5, 17.5}, {0.0, 2.2, 0.0});
  cam.yfov = 0.87;
  cam.znear = 0.1;
  cam.zfar = 120.0;
  s.cameras.push_back(cam);

  s.sun.enabled = true;
  s.sun.toSun = glm::normalize(glm::dvec3(-0.62, 0.42, 0.52));
  s.sun.color = {1.05f, 0.78f, 0.52f};
  s.sky.zenith = {0.035f, 0.06f, 0.16f};
  s.sky.horizon = {0.55f, 0.33f, 0.24f};
  s.sky.ground = {0.06f, 0.05f, 0.05f};
  s.sky.ambient = {0.045f, 0.05f, 0.08f};
  generateLights(s, lightCount);
}

Scene builtinTemple(int lightCount) {
  Scene s;
  s.source = "builtin:temple";
  const TempleMaterials mat = addMaterials(s);
  MeshBuilder b{s};
  addPlatform(s, b, mat);
  addColonnade(s, b, mat);
  addOrnaments(s, b, mat);
  addFoliage(s, b, mat);
  computeBounds(s);  // before the lights: generated lights are placed within the bounds
  addCameraAndLight(s, lightCount);
  return s;
}

}  // namespace gb
