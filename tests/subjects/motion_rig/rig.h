// motion_rig: the analytic scene, the camera path and the exact ray casts (README.md states every
// convention). World: metres, right-handed, +Z up. View: left-handed (x right, y up, z forward, as
// D3D), so view_from_world mirrors (det -1). Clip: D3D-style (y up), reversed-Z with an infinite far
// plane: depth = near / z_view, 1 at the near plane, 0 at infinity.
#pragma once
#include <cstdint>
#include <optional>
#include <vector>

#include <glm/glm.hpp>

namespace rig {

using vec2 = glm::dvec2;
using vec3 = glm::dvec3;
using vec4 = glm::dvec4;
using mat3 = glm::dmat3;
using mat4 = glm::dmat4;  // glm: column vectors, m[column][row]

// Object ids as stored in the `object` channel (0 = sky).
enum ObjectId : int { kSky = 0, kGround = 1, kCrate = 2, kBall = 3, kPillar = 4, kSpinner = 5, kPost = 6 };
constexpr int kMovingId = kSpinner;

constexpr double kFramesPerSecond = 30.0;
constexpr double kNear = 0.05;     // metres; no far plane
constexpr double kFovY = 0.9;      // radians, vertical

struct Hit {
  double t = 0.0;       // distance along the (unit) ray
  vec3 position{0.0};   // world
  vec3 normal{0.0};     // world, unit
  vec3 albedo{0.0};     // linear
  int id = kSky;
};

struct Ray {
  vec3 origin, direction;  // direction unit
};

// The scene at (possibly fractional, possibly negative) frame number f.
class Scene {
 public:
  explicit Scene(double frame);
  std::optional<Hit> trace(const Ray& ray) const;
  // world_from_object of the moving object at frame f (rigid).
  static mat4 spinnerFromObject(double frame);

 private:
  mat4 spinner_, spinnerInv_;
};

// One frame's camera.
struct Camera {
  int width = 0, height = 0;
  vec3 eye{0.0};
  mat4 viewFromWorld{1.0};   // left-handed view
  mat4 clipFromView{1.0};    // UNJITTERED projection
  vec2 jitter{0.0};          // pixels, +x right, +y down
  mat4 jitteredClipFromView() const;
  // Unjittered projection of a world point (w = 1) or direction (w = 0) to continuous pixel
  // coordinates (x right, y down, texel (i, j)'s centre at (i + 0.5, j + 0.5)); nullopt behind the eye.
  std::optional<vec2> project(const vec4& world) const;
  // The world ray through continuous UNJITTERED pixel coordinates p.
  Ray ray(vec2 p) const;
};

Camera cameraAt(int frame, int width, int height);
// The point light of frame f (it moves, so a lit colour changes from frame to frame), and the lit
// colour of a hit: albedo x (0.2 + 6 max(0, n.l) / (1 + d^2)), no shadows; the sky is black.
vec3 lightAt(int frame);
vec3 shade(const Hit& hit, int frame);
// Halton(2, 3) sub-pixel offset of frame f: index (f mod 8) + 1, each value minus 0.5.
vec2 haltonJitter(int frame);

}  // namespace rig
