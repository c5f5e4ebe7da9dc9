// The CPU reference in double precision: for each pixel centre of a frame, what the G-buffer and
// the lit image should contain. Embree finds the first hit (float), then the hit triangle is
// intersected again exactly in double; normals, materials, sun visibility (a ray toward the sun)
// and the shading (shaders/shading.h compiled as C++ double) follow from that hit.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <vector>

#include "renderer/core/camera.h"
#include "renderer/scene/scene.h"

namespace gb::reference {

class MipTexture;

// One pixel of the reference frame. Eye space throughout unless named otherwise.
struct Surface {
  bool hit = false;
  uint32_t instance = 0, triangle = 0;  // Scene::instances index, triangle within the mesh
  uint32_t primitiveId = 0;             // as the primitive_id target: 0 none, else firstPrimitiveIds + triangle
  glm::dvec3 eye{0.0};                  // position on the pixel-centre ray
  glm::dvec3 world{0.0};
  double eyeDepth = 0.0;                // -eye.z
  glm::dvec3 normal{0.0};               // shading normal: interpolated, flipped, normal-mapped (material.glsl)
  glm::dvec3 geometricNormal{0.0};      // unit face normal, same side as `normal` before normal mapping
  glm::dvec3 albedo{0.0};               // linear, clamped to [0, 1] as the sRGB target stores it
  double specular = 0.0;
  bool textured = false;                // albedo came from a texture (filtered: see sampler.h)
  bool unlit = false;                   // KHR_materials_unlit: the albedo is the colour (shadeUnlit)
  // Sun: 1 the ray toward the sun reaches it, 0 it is blocked, -1 not evaluated (no sun, or the
  // face turns away from the sun so the shadow term cannot matter).
  int8_t sunVisible = -1;
  double pixelFootprint = 0.0;          // world size of the pixel at the hit (for tolerances)
  // Largest change of the eye depth to a 4-neighbour pixel centre on this triangle's plane (its
  // whole depth when a neighbour's ray misses the plane): what a sub-pixel shift of the rasterized
  // triangle does to an interpolated depth (see placementAllowance in views/analysis/error.h).
  double eyeDepthChange = 0.0;
  // The size of the terms the vertex stage sums in float for this triangle's vertices (|eyeFromObject|
  // x |position| per row, the largest over the vertices): its rounding is ~2^-24 of this. Object
  // coordinates far from the eye (a city modelled in thousands of units) make it large.
  double vertexTerms = 0.0;
  // The largest |framebuffer coordinate| (pixels from the corner) of the triangle's vertices after
  // clipping to the near plane, at least the frame's size: the rasterizer's float coordinates, and
  // so the sub-pixel precision of the triangle's placement, scale with it (off-screen vertices of a
  // long triangle are thousands of pixels out).
  double screenExtent = 0.0;
};

struct Frame {
  Camera camera;
  std::vector<Surface> pixels;  // width * height, rows top to bottom
  const Surface& at(uint32_t x, uint32_t y) const { return pixels[size_t(y) * camera.width + x]; }
};

// The scene as Embree geometry (world space), built once and shared by every frame of it.
class RayScene {
 public:
  explicit RayScene(const Scene& scene, unsigned threads = 2);
  ~RayScene();
  RayScene(const RayScene&) = delete;
  RayScene& operator=(const RayScene&) = delete;

  const Scene& scene() const;
  const MipTexture& texture(int index) const;  // Scene::textures[index] with its mip chain
  // First hit of a world-space ray (camera rays: back faces of single-sided materials and
  // alpha-cut texels are skipped as the rasterizer skips them).
  struct Hit {
    bool hit = false;
    uint32_t instance = 0, triangle = 0;
  };
  Hit firstHit(const glm::dvec3& origin, const glm::dvec3& direction) const;
  // True when nothing that casts shadows blocks the ray toward the sun (both faces block; the
  // triangle the ray starts on is ignored; alpha-cut texels let light through).
  bool reachesSun(const glm::dvec3& origin, const glm::dvec3& toSun, uint32_t instance, uint32_t triangle,
                  double tnear) const;

  struct Impl;

 private:
  std::unique_ptr<Impl> impl_;
};

// Renders the reference for `camera` (positions, normals, materials, sun visibility).
Frame renderFrame(const RayScene& rays, const Camera& camera, unsigned threads = 2);

// One pixel of renderFrame: the first surface on the ray through pixel (x, y)'s centre.
Surface surfaceAtPixel(const RayScene& rays, const Camera& camera, uint32_t x, uint32_t y);

// The surface of one given triangle where the ray through pixel (x, y) meets its plane, even
// outside the triangle (attribute changes per pixel, for tolerances); sunVisible stays -1.
Surface surfaceOnTriangle(const RayScene& rays, const Camera& camera, uint32_t instance, uint32_t triangle, uint32_t x,
                          uint32_t y);

// World size of one shadow-map texel for a map of `size` texels (the renderer's sun fit).
double shadowTexelSize(const Scene& scene, uint32_t size);

// Pixels whose sun visibility changes within `radius` (world units, measured in the plane
// perpendicular to the sun): the penumbra band a filtered shadow map may legitimately disagree in.
std::vector<uint8_t> shadowBand(const RayScene& rays, const Frame& frame, double radius, unsigned threads = 2);

// ---- shading --------------------------------------------------------------------------------
// What the lighting passes need per pixel: the reference's own surface, or a GPU G-buffer texel
// decoded in double (to measure the lighting passes alone).
struct ShadingInput {
  bool geometry = false;
  glm::dvec3 P{0.0}, N{0.0}, albedo{0.0};
  double specular = 0.0;
  double shadow = 1.0;  // 1 lit, 0 shadowed
  bool unlit = false;   // shadeUnlit: the albedo, no lights
};
struct Light {
  glm::dvec3 eyePosition{0.0};
  double radius = 0.0;
  glm::dvec3 color{0.0};  // colour * intensity
};
struct Sun {
  bool enabled = false;
  glm::dvec3 toSunEye{0.0, 0.0, 1.0};
  glm::dvec3 color{0.0}, ambient{0.0};
};
struct Shaded {
  std::vector<glm::dvec3> hdr;     // ambient + sun + point lights
  std::vector<glm::dvec3> absSum;  // sum of |each contribution| (ambient+sun counts as one)
  std::vector<uint32_t> count;     // contributions that are non-zero (ambient+sun counts as one)
};

// The scene's lights at `time` in eye space, in double.
std::vector<Light> eyeLights(const Scene& scene, const Camera& camera, double time);
Sun sunOf(const Scene& scene, const Camera& camera);
ShadingInput shadingInput(const Surface& s);
// Shades every pixel (width x height of `camera`); each pixel's position P must lie on (within a
// pixel of) the ray through its centre, as the reference's and the G-buffer's positions do.
Shaded shade(const std::vector<ShadingInput>& pixels, const Camera& camera, const std::vector<Light>& lights,
             const Sun& sun, unsigned threads = 2);

// One pixel shaded as shade() does (every light, no binning: lights out of range add exactly 0).
glm::dvec3 shadeOne(const ShadingInput& s, const std::vector<Light>& lights, const Sun& sun);

// Runs f(y) for every row on `threads` threads (rows handed out one at a time).
void parallelRows(uint32_t height, unsigned threads, const std::function<void(uint32_t)>& f);

}  // namespace gb::reference
