// Lighting decomposition (issue 17, section 2) against the frame the GPU shaded and against
// counts and images made independently: sun + point lights equals the stored hdr within the
// probe's bound (the device's sRGB decode of the albedo and fp32 accumulation), diffuse + specular
// equals sun + point lights, the light count equals a brute-force count over every light, and
// "lighting only" equals the hdr of the same frame rendered with white materials.
#include <cmath>

#include "renderer/frame/session.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"
#include "tests/support/capture_util.h"
#include "views/analysis/decompose.h"
#include "views/capture/capture.h"

namespace gb {

namespace {
RenderOptions decomposeOptions() {
  RenderOptions o = smallCaptureOptions();
  o.lights = 16;
  o.fairies = false;  // sprites add to hdr: not lighting
  return o;
}
FrameSnapshot renderAll(GpuTest& t, const Scene& scene, const RenderOptions& o) {
  std::vector<Target> all = availableTargets(o);
  t.render(scene, o, captureRequest(all, o));
  return snapshotFromRenderer(t.renderer(scene), all);
}
// A frame of `scene` with every target read back, and its decomposition.
void renderAndDecompose(GpuTest& t, const Scene& scene, const RenderOptions& o, FrameSnapshot& f, Decomposition& d) {
  f = renderAll(t, scene, o);
  std::string error;
  ASSERT_TRUE(decomposeLighting(f, d, error, 2)) << error;
}
glm::dvec3 rgb(const CpuImage& img, uint32_t x, uint32_t y) {
  return {img.value(x, y, 0), img.value(x, y, 1), img.value(x, y, 2)};
}
}  // namespace

TEST_F(GpuTest, LightingDecompositionAddsUpToTheShadedFrame) {
  Scene scene = builtinTemple(16);
  const RenderOptions o = decomposeOptions();
  FrameSnapshot f;
  Decomposition d;
  ASSERT_NO_FATAL_FAILURE(renderAndDecompose(*this, scene, o, f, d));
  const CpuImage& hdr = f.target(Target::Hdr).image;
  const CpuImage& eye = f.target(Target::Depth).image;
  auto term = [&](LightingTerm t) -> const CpuImage& { return d.images[size_t(t)]; };
  size_t surfaces = 0, counted = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      if (eye.value(x, y, 0) == 0.0) continue;  // sky
      ++surfaces;
      const glm::dvec3 total = rgb(term(LightingTerm::Sun), x, y) + rgb(term(LightingTerm::PointLights), x, y);
      const glm::dvec3 parts = rgb(term(LightingTerm::Diffuse), x, y) + rgb(term(LightingTerm::Specular), x, y);
      for (int c = 0; c < 3; ++c) {
        ASSERT_NEAR(total[c], hdr.value(x, y, c), 6e-3 * hdr.value(x, y, c) + 2e-4) << x << "," << y << " channel " << c;
        ASSERT_NEAR(parts[c], total[c], 1e-6 * std::max(1.0, total[c])) << x << "," << y;
      }
      // Light count: every scene light, brute force, at the position rebuilt from the eye depth.
      const glm::dvec3 P = eyeFromEyeDepth(f.camera, x, y, eye.value(x, y, 0));
      int n = 0;
      for (const gpu::PointLight& l : f.eyeLights) {
        const glm::dvec3 c(l.eyePositionRadius);
        n += glm::dot(c - P, c - P) < double(l.eyePositionRadius.w) * l.eyePositionRadius.w;
      }
      ASSERT_EQ(term(LightingTerm::LightCount).value(x, y, 0), double(n)) << x << "," << y;
      counted += n > 0;
    }
  EXPECT_GT(surfaces, 2000u);
  EXPECT_GT(counted, 100u) << "the lights reach some surfaces";
}

TEST_F(GpuTest, LightingOnlyIsTheFrameWithWhiteMaterials) {
  Scene scene = builtinTemple(16);
  const RenderOptions o = decomposeOptions();
  FrameSnapshot f;
  Decomposition d;
  ASSERT_NO_FATAL_FAILURE(renderAndDecompose(*this, scene, o, f, d));
  Scene white = scene;
  for (MaterialDesc& m : white.materials)
    if (m.alphaMode == AlphaMode::Opaque) {  // masked leaves keep their texture (its alpha cuts them)
      m.baseColor = glm::vec4(1.0f);
      m.baseColorTexture = -1;
    }
  FrameSnapshot w = renderAll(*this, white, o);
  const CpuImage& albedo = w.target(Target::AlbedoSpecular).image;
  const CpuImage& hdr = w.target(Target::Hdr).image;
  const CpuImage& lighting = d.images[size_t(LightingTerm::Lighting)];
  size_t compared = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      if (albedo.value(x, y, 0) != 1.0 || albedo.value(x, y, 1) != 1.0 || albedo.value(x, y, 2) != 1.0) continue;
      if (w.target(Target::Depth).image.value(x, y, 0) == 0.0) continue;
      ++compared;
      for (int c = 0; c < 3; ++c)
        ASSERT_NEAR(lighting.value(x, y, c), hdr.value(x, y, c), 2e-5 * hdr.value(x, y, c) + 1e-5) << x << "," << y;
    }
  EXPECT_GT(compared, 2000u);
}

}  // namespace gb
