// The reference frame: per pixel centre, Embree's hit triangle intersected again in double
// (eye space, the ray through the pixel centre as the GPU reconstructs it), then normal,
// material and sun visibility at that point; and the penumbra band for shadow comparisons.
#include "renderer/reference/reference.h"

#include <algorithm>
#include <atomic>
#include <cmath>
#include <thread>

#include "renderer/core/progress.h"
#include "renderer/reference/sampler.h"

namespace gb::reference {

void parallelRows(uint32_t height, unsigned threads, const std::function<void(uint32_t)>& f) {
  std::atomic<uint32_t> next{0};
  // The caller's progress (core/progress.h): rows counted as they finish; once cancelled, no row
  // is started (the result is then incomplete, and the caller throws it away).
  WorkProgress* progress = currentProgress();
  auto work = [&] {
    for (uint32_t y; (!progress || !progress->cancelled()) && (y = next.fetch_add(1)) < height;) {
      f(y);
      if (progress) progress->done.fetch_add(progress->weight, std::memory_order_relaxed);
    }
  };
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < std::max(threads, 1u); ++i) pool.emplace_back(work);
  work();
  for (std::thread& t : pool) t.join();
}

namespace {

// Ray (origin 0, direction d) against the plane of triangle ABC, in double (Moeller-Trumbore
// without the inside test): t along d and the barycentrics of B and C.
bool intersectPlane(const glm::dvec3& d, const glm::dvec3& a, const glm::dvec3& b, const glm::dvec3& c, double& t,
                    double& b1, double& b2) {
  glm::dvec3 e1 = b - a, e2 = c - a;
  glm::dvec3 p = glm::cross(d, e2);
  double det = glm::dot(e1, p);
  if (det == 0.0 || !std::isfinite(det)) return false;
  glm::dvec3 s = -a;
  glm::dvec3 q = glm::cross(s, e1);
  b1 = glm::dot(s, p) / det;
  b2 = glm::dot(d, q) / det;
  t = glm::dot(e2, q) / det;
  return true;
}

struct InstanceTransform {
  glm::dmat4 eyeFromObject{1.0};
  glm::dmat3 normalEyeFromObject{1.0};  // inverse transpose, as DrawData
  bool mirrored = false;
};

struct Context {
  const RayScene& rays;
  const Scene& scene;
  const Camera& camera;
  std::vector<InstanceTransform> transforms;
  std::vector<uint32_t> firstPrimitive;
  glm::dvec3 cameraWorld{0.0};
  Sun sun;
  glm::dvec3 toSunWorld{0.0};
  double shadowTnear = 0.0;
};

struct Corner {
  const Vertex* v[3];
  glm::dvec3 eye[3];
};

Corner corners(const Context& c, uint32_t instance, uint32_t triangle) {
  const Mesh& mesh = c.scene.meshes[c.scene.instances[instance].mesh];
  Corner k;
  for (int i = 0; i < 3; ++i) {
    k.v[i] = &c.scene.vertices[mesh.firstVertex + c.scene.indices[mesh.firstIndex + 3 * triangle + i]];
    k.eye[i] = glm::dvec3(c.transforms[instance].eyeFromObject * glm::dvec4(glm::dvec3(k.v[i]->position), 1.0));
  }
  return k;
}

glm::dvec2 uvOf(const Vertex& v, int set) { return set == 0 ? glm::dvec2(v.uv0) : glm::dvec2(v.uv1); }

// Texture coordinates (set, transform) at barycentrics of the plane.
glm::dvec2 uvAt(const Corner& k, double b1, double b2, int set, const glm::mat3& transform) {
  glm::dvec2 uv = (1.0 - b1 - b2) * uvOf(*k.v[0], set) + b1 * uvOf(*k.v[1], set) + b2 * uvOf(*k.v[2], set);
  return glm::dvec2(glm::dmat3(transform) * glm::dvec3(uv, 1.0));
}

// uv and its per-pixel changes as the GPU's 2x2 quad sees them: coarse differences from the
// quad's top-left pixel, each pixel's ray meeting the plane of this triangle.
struct UvSample {
  glm::dvec2 uv, dx, dy;
};
UvSample uvSample(const Context& c, const Corner& k, uint32_t x, uint32_t y, double b1, double b2, int set,
                  const glm::mat3& transform) {
  UvSample s;
  s.uv = uvAt(k, b1, b2, set, transform);
  uint32_t qx = x & ~1u, qy = y & ~1u;
  auto at = [&](uint32_t px, uint32_t py) {
    double t, u, v;
    if (!intersectPlane(eyeFromEyeDepth(c.camera, px, py, 1.0), k.eye[0], k.eye[1], k.eye[2], t, u, v))
      return s.uv;
    return uvAt(k, u, v, set, transform);
  };
  glm::dvec2 base = at(qx, qy);
  s.dx = at(qx + 1, qy) - base;
  s.dy = at(qx, qy + 1) - base;
  return s;
}

// The surface of triangle `h` where the ray through pixel (x, y) meets its plane (inside the
// triangle when Embree found it there; extrapolated otherwise).
Surface evaluate(const Context& c, RayScene::Hit h, uint32_t x, uint32_t y, bool sunRay) {
  Surface s;
  const Camera& camera = c.camera;
  glm::dvec3 d = eyeFromEyeDepth(camera, x, y, 1.0);  // the pixel-centre ray, eye depth 1
  const Corner k = corners(c, h.instance, h.triangle);
  double t, b1, b2;
  if (!intersectPlane(d, k.eye[0], k.eye[1], k.eye[2], t, b1, b2) || !(t > 0.0)) return s;
  const double b0 = 1.0 - b1 - b2;
  s.hit = true;
  s.instance = h.instance;
  s.triangle = h.triangle;
  s.primitiveId = c.firstPrimitive[h.instance] + h.triangle;
  s.eye = t * d;
  s.eyeDepth = t;  // d.z = -1
  s.world = glm::dvec3(camera.worldFromEye * glm::dvec4(s.eye, 1.0));
  s.pixelFootprint = t * 2.0 * std::tan(camera.yfov * 0.5) / camera.height;
  // The framebuffer extent of the triangle, clipped to the near plane as the rasterizer clips it.
  s.screenExtent = double(std::max(camera.width, camera.height));
  for (int v = 0; v < 3; ++v) {
    const glm::dvec3 &a = k.eye[v], &b = k.eye[(v + 1) % 3];
    glm::dvec3 points[2] = {a, a};
    int n = 0;
    if (-a.z >= camera.znear) points[n++] = a;
    if ((-a.z < camera.znear) != (-b.z < camera.znear)) points[n++] = a + (b - a) * ((-camera.znear - a.z) / (b.z - a.z));
    for (int q = 0; q < n; ++q) {
      glm::dvec4 clip = camera.clipFromEye * glm::dvec4(points[q], 1.0);
      glm::dvec2 ndc = glm::dvec2(clip) / clip.w;
      s.screenExtent = std::max({s.screenExtent, std::abs((ndc.x + 1.0) * 0.5 * camera.width),
                                 std::abs((ndc.y + 1.0) * 0.5 * camera.height)});
    }
  }
  const InstanceTransform& placed = c.transforms[h.instance];
  for (int v = 0; v < 3; ++v) {
    glm::dvec3 p(k.v[v]->position), terms(0.0);
    for (int row = 0; row < 3; ++row)
      terms[row] = std::abs(placed.eyeFromObject[0][row] * p.x) + std::abs(placed.eyeFromObject[1][row] * p.y) +
                   std::abs(placed.eyeFromObject[2][row] * p.z) + std::abs(placed.eyeFromObject[3][row]);
    s.vertexTerms = std::max(s.vertexTerms, glm::length(terms));
  }
  for (auto [dx, dy] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
    double tn, u, v;
    glm::dvec3 dn = eyeFromEyeDepth(camera, double(x) + dx, double(y) + dy, 1.0);
    bool meets = intersectPlane(dn, k.eye[0], k.eye[1], k.eye[2], tn, u, v) && tn > 0.0;
    s.eyeDepthChange = std::max(s.eyeDepthChange, meets ? std::abs(tn - t) : t);
  }

  const InstanceTransform& xf = c.transforms[h.instance];
  glm::dvec3 g = glm::cross(k.eye[1] - k.eye[0], k.eye[2] - k.eye[0]);
  const bool frontFacing = (glm::dot(g, d) < 0.0) != xf.mirrored;
  s.geometricNormal = glm::normalize(glm::dot(g, d) < 0.0 ? g : -g);  // toward the camera

  // Shading normal (shaders/material.glsl: surfaceNormal).
  glm::dvec3 n = b0 * glm::dvec3(k.v[0]->normal) + b1 * glm::dvec3(k.v[1]->normal) + b2 * glm::dvec3(k.v[2]->normal);
  // A normal without a direction: the face's normal toward the camera (as surfaceNormal).
  glm::dvec3 nEye = xf.normalEyeFromObject * n;
  glm::dvec3 N = s.geometricNormal;
  if (glm::dot(nEye, nEye) > 1e-24) N = glm::normalize(nEye) * (frontFacing ? 1.0 : -1.0);
  const Mesh& mesh = c.scene.meshes[c.scene.instances[h.instance].mesh];
  static const MaterialDesc kDefault;
  const MaterialDesc& m = mesh.material >= 0 && size_t(mesh.material) < c.scene.materials.size()
                              ? c.scene.materials[mesh.material]
                              : kDefault;
  if (m.normalTexture >= 0) {
    glm::dvec4 tan4 = b0 * glm::dvec4(k.v[0]->tangent) + b1 * glm::dvec4(k.v[1]->tangent) + b2 * glm::dvec4(k.v[2]->tangent);
    glm::dvec3 tangent = glm::dmat3(xf.eyeFromObject) * glm::dvec3(tan4);
    glm::dvec3 tt = tangent - N * glm::dot(N, tangent);
    if (glm::dot(tt, tt) > 1e-20) {
      glm::dvec3 T = glm::normalize(tt);
      glm::dvec3 B = glm::cross(N, T) * (tan4.w < 0.0 ? -1.0 : 1.0);
      UvSample us = uvSample(c, k, x, y, b1, b2, m.normalUv, m.normalUvTransform);
      glm::dvec3 tn = glm::dvec3(c.rays.texture(m.normalTexture).sample(us.uv, us.dx, us.dy)) * 2.0 - 1.0;
      tn.x *= m.normalScale;
      tn.y *= m.normalScale;
      glm::dvec3 nm = T * tn.x + B * tn.y + N * tn.z;
      if (glm::dot(nm, nm) > 1e-20) N = glm::normalize(nm);
    }
  }
  s.normal = N;

  glm::dvec4 base = glm::dvec4(m.baseColor);
  if (m.baseColorTexture >= 0) {
    UvSample us = uvSample(c, k, x, y, b1, b2, m.baseColorUv, m.baseUvTransform);
    base *= c.rays.texture(m.baseColorTexture).sample(us.uv, us.dx, us.dy);
    s.textured = true;
  }
  s.albedo = glm::clamp(glm::dvec3(base), 0.0, 1.0);
  s.specular = std::clamp(double(m.specular), 0.0, 1.0);
  s.unlit = m.unlit;
  if (s.unlit) return s;  // no light reaches its colour: the sun's visibility cannot matter

  // The exact shadow, where it can matter: the face and the shading normal both turn toward the sun.
  if (sunRay && c.sun.enabled && glm::dot(N, c.sun.toSunEye) > 0.0 && glm::dot(s.geometricNormal, c.sun.toSunEye) > 0.0)
    s.sunVisible = c.rays.reachesSun(s.world, c.toSunWorld, h.instance, h.triangle,
                                     c.shadowTnear + 1e-6 * glm::length(s.world))
                       ? 1
                       : 0;
  return s;
}

Surface surfaceAt(const Context& c, uint32_t x, uint32_t y) {
  glm::dvec3 d = eyeFromEyeDepth(c.camera, x, y, 1.0);
  RayScene::Hit h = c.rays.firstHit(c.cameraWorld, glm::dmat3(c.camera.worldFromEye) * d);
  return h.hit ? evaluate(c, h, x, y, true) : Surface{};
}

// Everything a pixel needs; transforms of every instance, or only of `onlyInstance`.
Context makeContext(const RayScene& rays, const Camera& camera, int64_t onlyInstance = -1) {
  const Scene& scene = rays.scene();
  Context c{rays, scene, camera, {}, firstPrimitiveIds(scene), glm::dvec3(camera.worldFromEye[3]), sunOf(scene, camera), {}, 0.0};
  c.toSunWorld = glm::normalize(scene.sun.toSun);
  c.shadowTnear = 1e-6 * std::max(scene.bounds.radius(), 1e-3);
  c.transforms.resize(scene.instances.size());
  for (size_t i = 0; i < scene.instances.size(); ++i) {
    if (onlyInstance >= 0 && int64_t(i) != onlyInstance) continue;
    const Instance& inst = scene.instances[i];
    InstanceTransform& xf = c.transforms[i];
    xf.eyeFromObject = camera.eyeFromWorld * inst.worldFromObject;  // camera-relative, as the renderer forms it
    xf.normalEyeFromObject = glm::transpose(glm::inverse(glm::dmat3(xf.eyeFromObject)));
    xf.mirrored = glm::determinant(glm::dmat3(inst.worldFromObject)) < 0.0;
  }
  return c;
}

}  // namespace

Surface surfaceAtPixel(const RayScene& rays, const Camera& camera, uint32_t x, uint32_t y) {
  return surfaceAt(makeContext(rays, camera), x, y);
}

Surface surfaceOnTriangle(const RayScene& rays, const Camera& camera, uint32_t instance, uint32_t triangle, uint32_t x,
                          uint32_t y) {
  Context c = makeContext(rays, camera, instance);
  return evaluate(c, {true, instance, triangle}, x, y, false);
}

Frame renderFrame(const RayScene& rays, const Camera& camera, unsigned threads) {
  Context c = makeContext(rays, camera);
  Frame f;
  f.camera = camera;
  f.pixels.resize(size_t(camera.width) * camera.height);
  parallelRows(camera.height, threads, [&](uint32_t y) {
    for (uint32_t x = 0; x < camera.width; ++x) f.pixels[size_t(y) * camera.width + x] = surfaceAt(c, x, y);
  });
  return f;
}

double shadowTexelSize(const Scene& scene, uint32_t size) {
  glm::dmat4 m = shadowClipFromWorld(scene);  // orthographic: row 0 scales world x'' to [-1, 1]
  double scale = glm::length(glm::dvec3(m[0][0], m[1][0], m[2][0]));
  return 2.0 / (scale * std::max(size, 1u));
}

std::vector<uint8_t> shadowBand(const RayScene& rays, const Frame& f, double radius, unsigned threads) {
  const Scene& scene = rays.scene();
  std::vector<uint8_t> band(f.pixels.size(), 0);
  if (!scene.sun.enabled) return band;
  const glm::dvec3 toSun = glm::normalize(scene.sun.toSun);
  const glm::dvec3 e1 = glm::normalize(glm::cross(toSun, std::abs(toSun.y) < 0.9 ? glm::dvec3(0, 1, 0) : glm::dvec3(1, 0, 0)));
  const glm::dvec3 e2 = glm::cross(toSun, e1);
  const double tnear = 1e-5 * std::max(scene.bounds.radius(), 1e-3);
  const int kSamples = 8;
  parallelRows(f.camera.height, threads, [&](uint32_t y) {
    for (uint32_t x = 0; x < f.camera.width; ++x) {
      const Surface& s = f.at(x, y);
      if (s.sunVisible < 0) continue;
      glm::dvec3 ng = glm::dmat3(f.camera.worldFromEye) * s.geometricNormal;
      double facing = glm::dot(toSun, ng);
      for (int k = 0; k < kSamples && !band[size_t(y) * f.camera.width + x]; ++k) {
        double a = 2.0 * M_PI * k / kSamples;
        glm::dvec3 o = radius * (std::cos(a) * e1 + std::sin(a) * e2);
        // The point of the receiver's plane whose sun ray passes `o` away from this one's:
        // `radius` apart in the shadow map.
        double along = glm::dot(o, ng) / facing;
        bool differs = true;  // grazing receivers: the band covers them
        if (std::abs(along) < 1e3 * radius) {
          glm::dvec3 p = s.world + o - toSun * along;
          differs = rays.reachesSun(p, toSun, s.instance, s.triangle, tnear + 1e-6 * glm::length(p)) != (s.sunVisible == 1);
        }
        if (differs) band[size_t(y) * f.camera.width + x] = 1;
      }
    }
  });
  return band;
}

}  // namespace gb::reference
