// glTF files on the command line and on the GPU: exit codes and messages of the CLI; a MASK
// cut-out quad at a known eye depth; a mirrored single-sided quad that must stay visible; a few
// corpus files rendered with zero validation messages.
#include "tests/support/test_paths.h"
#include <sys/wait.h>

#include <cmath>
#include <fstream>
#include <list>
#include <sstream>

#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"
#include "views/analysis/accuracy.h"
#include "views/analysis/probe.h"

namespace gb {

namespace {

std::string corpus(const std::string& name) { return std::string(GBLENS_SOURCE_DIR) + "/tests/data/gltf/" + name; }
Scene load(const std::string& name, int lights = 0) { return loadScene(corpus(name), lights); }

}  // namespace

// ---- on the GPU ---------------------------------------------------------------------------

static RenderOptions tiny(uint32_t size) {
  RenderOptions o;
  o.width = o.height = size;
  o.lights = 0;
  o.fairies = false;
  return o;
}

// A 2x2 quad at z = -3, camera at the origin (yfov 1, square output): a pixel centre at NDC (x, y)
// meets the plane at X = 3 tan(0.5) x. The MASK texture's left texel has alpha 0, the right 1:
// linear filtering crosses 0.5 at X = 0. Drawn pixels have eye depth exactly 3.
TEST_F(GpuTest, GltfMaskCutoutAndEyeDepthMatchTheQuad) {
  Scene s = load("valid/cutout_quad.gltf");
  RenderOptions o = tiny(64);
  render(s, o, {{Target::Depth}});
  const CpuImage& depth = renderer(s).readback[size_t(Target::Depth)];
  int kept = 0, cut = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      double X = 3.0 * std::tan(0.5) * ((x + 0.5) / o.width * 2.0 - 1.0);
      double Y = 3.0 * std::tan(0.5) * ((y + 0.5) / o.height * 2.0 - 1.0);
      if (std::abs(Y) > 0.95 || std::abs(X) > 0.95) continue;  // near the quad's edge
      double d = depth.value(x, y, 0);
      if (X < -0.1) {
        EXPECT_EQ(d, 0.0) << x << "," << y << " should be cut out";
        ++cut;
      } else if (X > 0.1) {
        EXPECT_NEAR(d, 3.0, 3e-6) << x << "," << y;
        ++kept;
      }
    }
  EXPECT_GT(kept, 300);
  EXPECT_GT(cut, 300);
}

// A single-sided quad facing the camera through a mirroring node (scale -1 in x): its winding is
// reversed, and it must still be drawn (front face flipped by the renderer), not culled.
TEST_F(GpuTest, GltfMirroredQuadStaysVisible) {
  Scene s = load("valid/mirrored_quad.gltf");
  ASSERT_LT(glm::determinant(glm::dmat3(s.instances[0].worldFromObject)), 0.0);
  RenderOptions o = tiny(32);
  render(s, o, {{Target::Depth}});
  const CpuImage& depth = renderer(s).readback[size_t(Target::Depth)];
  EXPECT_NEAR(depth.value(16, 16, 0), 3.0, 3e-6);
  EXPECT_EQ(depth.value(1, 1, 0), 0.0);  // outside the quad
}

// Files that exercise textures, normal maps, alpha modes, lights and cameras render with zero
// validation messages (the fixture fails the test on any).
TEST_F(GpuTest, GltfCorpusRendersWithoutValidationMessages) {
  std::list<Scene> scenes;  // the fixture keeps a renderer per scene address: keep each alive
  for (const char* file : {"valid/materials.gltf", "valid/two_uv_sets.gltf", "valid/lights.gltf", "valid/binary.glb",
                           "valid/quantized.gltf"}) {
    const Scene& s = scenes.emplace_back(load(file, 4));
    for (int camera = 0; camera < int(s.cameras.size()); ++camera) {
      RenderOptions o = tiny(24);
      o.camera = camera;
      o.fairies = true;
      render(s, o, {{Target::Final}});
    }
  }
}

// KHR_materials_unlit: the left quad is unlit orange, the right one lit grey, with a sun and
// point lights. In every method the unlit pixels' hdr is their albedo as the lighting reads it
// (deferred, tiled: the 8-bit sRGB albedo target through the device's decode; forward: the base
// colour itself), the lit ones are not; the reference agrees, and the probe says "unlit".
TEST_F(GpuTest, GltfUnlitMaterialShowsItsBaseColour) {
  Scene s = load("valid/unlit.gltf", 8);
  ReferenceCache cache(s);
  const double orange[3] = {1.0, 0.217637640824031, 0.0};
  RenderOptions o = tiny(48);
  o.lights = 8;
  // The G-buffer and the probe (deferred); which pixels are the unlit quad's and the lit one's.
  FrameSnapshot g = snapshot(s, o, {Target::Hdr, Target::AlbedoSpecular, Target::NormalShadow, Target::Depth,
                                    Target::DepthStencil});
  const CpuImage& albedo = g.target(Target::AlbedoSpecular).image;
  std::vector<std::pair<uint32_t, uint32_t>> unlitPixels, litPixels;
  for (uint32_t y = 4; y < o.height - 4; ++y)
    for (uint32_t x = 4; x < o.width - 4; ++x) {
      if (g.target(Target::Depth).image.value(x, y, 0) <= 0.0) continue;
      if (x < o.width / 2 - 1) unlitPixels.push_back({x, y});
      if (x > o.width / 2 + 1) litPixels.push_back({x, y});
    }
  ASSERT_GT(unlitPixels.size(), 300u);
  ASSERT_GT(litPixels.size(), 300u);
  for (auto [x, y] : unlitPixels) EXPECT_TRUE(probePixel(g, x, y).unlit) << x << "," << y;
  for (auto [x, y] : litPixels) EXPECT_FALSE(probePixel(g, x, y).unlit) << x << "," << y;
  for (Method method : {Method::Deferred, Method::Tiled, Method::Forward}) {
    SCOPED_TRACE(name(method));
    o.method = method;
    MeasuredFrame m = measureFrame(source(s), o, cache);
    EXPECT_GT(m.error.unlit, 300u);
    EXPECT_EQ(m.error.unlitMismatched, 0u);
    if (method != Method::Forward) EXPECT_LT(m.error.lighting.relative.max, 1e-5);  // the reference's rule too
    const CpuImage hdr = snapshot(s, o, {Target::Hdr}).target(Target::Hdr).image;
    for (auto [x, y] : unlitPixels)
      for (int c = 0; c < 3; ++c) {
        double expected = method == Method::Forward ? orange[c] : double(g.srgbDecode[albedo.raw(x, y, c)]);
        EXPECT_NEAR(hdr.value(x, y, c), expected, 1e-6) << x << "," << y << " channel " << c;
      }
    int lit = 0;
    for (auto [x, y] : litPixels) lit += std::abs(hdr.value(x, y, 0) - g.srgbDecode[albedo.raw(x, y, 0)]) > 1e-3;
    EXPECT_GT(lit, 300);  // the grey quad is lit (ambient + sun), not shown as its albedo
  }
}

}  // namespace gb
