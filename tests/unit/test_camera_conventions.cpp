// Every camera convention a layout can state, against points computed by hand: each up axis and
// sign, right- and left-handed views, right- and left-handed worlds, perspective and orthographic
// projections, Vulkan, D3D and GL clip spaces, standard and reversed depth. For each, a camera is
// built from its basis vectors and a projection written out term by term (not through gblens's
// camera code); a point placed on a chosen pixel centre at a chosen eye depth must come back from
// import: in gblens's eye space, on that pixel, and rebuilt from its eye, hardware and radial depth
// as that point in the layout's own world coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <sstream>

#include "renderer/core/camera.h"
#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "views/import/import.h"

namespace gb {
namespace {

constexpr uint32_t kW = 8, kH = 6;
constexpr double kNear = 0.5, kFar = 40.0, kTan = 0.4, kHalfHeight = 3.0;

struct Case {
  Axis up;
  bool viewLeft, worldLeft, ortho, reversed;
  LayoutCamera::Convention convention;
  std::string text() const {
    std::ostringstream s;
    static const char* conv[] = {"vulkan", "d3d", "gl"};
    s << "up " << name(up) << ", " << (viewLeft ? "left" : "right") << " view, " << (worldLeft ? "left" : "right")
      << " world, " << (ortho ? "orthographic" : "perspective") << ", " << conv[int(convention)]
      << (reversed ? ", reversed" : "");
    return s.str();
  }
};

glm::dvec3 axis(Axis a) {
  glm::dvec3 v(0.0);
  v[int(a) / 2] = int(a) % 2 ? -1.0 : 1.0;
  return v;
}

// The camera's basis in the layout's world coordinates: up along the up axis, right along the next
// axis, forward from right and up by the world's handedness (right-handed: up x right).
struct Basis {
  glm::dvec3 eye, right, up, forward;
};
Basis basis(const Case& c) {
  Basis b;
  b.up = axis(c.up);
  const int u = int(c.up) / 2;
  b.right = glm::dvec3(0.0);
  b.right[(u + 1) % 3] = 1.0;
  b.forward = c.worldLeft ? glm::cross(b.right, b.up) : glm::cross(b.up, b.right);
  b.eye = glm::dvec3(1.5, -2.0, 0.75);
  return b;
}

// view_from_world by hand: rows right, up and the view's z axis (backward for a right-handed view,
// forward for a left-handed one), and the eye at the origin.
glm::dmat4 viewFromWorld(const Case& c, const Basis& b) {
  const glm::dvec3 z = c.viewLeft ? b.forward : -b.forward;
  glm::dmat4 m(1.0);
  for (int col = 0; col < 3; ++col) m[col][0] = b.right[col], m[col][1] = b.up[col], m[col][2] = z[col];
  m[3][0] = -glm::dot(b.right, b.eye), m[3][1] = -glm::dot(b.up, b.eye), m[3][2] = -glm::dot(z, b.eye);
  return m;
}

// clip_from_view term by term: x and y scaled (y negated for Vulkan's y-down clip space), w the
// forward distance d (perspective) or 1, depth a function of d: 0..1 (or 1..0 reversed) for Vulkan
// and D3D, -1..1 for GL.
glm::dmat4 clipFromView(const Case& c) {
  const double aspect = double(kW) / kH, n = kNear, f = kFar;
  const double sd = c.viewLeft ? 1.0 : -1.0;  // d = sd * z_view
  const double sy = c.convention == LayoutCamera::Convention::Vulkan ? -1.0 : 1.0;
  const bool gl = c.convention == LayoutCamera::Convention::Gl;
  glm::dmat4 m(0.0);
  double a, b;  // clip.z = a d + b
  if (!c.ortho) {
    m[0][0] = 1.0 / (kTan * aspect);
    m[1][1] = sy / kTan;
    m[2][3] = sd;  // w = d
    if (gl) a = (f + n) / (f - n), b = -2.0 * f * n / (f - n);
    else if (c.reversed) a = -n / (f - n), b = f * n / (f - n);
    else a = f / (f - n), b = -f * n / (f - n);
  } else {
    m[0][0] = 1.0 / (kHalfHeight * aspect);
    m[1][1] = sy / kHalfHeight;
    m[3][3] = 1.0;
    if (gl) a = 2.0 / (f - n), b = -2.0 * n / (f - n) - 1.0;
    else if (c.reversed) a = -1.0 / (f - n), b = f / (f - n);
    else a = 1.0 / (f - n), b = -n / (f - n);
  }
  m[2][2] = a * sd;
  m[3][2] = b;
  return m;
}

// The hardware depth the projection gives at forward distance d (window depth for GL: ndc / 2 + 1/2).
double hardware(const Case& c, double d) {
  const glm::dmat4 p = clipFromView(c);
  const double sd = c.viewLeft ? 1.0 : -1.0, z = sd * d;
  const double w = c.ortho ? 1.0 : d, ndc = (p[2][2] * z + p[3][2]) / w;
  return c.convention == LayoutCamera::Convention::Gl ? ndc * 0.5 + 0.5 : ndc;
}

// A frame holding one depth quantity at pixel (px, py), with the case's camera.
FrameSnapshot frameWithDepth(const LayoutCamera& camera, const Camera& converted, DepthEncoding e, uint32_t px,
                             uint32_t py, double stored) {
  Layout l;
  l.camera = camera;
  LayoutTarget t;
  t.name = "depth";
  parseStorageFormat("r32f", t.format);
  t.channels = {"Z"};
  l.targets.push_back(t);
  Quantity q;
  q.kind = QuantityKind::Depth;
  q.name = "Z";
  q.channels = {0};
  q.depth = e;
  l.quantities.push_back(q);
  FrameSnapshot f;
  f.setLayout(l);
  f.camera = converted;
  CpuImage& img = f.images[0].image;
  describeImage(t, img);
  img.width = kW, img.height = kH;
  img.data.assign(size_t(kW) * kH * 4, 0);
  const float v = float(stored);
  std::memcpy(&img.data[(size_t(py) * kW + px) * 4], &v, 4);
  f.images[0].targetWidth = kW, f.images[0].targetHeight = kH;
  return f;
}

TEST(CameraConventions, EveryUpAxisHandednessProjectionAndClipSpaceRebuildsHandPlacedPoints) {
  const uint32_t px = 6, py = 1;  // right of centre, near the top
  const double d = 7.25;
  size_t cases = 0;
  for (int up = 0; up < 6; ++up)
    for (bool viewLeft : {false, true})
      for (bool worldLeft : {false, true})
        for (bool ortho : {false, true})
          for (int conv = 0; conv < 3; ++conv)
            for (bool reversed : {false, true}) {
              if (reversed && conv == 2) continue;  // GL's -1..1 is not reversed here
              const Case c{Axis(up), viewLeft, worldLeft, ortho, reversed, LayoutCamera::Convention(conv)};
              SCOPED_TRACE(c.text());
              ++cases;
              const Basis b = basis(c);
              LayoutCamera lc;
              lc.present = true;
              lc.up = c.up;
              lc.leftHanded = c.viewLeft;
              lc.convention = c.convention;
              lc.viewFromWorld = viewFromWorld(c, b);
              lc.clipFromView = clipFromView(c);
              std::string error;
              ASSERT_TRUE(settleWorldHandedness(lc, error)) << error;
              EXPECT_EQ(lc.worldLeftHanded, c.worldLeft);
              Camera cam;
              ASSERT_TRUE(importCamera(lc, kW, kH, cam, error)) << error;
              EXPECT_EQ(orthographic(cam), c.ortho);
              EXPECT_EQ(cam.reversedZ, c.reversed);
              EXPECT_NEAR(cam.znear, kNear, 1e-9);
              EXPECT_NEAR(cam.zfar, kFar, 1e-6);
              // gblens's world is right-handed (eye from world is a rotation) and its +Y is the layout's
              // up: here the camera's up, the eye's +Y.
              EXPECT_NEAR(glm::determinant(glm::dmat3(cam.eyeFromWorld)), 1.0, 1e-12);
              EXPECT_NEAR(glm::length(glm::dmat3(cam.eyeFromWorld) * glm::dvec3(0, 1, 0) - glm::dvec3(0, 1, 0)), 0.0, 1e-12);

              // The point on pixel (px, py) at forward distance d, by the projection's own terms.
              const double aspect = double(kW) / kH;
              const double nx = (px + 0.5) / kW * 2.0 - 1.0, nyUp = 1.0 - (py + 0.5) / kH * 2.0;
              const double halfW = c.ortho ? kHalfHeight * aspect : d * kTan * aspect, halfH = c.ortho ? kHalfHeight : d * kTan;
              const double a = nx * halfW, h = nyUp * halfH;
              const glm::dvec3 world = b.eye + d * b.forward + a * b.right + h * b.up;
              const glm::dvec3 eye = glm::dvec3(cam.eyeFromWorld * glm::dvec4(worldFromLayoutWorld(lc) * world, 1.0));
              EXPECT_NEAR(glm::length(eye - glm::dvec3(a, h, -d)), 0.0, 1e-12);
              const glm::dvec4 clip = cam.clipFromEye * glm::dvec4(eye, 1.0);
              EXPECT_NEAR((clip.x / clip.w * 0.5 + 0.5) * kW - 0.5, px, 1e-9);
              EXPECT_NEAR((clip.y / clip.w * 0.5 + 0.5) * kH - 0.5, py, 1e-9);

              // Rebuilt from each depth, in the layout's own world axes.
              std::vector<std::pair<DepthEncoding, double>> depths = {{DepthEncoding::Eye, d},
                                                                       {DepthEncoding::Hardware, hardware(c, d)}};
              if (!c.ortho) depths.push_back({DepthEncoding::Radial, glm::length(world - b.eye)});
              for (auto [e, stored] : depths) {
                const FrameSnapshot f = frameWithDepth(lc, cam, e, px, py, stored);
                std::optional<glm::dvec3> p = decodePosition(f, f.layout.quantities[0], px, py);
                ASSERT_TRUE(p.has_value()) << name(e);
                const glm::dvec3 back = spaceFromEye(f, Space::World, *p, true);
                // float32 storage of the depth: one rounding of d, and the projection's amplification of it.
                const double bound = e == DepthEncoding::Hardware ? (c.ortho ? 1e-5 : 2e-4) * d : 1e-6 * d;
                EXPECT_NEAR(glm::length(back - world), 0.0, bound) << name(e) << " stored " << stored;
                EXPECT_NEAR(-p->z, d, bound) << name(e);
              }
            }
  EXPECT_EQ(cases, 6u * 2 * 2 * 2 * 5);
}

TEST(CameraConventions, WhatCannotBeReconstructedIsRefusedWithOneLine) {
  LayoutCamera c;
  c.present = true;
  Camera cam;
  std::string error;
  // A perspective looking down +Z while the layout says the view is right-handed.
  c.clipFromView = perspective(0.8, 1.5, 0.1, 10.0, false);
  c.clipFromView[2][3] = 1.0;
  c.clipFromView[2][2] *= -1.0;
  EXPECT_FALSE(importCamera(c, 8, 6, cam, error));
  EXPECT_NE(error.find("view_handedness is \"left\""), std::string::npos) << error;
  // Clip w from z and a constant at once: neither projection.
  c.clipFromView = perspective(0.8, 1.5, 0.1, 10.0, false);
  c.clipFromView[3][3] = 0.5;
  EXPECT_FALSE(importCamera(c, 8, 6, cam, error));
  EXPECT_NE(error.find("neither a perspective nor an orthographic projection"), std::string::npos) << error;
  // A stated projection that the matrix is not.
  c.clipFromView = perspective(0.8, 1.5, 0.1, 10.0, false);
  c.statedOrthographic = true;
  EXPECT_FALSE(importCamera(c, 8, 6, cam, error));
  EXPECT_NE(error.find("projection: \"orthographic\", but clip_from_view is perspective"), std::string::npos) << error;
}

TEST(CameraConventions, LayoutFilesSayEveryUpAxisAndRefuseOthers) {
  for (const char* up : {"x", "-x", "y", "-y", "z", "-z", "+y"}) {
    LayoutCamera c;
    std::string error;
    nlohmann::json j = {{"up", up}, {"view_from_world", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}},
                        {"clip_from_view", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}};
    ASSERT_TRUE(parseLayoutCamera(j, "cam.json", c, error)) << up << ": " << error;
    EXPECT_EQ(layoutCameraJson(c)["up"], std::string(up) == "+y" ? "y" : up);
  }
  LayoutCamera c;
  std::string error;
  EXPECT_FALSE(parseLayoutCamera({{"up", "w"}}, "cam.json", c, error));
  EXPECT_EQ(error, "cam.json: camera: up: \"w\" is not one of x, -x, y, -y, z, -z");
  // A stated world handedness the view matrix contradicts (a mirror with a right-handed view: left).
  nlohmann::json mirrored = {{"world_handedness", "right"},
                             {"view_from_world", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, 0, 0, 0, 0, 1}},
                             {"clip_from_view", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1}}};
  EXPECT_FALSE(parseLayoutCamera(mirrored, "cam.json", c, error));
  EXPECT_NE(error.find("world_handedness: \"right\", but the view matrix mirrors"), std::string::npos) << error;
  mirrored["world_handedness"] = "left";
  EXPECT_TRUE(parseLayoutCamera(mirrored, "cam.json", c, error)) << error;
  EXPECT_TRUE(c.worldLeftHanded);
}

}  // namespace
}  // namespace gb
