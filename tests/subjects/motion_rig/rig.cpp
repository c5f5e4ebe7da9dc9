// motion_rig: scene, camera path and exact intersections (rig.h).
#include "rig.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include <glm/gtc/matrix_transform.hpp>

namespace rig {
namespace {

constexpr double kEps = 1e-9;

struct Box {
  int id;
  vec3 half;          // half extents in the object's own axes
  mat4 worldFromBox;  // rigid
  mat4 boxFromWorld = glm::inverse(worldFromBox);
};

mat4 rotateZ(double a) { return glm::rotate(mat4(1.0), a, vec3(0, 0, 1)); }
mat4 rotateX(double a) { return glm::rotate(mat4(1.0), a, vec3(1, 0, 0)); }
mat4 translate(vec3 t) { return glm::translate(mat4(1.0), t); }

const Box kCrateBox{kCrate, {0.6, 0.6, 0.6}, translate({0.5, -1.2, 0.6}) * rotateZ(0.4)};
const Box kPillarBox{kPillar, {0.35, 0.35, 1.4}, translate({2.5, 1.15, 1.4}) * rotateZ(-0.3)};
const Box kPostBox{kPost, {0.15, 0.15, 0.9}, translate({-1.94, -2.26, 0.9})};
const vec3 kBallCentre{0.05, 1.2, 0.9};
constexpr double kBallRadius = 0.9;
const vec3 kSpinnerHalf{0.55, 0.3, 0.3};

// Ray against a rigid box: the entry distance and the world normal there.
bool hitBox(const Ray& r, const mat4& worldFromBox, const mat4& boxFromWorld, vec3 half, double& t, vec3& normal,
            vec3& local) {
  const vec3 o = vec3(boxFromWorld * vec4(r.origin, 1.0));
  const vec3 d = mat3(boxFromWorld) * r.direction;
  double tNear = -std::numeric_limits<double>::infinity(), tFar = std::numeric_limits<double>::infinity();
  int axis = -1;
  double sign = 0.0;
  for (int a = 0; a < 3; ++a) {
    if (std::abs(d[a]) < 1e-300) {
      if (std::abs(o[a]) > half[a]) return false;
      continue;
    }
    double t0 = (-half[a] - o[a]) / d[a], t1 = (half[a] - o[a]) / d[a];
    double s = -1.0;  // entering through the -half face when t0 < t1
    if (t0 > t1) std::swap(t0, t1), s = 1.0;
    if (t0 > tNear) tNear = t0, axis = a, sign = s;
    tFar = std::min(tFar, t1);
    if (tNear > tFar) return false;
  }
  if (axis < 0 || tNear <= kEps) return false;  // the eye is never inside a box
  t = tNear;
  vec3 n(0.0);
  n[axis] = sign;
  normal = glm::normalize(mat3(worldFromBox) * n);
  local = o + d * t;
  return true;
}

vec3 groundAlbedo(vec3 p) {
  const bool odd = (static_cast<long>(std::floor(p.x)) + static_cast<long>(std::floor(p.y))) & 1;
  return odd ? vec3(0.62, 0.6, 0.55) : vec3(0.2, 0.22, 0.25);
}

// The moving box's faces have their own colours, so its turning shows in the albedo.
vec3 spinnerAlbedo(vec3 local) {
  const vec3 a = glm::abs(local / kSpinnerHalf);
  if (a.x >= a.y && a.x >= a.z) return local.x > 0 ? vec3(0.85, 0.15, 0.1) : vec3(0.4, 0.05, 0.05);
  if (a.y >= a.z) return local.y > 0 ? vec3(0.15, 0.75, 0.2) : vec3(0.05, 0.35, 0.1);
  return local.z > 0 ? vec3(0.2, 0.3, 0.9) : vec3(0.1, 0.1, 0.4);
}

}  // namespace

mat4 Scene::spinnerFromObject(double f) {
  // Across the view 3.4 m ahead of the first eye, between the post (nearer) and the crate and ball.
  const vec3 centre{-1.9 + 0.0847 * f, -0.537 - 0.1238 * f, 0.7 + 0.1 * std::sin(0.5 * f)};
  return translate(centre) * rotateZ(0.35 * f) * rotateX(0.5);
}

Scene::Scene(double frame) : spinner_(spinnerFromObject(frame)), spinnerInv_(glm::inverse(spinner_)) {}

std::optional<Hit> Scene::trace(const Ray& r) const {
  Hit best;
  best.t = std::numeric_limits<double>::infinity();
  auto take = [&](double t, vec3 n, vec3 albedo, int id) {
    if (t > kEps && t < best.t) best.t = t, best.normal = n, best.albedo = albedo, best.id = id;
  };
  // Ground z = 0, seen from above only.
  if (r.direction.z < 0.0 && r.origin.z > 0.0) {
    const double t = -r.origin.z / r.direction.z;
    const vec3 p = r.origin + r.direction * t;
    take(t, {0, 0, 1}, groundAlbedo(p), kGround);
  }
  // Ball.
  {
    const vec3 oc = r.origin - kBallCentre;
    const double b = glm::dot(oc, r.direction), c = glm::dot(oc, oc) - kBallRadius * kBallRadius;
    const double disc = b * b - c;
    if (disc >= 0.0) {
      const double t = -b - std::sqrt(disc);
      const vec3 p = r.origin + r.direction * t;
      const bool stripe = std::sin(7.0 * p.z) > 0.0;
      take(t, glm::normalize(p - kBallCentre), stripe ? vec3(0.8, 0.8, 0.78) : vec3(0.15, 0.3, 0.7), kBall);
    }
  }
  double t;
  vec3 n, local;
  for (const Box* b : {&kCrateBox, &kPillarBox, &kPostBox}) {
    if (hitBox(r, b->worldFromBox, b->boxFromWorld, b->half, t, n, local)) {
      vec3 albedo = b->id == kCrate ? vec3(0.8, 0.45, 0.2) : b->id == kPillar ? vec3(0.3, 0.6, 0.3) : vec3(0.7, 0.7, 0.75);
      if (b->id == kCrate && std::abs(local.z) > 0.55) albedo *= 0.6;  // a darker band round the crate's top and bottom
      take(t, n, albedo, b->id);
    }
  }
  if (hitBox(r, spinner_, spinnerInv_, kSpinnerHalf, t, n, local)) take(t, n, spinnerAlbedo(local), kSpinner);
  if (!std::isfinite(best.t)) return std::nullopt;
  best.position = r.origin + r.direction * best.t;
  return best;
}

vec2 haltonJitter(int frame) {
  auto radicalInverse = [](int i, int base) {
    double f = 1.0, r = 0.0;
    while (i > 0) {
      f /= base;
      r += f * (i % base);
      i /= base;
    }
    return r;
  };
  const int index = ((frame % 8) + 8) % 8 + 1;
  return {radicalInverse(index, 2) - 0.5, radicalInverse(index, 3) - 0.5};
}

Camera cameraAt(int frame, int width, int height) {
  const double f = frame;
  Camera c;
  c.width = width, c.height = height;
  // From (-4.2, -3.2, 1.6) sideways to the right of the first view and a little forward, turning right.
  const vec3 forward0{0.8253356149, 0.5646424734, 0.0}, right0{0.5646424734, -0.8253356149, 0.0};  // yaw 0.6
  c.eye = vec3(-4.2, -3.2, 1.6) + f * (0.10 * right0 + 0.05 * forward0) + vec3(0.0, 0.0, 0.1 * std::sin(0.2 * f));
  const double yaw = 0.6 - 0.02 * f, pitch = -0.2;
  const vec3 forward{std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch)};
  const vec3 right = glm::normalize(glm::cross(forward, vec3(0, 0, 1)));
  const vec3 up = glm::cross(right, forward);
  // Rows: right, up, forward (a left-handed view of the right-handed world).
  mat4 v(1.0);
  for (int k = 0; k < 3; ++k) v[k][0] = right[k], v[k][1] = up[k], v[k][2] = forward[k];
  v[3][0] = -glm::dot(right, c.eye), v[3][1] = -glm::dot(up, c.eye), v[3][2] = -glm::dot(forward, c.eye);
  c.viewFromWorld = v;
  const double sy = 1.0 / std::tan(kFovY / 2.0), sx = sy * height / width;
  mat4 p(0.0);
  p[0][0] = sx;
  p[1][1] = sy;
  p[3][2] = kNear;  // clip z = near (w = 1): depth = near / z_view
  p[2][3] = 1.0;    // clip w = z_view
  c.clipFromView = p;
  c.jitter = haltonJitter(frame);
  return c;
}

vec3 lightAt(int frame) { return {-1.5 + 0.25 * frame, -0.3, 2.2}; }

vec3 shade(const Hit& hit, int frame) {
  const vec3 toLight = lightAt(frame) - hit.position;
  const double d2 = glm::dot(toLight, toLight);
  const double lambert = std::max(0.0, glm::dot(hit.normal, toLight / std::sqrt(d2)));
  return hit.albedo * (0.2 + 6.0 * lambert / (1.0 + d2));
}

mat4 Camera::jitteredClipFromView() const {
  mat4 p = clipFromView;
  p[2][0] += 2.0 * jitter.x / width;   // ndc x += 2 jx / W: the image moves right by jx pixels
  p[2][1] -= 2.0 * jitter.y / height;  // ndc y -= 2 jy / H: the image moves down by jy pixels (ndc y is up)
  return p;
}

std::optional<vec2> Camera::project(const vec4& world) const {
  const vec4 clip = clipFromView * viewFromWorld * world;
  if (!(clip.w > 1e-12)) return std::nullopt;
  const double nx = clip.x / clip.w, ny = clip.y / clip.w;
  return vec2((nx + 1.0) * 0.5 * width, (1.0 - ny) * 0.5 * height);
}

Ray Camera::ray(vec2 p) const {
  const double nx = 2.0 * p.x / width - 1.0, ny = 1.0 - 2.0 * p.y / height;
  const vec3 view{nx / clipFromView[0][0], ny / clipFromView[1][1], 1.0};
  const mat3 r = mat3(viewFromWorld);  // orthogonal (det -1): its inverse is its transpose
  return {eye, glm::normalize(glm::transpose(r) * view)};
}

}  // namespace rig
