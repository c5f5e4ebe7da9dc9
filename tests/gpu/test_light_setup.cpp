// Light setup on the GPU (--light-setup gpu: light_setup + light_compact in double) against the
// CPU's classifyLights: the same eye-space lights (the same floats but for the rounding of the
// GPU's sin/cos kernels), the same visible set and culled counts, the same image within the
// accumulation bound, and nothing per light left on the CPU (the pass list says where it ran).
#include <algorithm>
#include <cmath>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/frame/session.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace {

void expectSameLights(GpuTest& t, const Scene& scene, RenderOptions o, const std::string& what) {
  if (!t.ctx().features.float64) GTEST_SKIP() << "no shaderFloat64: light setup stays on the CPU";
  o.lightSetup = LightSetup::Cpu;
  const FrameStats cpu = t.render(scene, o, {{Target::Hdr}});
  const FrameSnapshot a = snapshotFromRenderer(t.renderer(scene), {Target::Hdr});
  o.lightSetup = LightSetup::Gpu;
  const FrameStats gpu = t.render(scene, o, {{Target::Hdr}});
  ASSERT_TRUE(passRan(gpu, "light_setup") && passRan(gpu, "light_compact")) << what;
  EXPECT_EQ(gpu.lightSetup, "gpu");
  const FrameSnapshot b = snapshotFromRenderer(t.renderer(scene), {Target::Hdr});
  ASSERT_EQ(a.eyeLights.size(), b.eyeLights.size());
  size_t different = 0;
  double worst = 0.0;
  for (size_t i = 0; i < a.eyeLights.size(); ++i) {
    const glm::vec4 &p = a.eyeLights[i].eyePositionRadius, &q = b.eyeLights[i].eyePositionRadius;
    EXPECT_EQ(a.eyeLights[i].color, b.eyeLights[i].color) << what << " light " << i;
    EXPECT_EQ(p.w, q.w);
    if (glm::vec3(p) != glm::vec3(q)) ++different;
    for (int c = 0; c < 3; ++c) worst = std::max(worst, double(std::abs(p[c] - q[c])) / std::max(std::abs(double(p[c])), 1.0));
  }
  EXPECT_LE(worst, 2e-7) << what << ": eye positions differ by more than a float rounding";
  EXPECT_LE(different, a.eyeLights.size() / 20) << what;
  std::vector<uint32_t> va = a.visibleLights, vb = b.visibleLights;
  EXPECT_TRUE(std::is_sorted(vb.begin(), vb.end())) << what << ": the GPU's list is in scene order";
  std::sort(va.begin(), va.end());
  EXPECT_EQ(va, vb) << what;
  EXPECT_EQ(cpu.lightsVisible, gpu.lightsVisible);
  EXPECT_EQ(cpu.lightsCulledFrustum, gpu.lightsCulledFrustum);
  EXPECT_EQ(cpu.lightsCulledEmpty, gpu.lightsCulledEmpty);
  EXPECT_EQ(cpu.lightsCulledSubpixel, gpu.lightsCulledSubpixel);
  // Lights in another order sum in another order: fp32 sums of the same terms (hundreds at most).
  const CpuImage& x = a.target(Target::Hdr).image;
  const CpuImage& y = b.target(Target::Hdr).image;
  int bad = 0;
  for (uint32_t py = 0; py < x.height; ++py)
    for (uint32_t px = 0; px < x.width; ++px)
      for (int c = 0; c < 3; ++c) {
        const double u = x.value(px, py, c), v = y.value(px, py, c);
        bad += !(std::abs(u - v) <= 1e-4 * std::max(std::abs(u), std::abs(v)) + 1e-7);
      }
  EXPECT_EQ(bad, 0) << what;
}

}  // namespace

TEST_F(GpuTest, LightSetupOnTheGpuMatchesTheCpu) {
  RenderOptions o;
  o.width = 96;
  o.height = 54;
  o.fairies = true;
  const Scene temple = builtinTemple(2048);  // some culled by the frustum, some sub-pixel
  o.time = 3.7;
  for (Method m : {Method::Tiled, Method::Clustered}) {
    o.method = m;
    expectSameLights(*this, temple, o, std::string("temple ") + name(m));
  }
  // Far from the origin, late in the animation, with empty lights.
  Scene far = builtinTemple(512);
  const glm::dvec3 offset(3.0e5, -2.0e3, 7.0e4);
  for (Instance& i : far.instances) i.worldFromObject = glm::translate(glm::dmat4(1.0), offset) * i.worldFromObject;
  for (CameraDesc& c : far.cameras) c.worldFromEye = glm::translate(glm::dmat4(1.0), offset) * c.worldFromEye;
  for (PointLightDesc& l : far.lights) l.center += offset;
  far.generatedLights = false;
  far.lights[3].intensity = 0.0;
  far.lights[7].radius = 0.0;
  o.method = Method::Clustered;
  o.time = 12345.25;
  expectSameLights(*this, far, o, "far from the origin");
}

// Auto: on the GPU path only for tiled and clustered on a GPU device; the pass list says why not.
TEST_F(GpuTest, LightSetupSaysWhereItRan) {
  Scene scene = builtinTemple(16);
  RenderOptions o;
  o.width = 64;
  o.height = 36;
  o.method = Method::Deferred;
  o.lightSetup = LightSetup::Gpu;
  const FrameStats& st = render(scene, o);
  EXPECT_EQ(st.lightSetup, "cpu");  // deferred needs the CPU's light classes
  EXPECT_FALSE(passRan(st, "light_setup"));
  o.method = Method::Clustered;
  o.lightSetup = LightSetup::Auto;
  const FrameStats& c = render(scene, o);
  EXPECT_EQ(c.lightSetup, ctx().isCpu || !ctx().features.float64 ? "cpu" : "gpu") << c.lightSetupReason;
}

}  // namespace gb
