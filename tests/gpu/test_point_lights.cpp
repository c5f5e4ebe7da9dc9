// Point lights (stencil light-volume culling): culled vs unculled and single- vs two-pass agree,
// no light is lost where the scheme usually fails (camera inside, near/far plane), the lit disc
// of one light matches the analytic disc, the ideal pair count matches brute force, and the
// lights sharing a stencil bit (a layer) rasterize disjoint pixels; the point-light formula in float
// stays near the same formula in double at grazing angles.
#include <cmath>
#include <random>

#include "renderer/core/camera.h"
#include "renderer/frame/light_culling.h"
#include "renderer/readback/shading_probe.h"
#include "renderer/scene/builtin.h"
#include "renderer/scene/mesh_builder.h"
#include "shaders/shading.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

static RenderOptions lightOptions(uint32_t w, uint32_t h) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.fairies = false;  // sprites would cover the pixels these tests check
  o.sky = false;
  o.coverage = true;
  return o;
}

// |a - b| <= N * 2^-11 * max(|a|, |b|) per channel, N = lights that shaded the pixel (fp16
// accumulation rounds once per light); a tiny absolute floor for values near zero.
static int countOutOfBound(const CpuImage& a, const CpuImage& b, const CpuImage& coverage) {
  int bad = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      double n = std::max(1.0, coverage.value(x, y, 0));
      for (int c = 0; c < 3; ++c) {
        double va = a.value(x, y, c), vb = b.value(x, y, c);
        if (std::abs(va - vb) > n * std::ldexp(1.0, -11) * std::max(std::abs(va), std::abs(vb)) + 1e-6) ++bad;
      }
    }
  return bad;
}

TEST_F(GpuTest, StencilCulledAndUnculledImagesAgree) {
  for (int lights : {0, 1, 16, 256, 4096}) {
    Scene scene = builtinTemple(lights);
    RenderOptions o = lightOptions(128, 72);
    o.lights = lights;
    o.stencilCulling = false;
    render(scene, o, {{Target::Hdr, Target::CoverageMasked}});
    CpuImage unculled = renderer(scene).readback[size_t(Target::Hdr)];
    CpuImage coverage = renderer(scene).readback[size_t(Target::CoverageMasked)];
    o.stencilCulling = true;
    for (auto [mask, layers] : {std::pair{StencilMask::PerLight, StencilLayers::On},
                                std::pair{StencilMask::PerLight, StencilLayers::Off},
                                std::pair{StencilMask::Shared, StencilLayers::Auto}}) {
      o.stencilMask = mask;
      o.stencilLayers = layers;
      render(scene, o, {{Target::Hdr}});
      EXPECT_EQ(countOutOfBound(renderer(scene).readback[size_t(Target::Hdr)], unculled, coverage), 0)
          << lights << " lights, " << name(mask) << " mask, stencil layers " << name(layers);
    }
  }
}

TEST_F(GpuTest, SinglePassAndTwoPassImagesAgree) {
  for (int lights : {16, 256}) {
    Scene scene = builtinTemple(lights);
    RenderOptions o = lightOptions(128, 72);
    o.lights = lights;
    o.fairies = true;
    o.sky = true;
    for (bool eyeDepth : {true, false}) {
      o.eyeDepth = eyeDepth;
      o.path = Path::TwoPass;
      render(scene, o, {{Target::Hdr, Target::CoverageMasked}});
      CpuImage twoPass = renderer(scene).readback[size_t(Target::Hdr)];
      CpuImage coverage = renderer(scene).readback[size_t(Target::CoverageMasked)];
      o.path = Path::SinglePass;
      render(scene, o, {{Target::Hdr}});
      EXPECT_EQ(countOutOfBound(renderer(scene).readback[size_t(Target::Hdr)], twoPass, coverage), 0)
          << lights << " lights, eye depth " << eyeDepth;
    }
  }
}

// One light over the floor: the GPU's hdr must equal the light evaluated on the CPU (double,
// the same formulas) at every pixel's read-back surface point, and no lit pixel may be missing.
static void expectLightMatchesCpu(GpuTest& t, const Scene& scene, const RenderOptions& o, const char* what,
                                  int minLitPixels) {
  Renderer& r = t.renderer(scene);
  const CpuImage& hdr = r.readback[size_t(Target::Hdr)];
  const CpuImage& depth = r.readback[size_t(Target::Depth)];
  const CpuImage& albedo = r.readback[size_t(Target::AlbedoSpecular)];
  const gpu::PointLight& l = r.lights.eye[0];
  int lit = 0, missing = 0, wrong = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      double d = depth.value(x, y, 0);
      if (d <= 0.0) continue;
      glm::dvec3 p = eyeFromEyeDepth(r.camera, x, y, d);
      glm::dvec3 n = glm::normalize(glm::dmat3(r.camera.eyeFromWorld) * glm::dvec3(0, 1, 0));
      glm::dvec3 a(albedo.value(x, y, 0), albedo.value(x, y, 1), albedo.value(x, y, 2));
      glm::dvec3 e = shading::shadePoint(a, albedo.value(x, y, 3), n, p, glm::dvec3(l.eyePositionRadius),
                                         l.eyePositionRadius.w, glm::dvec3(l.color));
      for (int c = 0; c < 3; ++c) {
        double g = hdr.value(x, y, c);
        if (e[c] > 1e-3 && g == 0.0) ++missing;
        if (std::abs(g - e[c]) > 4e-3 * e[c] + 2e-4) ++wrong;
      }
      if (e.x > 1e-3) ++lit;
    }
  EXPECT_EQ(missing, 0) << what << ": pixels the light should reach are black";
  EXPECT_EQ(wrong, 0) << what << ": pixels differ from the CPU evaluation";
  EXPECT_GT(lit, minLitPixels) << what;
}

static Scene oneLightScene(glm::dvec3 light, double radius) {
  Scene s = floorScene(200.0);
  s.materials[0].baseColor = glm::vec4(0.8f, 0.6f, 0.4f, 1.0f);
  PointLightDesc l;
  l.center = light;
  l.radius = radius;
  l.color = glm::vec3(1.0f, 0.9f, 0.7f);
  l.intensity = 2.0;
  s.lights = {l};
  return s;
}

class PointLightMasks : public GpuTest, public ::testing::WithParamInterface<StencilMask> {};
INSTANTIATE_TEST_SUITE_P(Masks, PointLightMasks, ::testing::Values(StencilMask::PerLight, StencilMask::Shared),
                         [](const auto& info) { return std::string(info.param == StencilMask::PerLight ? "PerLight" : "Shared"); });

TEST_P(PointLightMasks, NoLightIsLostWhenTheVolumeContainsTheCameraOrCrossesNearOrFar) {
  RenderOptions o = lightOptions(96, 64);
  o.stencilMask = GetParam();
  o.lights = 1;
  FrameRequest req{{Target::Hdr, Target::Depth, Target::AlbedoSpecular}};
  {  // The camera inside the light's sphere.
    Scene s = oneLightScene({0.0, 1.5, 0.0}, 4.0);
    setCamera(s, {0.5, 2.0, 1.0}, {0.0, 0.0, -3.0}, 0.9, 0.1, 100.0);
    render(s, o, req);
    EXPECT_EQ(renderer(s).lights.stencilCount, 0u);  // drawn in the near-plane class
    expectLightMatchesCpu(*this, s, o, "camera inside", 500);
  }
  {  // The sphere crosses the near plane beside the camera without containing it (camera 0.7
     // above the floor looking down; the light's eye-space z spans -0.8..0.1 around near 0.3).
    Scene s = oneLightScene({0.5, 0.35, 0.0}, 0.45);
    setCamera(s, {0.0, 0.7, 0.0}, {0.0, 0.0, 0.0}, 1.2, 0.3, 100.0);
    render(s, o, req);
    EXPECT_GT(glm::length(glm::dvec3(renderer(s).lights.eye[0].eyePositionRadius)), 0.45);  // camera outside
    EXPECT_EQ(renderer(s).lights.stencilCount, 0u);
    expectLightMatchesCpu(*this, s, o, "near plane", 100);
  }
  {  // The sphere crosses the far plane: back faces beyond it are clamped, not clipped.
    Scene s = oneLightScene({0.0, 0.5, -20.0}, 6.0);
    setCamera(s, {0.0, 1.0, 0.0}, {0.0, 0.6, -20.0}, 0.6, 0.1, 20.5);
    render(s, o, req);
    EXPECT_EQ(renderer(s).lights.stencilCount, 1u);  // a stencil-class light
    expectLightMatchesCpu(*this, s, o, "far plane", 20);
  }
}

TEST_F(GpuTest, OneLightOverTheFloorLightsExactlyTheAnalyticDisc) {
  const double h = 1.0, radius = 3.0, rho = std::sqrt(radius * radius - h * h);
  Scene s = oneLightScene({0.3, h, -0.2}, radius);
  setCamera(s, {0.0, 10.0, 0.0}, {0.0, 0.0, 0.0}, 0.9, 0.1, 100.0);
  RenderOptions o = lightOptions(160, 120);
  o.lights = 1;
  render(s, o, {{Target::Hdr, Target::Depth}});
  Renderer& r = renderer(s);
  const CpuImage& hdr = r.readback[size_t(Target::Hdr)];
  // Pixel footprint on the floor, for the edge band: distance 10, vertical fov 0.9.
  const double pixel = 2.0 * 10.0 * std::tan(0.45) / o.height;
  int expected = 0, gpu = 0, offEdge = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      glm::dvec3 dirEye = eyeFromEyeDepth(r.camera, x, y, 1.0);
      glm::dvec3 d = glm::dmat3(r.camera.worldFromEye) * dirEye;
      glm::dvec3 hit = glm::dvec3(0, 10, 0) + d * (10.0 / -d.y);
      double dist = glm::length(glm::dvec2(hit.x - 0.3, hit.z + 0.2));
      bool inDisc = dist < rho;
      bool litGpu = hdr.value(x, y, 0) > 0.0;
      expected += inDisc;
      gpu += litGpu;
      if (inDisc != litGpu && std::abs(dist - rho) > 1.5 * pixel) ++offEdge;
    }
  EXPECT_GT(expected, 1000);
  EXPECT_NEAR(gpu, expected, 0.01 * expected + 2.0 * M_PI * rho / pixel);  // 1% + one-pixel edge band
  EXPECT_EQ(offEdge, 0) << "lit/unlit pixels away from the disc's edge";
}

TEST_P(PointLightMasks, EveryIdealPairIsShadedAndTheCountMatchesBruteForce) {
  for (StencilLayers layers : {StencilLayers::On, StencilLayers::Off}) {
    SCOPED_TRACE(std::string("stencil layers ") + name(layers));
    Scene scene = builtinTemple(96);
    RenderOptions o = lightOptions(80, 45);
    o.stencilMask = GetParam();
    o.stencilLayers = layers;
    o.lights = 96;
    const FrameStats& st = render(scene, o, {{Target::Depth, Target::CoverageMasked}, {}, true});
    Renderer& r = renderer(scene);
    const CpuImage& depth = r.readback[size_t(Target::Depth)];
    const CpuImage& coverage = r.readback[size_t(Target::CoverageMasked)];
    uint64_t brute = idealPairsBruteForce(r.camera, depth, r.lights.eye);
    EXPECT_EQ(st.culling.idealPairs, brute);
    EXPECT_GT(brute, 1000u);
    // Stencil culling must never skip a light that reaches the pixel's surface point.
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        double d = depth.value(x, y, 0);
        if (d <= 0.0) continue;
        glm::dvec3 p = eyeFromEyeDepth(r.camera, x, y, d);
        uint32_t reaching = 0;
        for (const gpu::PointLight& l : r.lights.eye) {
          glm::dvec3 v = p - glm::dvec3(l.eyePositionRadius);
          reaching += glm::dot(v, v) < double(l.eyePositionRadius.w) * l.eyePositionRadius.w;
        }
        ASSERT_GE(coverage.raw(x, y, 0), reaching) << "pixel " << x << "," << y;
      }
    EXPECT_GE(st.culling.invocations, st.culling.idealPairs);
  }
}

// The single-pass path with a transient G-buffer (nothing stored between subpasses; lazily
// allocated memory where the device has it, a clean fallback where it does not, as on lavapipe)
// gives the same pixels as the single-pass path that keeps the G-buffer for the views.
TEST_F(GpuTest, SinglePassWithTransientGBufferGivesTheSameImage) {
  Scene scene = builtinTemple(64);
  RenderOptions o = lightOptions(96, 54);
  o.lights = 64;
  o.fairies = true;
  o.sky = true;
  o.path = Path::SinglePass;
  o.keepGBuffer = true;
  render(scene, o, {{Target::Hdr}});
  CpuImage kept = renderer(scene).readback[size_t(Target::Hdr)];
  o.keepGBuffer = false;
  render(scene, o, {{Target::Hdr}});
  Renderer& r = renderer(scene);
  for (Target t : {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth}) {
    const Image& img = r.targets[size_t(t)].image;
    EXPECT_TRUE(img.desc.transient) << targetName(t);
    EXPECT_EQ(img.lazilyAllocated, ctx().features.lazilyAllocatedMemory) << targetName(t);
  }
  EXPECT_EQ(r.readback[size_t(Target::Hdr)].data, kept.data);
}

// shadePoint on the device (float) against shadePoint in double on the same float inputs, over
// random surface points, half of them seen at grazing angles with the light nearly opposite the eye
// (L close to -V, where |L + V| is small): within 1e-4 relative wherever the light gives more than
// 1e-3. (|L + V|^2 formed as 2 + 2 L.V cancels there: in float it was off by up to 1.5e-3.)
TEST_F(GpuTest, ThePointLightFormulaInFloatStaysNearTheDoubleOneAtGrazingAngles) {
  Scene scene = builtinTemple(1);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::normal_distribution<double> g;
  auto randomUnit = [&] { return glm::normalize(glm::dvec3(g(rng), g(rng), g(rng))); };
  std::vector<ShadingCase> cases;
  while (cases.size() < 65536) {
    const bool grazing = cases.size() % 2 == 1;
    const glm::dvec3 P(6.0 * u(rng) - 3.0, 6.0 * u(rng) - 3.0, -1.0 - 9.0 * u(rng));
    const glm::dvec3 V = glm::normalize(-P);
    glm::dvec3 N = randomUnit();
    if (grazing) {  // N.V in (0.001, 0.2]
      const glm::dvec3 side = glm::normalize(glm::cross(V, randomUnit()));
      const double c = 0.001 + 0.199 * u(rng);
      N = glm::normalize(V * c + side * std::sqrt(1.0 - c * c));
    } else if (glm::dot(N, V) < 0.0) {
      N = -N;
    }
    glm::dvec3 d = grazing ? glm::normalize(-V + 0.3 * randomUnit()) : randomUnit();
    if (glm::dot(N, d) < 0.0) d -= 2.0 * glm::dot(N, d) * N;  // above the surface
    if (glm::dot(N, d) < 1e-6) continue;
    const double length = 0.05 + 5.0 * u(rng);
    cases.push_back({glm::vec3(N), glm::vec3(P), glm::vec3(P + d * length), float(length * (1.05 + 2.0 * u(rng)))});
  }
  const std::vector<glm::vec3> got = shadePointsOnDevice(renderer(scene), cases);
  ASSERT_EQ(got.size(), cases.size());
  size_t compared = 0, outside = 0;
  double worst = 0.0;
  for (size_t i = 0; i < cases.size(); ++i) {
    const ShadingCase& c = cases[i];
    const glm::dvec3 ref = shading::shadePoint(glm::dvec3(1.0), 1.0, glm::dvec3(c.normal), glm::dvec3(c.position),
                                               glm::dvec3(c.light), double(c.radius), glm::dvec3(1.0));
    if (ref.x <= 1e-3) continue;
    ++compared;
    const double relative = std::abs(double(got[i].x) - ref.x) / ref.x;
    worst = std::max(worst, relative);
    outside += relative > 1e-4 ? 1 : 0;
  }
  EXPECT_GT(compared, cases.size() / 4);
  EXPECT_EQ(outside, 0u) << "worst relative error " << worst << " over " << compared << " cases";
}

}  // namespace gb
