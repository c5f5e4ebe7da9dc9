// Hand-made G-buffers for the import tests: an analytic scene (a floor square and a sphere resting on
// it, seen by a known camera) written as EXR (multi-layer, multi-part, half), PNG, TIFF and raw dumps in
// two sets of conventions, with the layouts that describe them. Nothing here uses gblens's decoder.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

namespace gb::fixtures {

constexpr uint32_t kW = 64, kH = 48;

// One pixel of the scene, through the pixel centre (rows from the top).
struct Truth {
  bool hit = false;
  glm::dvec3 world{0.0}, normalWorld{0.0};  // right-handed, Y up
  glm::dvec3 eye{0.0}, normalEye{0.0};      // eye space: right-handed, looking down -Z, Y up
};

struct Scene {
  glm::dmat4 view{1.0};  // eye from world (Y up)
  double fovy = 0.9, aspect = double(kW) / kH, znear = 0.1, zfar = 50.0;
  glm::dmat4 glProjection{1.0};   // A: OpenGL clip space (y up, z -1..1), standard depth
  glm::dmat4 d3dReversed{1.0};    // B: D3D clip space of a left-handed view (y up, z 0..1), reversed depth
  glm::dmat4 viewLeftZUp{1.0};    // B: left-handed view from a Z-up world
  std::vector<Truth> pixels;      // kW * kH
  const Truth& at(uint32_t x, uint32_t y) const { return pixels[size_t(y) * kW + x]; }
};
Scene makeScene();

// Z-up world coordinates of a Y-up point or direction (Blender's axes): (x, y, z) -> (x, -z, y).
glm::dvec3 zUp(const glm::dvec3& v);
// The octahedral map of a unit vector onto [-1, 1]^2 (Meyer et al. 2010; Cigolle et al. 2014, JCGT 3(2)).
glm::dvec2 octahedral(glm::dvec3 n);
// Eye depth from stored hardware depth, inverting each fixture's projection by hand.
double eyeDepthFromGlWindowDepth(const Scene& s, double d);
double eyeDepthFromD3dReversedDepth(const Scene& s, double d);
// The hardware depth each fixture stores for an eye-space point.
double glWindowDepth(const Scene& s, const glm::dvec3& eye);
double d3dReversedDepth(const Scene& s, const glm::dvec3& eye);

// Fixture A: GL conventions, column-major matrices in the layout, rows bottom first (a GL read-back):
// gbuffer.exr (multi-layer: world normals N.*, world positions P.*, eye depth Z; float), normal_view.png
// (view normals n * 0.5 + 0.5, 8 bits), normal_oct.bin (raw octahedral view normals, rg16_snorm),
// depth.exr (two parts: "hardware" standard window depth, "radial" distance from the eye; float).
// Returns the layout (written as a.json too).
nlohmann::json writeFixtureA(const std::string& dir, const Scene& s);
// Fixture B: D3D conventions, left-handed view, Z-up world, row-major matrices from a sidecar
// (camera_b.json), rows top first: depth_reversed.bin (raw d32f reversed depth), normal_half.exr
// (world normals, half), position.tif (world positions, float TIFF). Layout b.json.
nlohmann::json writeFixtureB(const std::string& dir, const Scene& s);

// A small G-buffer (16x8, every pixel a surface) for `gblens check`: gbuf.exr (rgba32f: albedo RGB,
// roughness), normal.exr (half view normals), depth.exr (float eye depth); layout c.json. With
// `plant`, the texels check must find are planted in it (see test_import_check.cpp).
nlohmann::json writeFixtureC(const std::string& dir, bool plant);

void writeJson(const std::string& path, const nlohmann::json& j);

}  // namespace gb::fixtures
