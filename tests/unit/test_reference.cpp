// The CPU reference on analytic cases: a plane and a tessellated sphere at known positions.
// Positions and normals must match independent double computations to 1e-12 (relative to the
// distance), coverage must follow the sphere's inscribed/circumscribed radii, and the exact
// shadow of a box must land where the geometry says.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/reference/reference.h"
#include "renderer/scene/mesh_builder.h"
#include "tests/support/scenes.h"

namespace gb {

static Camera testCamera(const Scene& s, uint32_t w, uint32_t h) { return makeCamera(s.cameras[0], w, h, false); }

TEST(Reference, PlanePositionsAndNormalsAreExact) {
  Scene scene = floorScene(50.0);
  setCamera(scene, {0.3, 3.0, 6.0}, {0.0, 0.0, -4.0}, 0.9, 0.1, 200.0);
  Camera v = testCamera(scene, 64, 48);
  reference::RayScene rays(scene);
  reference::Frame f = reference::renderFrame(rays, v);
  const glm::dvec3 o(v.worldFromEye[3]);
  const glm::dvec3 up = glm::dmat3(v.eyeFromWorld) * glm::dvec3(0, 1, 0);
  int hits = 0;
  for (uint32_t y = 0; y < v.height; ++y)
    for (uint32_t x = 0; x < v.width; ++x) {
      glm::dvec3 d = glm::dmat3(v.worldFromEye) * eyeFromEyeDepth(v, x, y, 1.0);
      double t = -o.y / d.y;  // the ray meets y = 0
      bool expectHit = t > 0.0 && std::abs(o.x + t * d.x) < 50.0 && std::abs(o.z + t * d.z) < 50.0;
      const reference::Surface& s = f.at(x, y);
      ASSERT_EQ(s.hit, expectHit) << x << "," << y;
      if (!s.hit) continue;
      glm::dvec3 expected = glm::dvec3(v.eyeFromWorld * glm::dvec4(o + t * d, 1.0));
      double dist = glm::length(expected);
      ASSERT_LE(glm::length(s.eye - expected), 1e-12 * dist) << x << "," << y;
      ASSERT_LE(std::abs(s.eyeDepth - (-expected.z)), 1e-12 * dist);
      ASSERT_LE(glm::length(s.world - (o + t * d)), 1e-12 * dist);
      ASSERT_LE(glm::length(s.normal - up), 1e-12);
      ASSERT_EQ(s.primitiveId, 1u + s.triangle);
      ++hits;
    }
  EXPECT_GT(hits, 1000);
}

TEST(Reference, SpherePositionsLieOnTheHitTriangleAndNormalsInterpolate) {
  Scene scene = floorScene(1.0);
  scene.instances.clear();
  MeshBuilder b{scene};
  const glm::dvec3 centre(0.25, 1.5, -0.5);
  const double R = 1.25;
  const int segments = 32, rings = 16;
  b.begin("sphere", 0);
  b.sphere(glm::vec3(0.0f), float(R), segments, rings);
  b.end();
  glm::dmat4 m(1.0);
  m[3] = glm::dvec4(centre, 1.0);
  scene.instances.push_back({b.meshIndex, m, true});
  computeBounds(scene);
  setCamera(scene, {1.0, 2.5, 4.0}, centre, 0.8, 0.1, 100.0);
  Camera v = testCamera(scene, 64, 64);
  reference::RayScene rays(scene);
  reference::Frame f = reference::renderFrame(rays, v);
  // Every point of the tessellation lies between the inscribed sphere of its faces and R.
  const double inner = R * std::cos(M_PI / segments) * std::cos(M_PI / rings) * 0.999;
  const glm::dvec3 cEye = glm::dvec3(v.eyeFromWorld * glm::dvec4(centre, 1.0));
  const Mesh& mesh = scene.meshes[b.meshIndex];
  int hits = 0;
  for (uint32_t y = 0; y < v.height; ++y)
    for (uint32_t x = 0; x < v.width; ++x) {
      glm::dvec3 d = glm::normalize(eyeFromEyeDepth(v, x, y, 1.0));
      double missDistance = glm::length(cEye - d * glm::dot(cEye, d));  // ray to centre
      const reference::Surface& s = f.at(x, y);
      if (missDistance > R * 1.000001) {
        ASSERT_FALSE(s.hit) << x << "," << y;
      }
      if (missDistance < inner) {
        ASSERT_TRUE(s.hit) << x << "," << y;
      }
      if (!s.hit) continue;
      ++hits;
      // The hit triangle, independently: world-space vertices in double.
      glm::dvec3 p[3], n[3];
      for (int k = 0; k < 3; ++k) {
        const Vertex& vx = scene.vertices[mesh.firstVertex + scene.indices[mesh.firstIndex + 3 * s.triangle + k]];
        p[k] = glm::dvec3(v.eyeFromWorld * (m * glm::dvec4(glm::dvec3(vx.position), 1.0)));
        n[k] = glm::dmat3(v.eyeFromWorld) * glm::dvec3(vx.normal);
      }
      glm::dvec3 face = glm::cross(p[1] - p[0], p[2] - p[0]);
      double area2 = glm::length(face);
      glm::dvec3 unit = face / area2;
      double scale = glm::length(s.eye);
      ASSERT_LE(std::abs(glm::dot(s.eye - p[0], unit)), 1e-12 * scale) << "off the triangle's plane";
      ASSERT_LT(glm::dot(unit, s.eye), 0.0) << "a back face was hit";
      // Barycentrics by sub-triangle areas (not the reference's Moeller-Trumbore).
      double w0 = glm::dot(glm::cross(p[1] - s.eye, p[2] - s.eye), unit) / area2;
      double w1 = glm::dot(glm::cross(p[2] - s.eye, p[0] - s.eye), unit) / area2;
      double w2 = 1.0 - w0 - w1;
      ASSERT_GE(std::min({w0, w1, w2}), -1e-6) << "outside the hit triangle";
      glm::dvec3 expectedN = glm::normalize(w0 * n[0] + w1 * n[1] + w2 * n[2]);
      ASSERT_LE(glm::length(s.normal - expectedN), 1e-12) << x << "," << y;
      double r = glm::length(s.eye - cEye);
      ASSERT_LE(r, R * (1.0 + 1e-7));
      ASSERT_GE(r, inner);
      ASSERT_LE(std::abs(-s.eye.z - s.eyeDepth), 1e-12 * scale);
    }
  EXPECT_GT(hits, 500);
}

TEST(Reference, ExactShadowOfABoxFollowsTheSunDirection) {
  Scene scene = floorScene(20.0);
  addBox(scene, {-0.5f, 0.0f, -0.5f}, {0.5f, 3.0f, 0.5f});
  scene.sun.enabled = true;
  scene.sun.toSun = glm::normalize(glm::dvec3(1.0, 1.0, 0.0));  // 45 degrees: the shadow spans x in [-3.5, -0.5]
  setCamera(scene, {0, 12, 8}, {-1.5, 0, 0});
  Camera v = testCamera(scene, 96, 72);
  reference::RayScene rays(scene);
  reference::Frame f = reference::renderFrame(rays, v);
  int lit = 0, shadowed = 0;
  for (const reference::Surface& s : f.pixels) {
    if (!s.hit || std::abs(s.world.y) > 1e-9) continue;  // floor pixels only
    ASSERT_GE(s.sunVisible, 0);
    // Analytic: the sun ray (x + t, t, z) crosses the box [-0.5, 0.5] x [0, 3] x [-0.5, 0.5]
    // for some t in [0, 3] exactly when |z| < 0.5 and -3.5 < x < 0.5.
    bool inShadow = std::abs(s.world.z) < 0.5 && s.world.x > -3.5 && s.world.x < 0.5;
    double margin = std::min({std::abs(std::abs(s.world.z) - 0.5), std::abs(s.world.x + 3.5)});
    if (margin < 1e-9) continue;
    ASSERT_EQ(s.sunVisible == 0, inShadow) << s.world.x << "," << s.world.z;
    (inShadow ? shadowed : lit)++;
  }
  EXPECT_GT(shadowed, 50);
  EXPECT_GT(lit, 500);
}

}  // namespace gb
