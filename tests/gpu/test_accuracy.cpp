// The GPU frame against the double-precision reference, pixel by pixel on surface pixels (same
// triangle in both), with tolerances derived from each storage format plus the rasterizer's
// sub-pixel vertex snapping (the attribute's change per pixel times the snap step). Rounding:
// Vulkan lets a conversion to a float format land on either neighbour (one ulp; llvmpipe
// truncates), and says conversions to normalized formats should round to nearest (half a step).
#include <cmath>

#include "renderer/core/codec.h"
#include "renderer/reference/reference.h"
#include "renderer/scene/builtin.h"
#include "renderer/scene/mesh_builder.h"
#include "tests/gpu/gpu_test.h"
#include "views/analysis/accuracy.h"

namespace gb {

namespace {

RenderOptions accuracyOptions() {
  RenderOptions o;
  o.width = 160;
  o.height = 90;
  o.lights = 16;
  o.fairies = false;
  return o;
}

// Largest change of f from a pixel to its 4-neighbours, on the plane of the pixel's triangle
// (extrapolated past its edges: thin triangles seen edge-on change fastest across them).
template <class F>
double changePerPixel(const ReferenceCache& cache, const reference::Frame& f, uint32_t x, uint32_t y, F value) {
  const reference::Surface& s = f.at(x, y);
  double g = 0.0;
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    int nx = int(x) + dx[k], ny = int(y) + dy[k];
    if (nx < 0 || ny < 0) continue;
    reference::Surface n =
        reference::surfaceOnTriangle(cache.rays(), f.camera, s.instance, s.triangle, uint32_t(nx), uint32_t(ny));
    if (n.hit) g = std::max(g, value(n, s));
  }
  return g;
}

double ulp(double v) { return double(std::nextafter(float(std::abs(v)), INFINITY)) - double(float(std::abs(v))); }

}  // namespace

class Accuracy : public GpuTest {
 protected:
  // Rasterizer vertex snapping: each vertex moves up to half a sub-pixel step in x and y, which
  // shifts an interpolated attribute by at most its per-pixel change times this.
  double snap() const { return std::sqrt(2.0) * std::ldexp(0.5, -int(ctx().properties.limits.subPixelPrecisionBits)); }
  // Reference surface pixels that the GPU saw on the same triangle.
  bool surface(const Renderer& r, const reference::Frame& f, uint32_t x, uint32_t y) const {
    const reference::Surface& s = f.at(x, y);
    return s.hit && r.readback[size_t(Target::PrimitiveId)].raw(x, y, 0) == s.primitiveId;
  }
};

TEST_F(Accuracy, GBufferMatchesTheReferenceWithinEachNormalFormat) {
  ASSERT_TRUE(ctx().features.primitiveId);
  Scene scene = builtinTemple(16);
  ReferenceCache cache(scene);
  // Largest angle (radians) from storing a unit normal, per format: one rounding of each stored
  // component, through the decode.
  const std::pair<NormalFormat, double> formats[] = {
      {NormalFormat::Rgba16f, std::sqrt(3.0) * std::ldexp(1.0, -11)},      // fp16: an ulp <= 2^-11 below 1
      {NormalFormat::Rgba8Snorm, std::sqrt(3.0) * 0.5 / 127.0},             // snorm8: step 1/127
      {NormalFormat::OctRg16, std::sqrt(18.0) * 0.5 / 32767.0},             // snorm16 octahedral: stretch <= sqrt(18)
      {NormalFormat::Rgb10a2, std::sqrt(3.0) * 2.0 * 0.5 / 1023.0}};        // unorm10 of n*0.5+0.5
  for (auto [format, bound] : formats) {
    RenderOptions o = accuracyOptions();
    o.normalFormat = format;
    FrameError e = measureFrame(source(scene), o, cache).error;
    Renderer& r = renderer(scene);
    ReferenceView ref = cache.get(r.camera, o.time, kShadowBandTexels, o.shadowMapSize);
    const reference::Frame& f = *ref.frame;
    const CpuImage& ns = r.readback[size_t(Target::NormalShadow)];
    int checked = 0;
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        if (!surface(r, f, x, y)) continue;
        const reference::Surface& s = f.at(x, y);
        glm::dvec3 n = decodeNormalTexel(ns, x, y, format).unit;
        double angle = std::atan2(glm::length(glm::cross(n, s.normal)), glm::dot(n, s.normal));
        double change = changePerPixel(cache, f, x, y, [](auto& a, auto& b) { return glm::length(a.normal - b.normal); });
        ASSERT_LE(angle, bound + change * snap() + 1e-5) << name(format) << " pixel " << x << "," << y;
        if (format == NormalFormat::OctRg16) {
          ASSERT_EQ(ns.raw(x, y, 2), 0u);  // the normal is x, y only
        }
        ++checked;
      }
    EXPECT_GT(checked, int(o.width * o.height / 2)) << name(format);
    EXPECT_LT(e.silhouette + e.coverageOnlyGpu + e.coverageOnlyReference, uint64_t(0.03 * o.width * o.height));
  }
}

TEST_F(Accuracy, AlbedoSpecularAndEyeDepthMatchTheReferenceToTheirStorage) {
  Scene scene = builtinTemple(16);
  ReferenceCache cache(scene);
  RenderOptions o = accuracyOptions();
  measureFrame(source(scene), o, cache).error;
  Renderer& r = renderer(scene);
  const reference::Frame& f = *cache.get(r.camera, o.time, kShadowBandTexels, o.shadowMapSize).frame;
  const CpuImage& albedo = r.readback[size_t(Target::AlbedoSpecular)];
  const CpuImage& depth = r.readback[size_t(Target::Depth)];
  int untextured = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      if (!surface(r, f, x, y)) continue;
      const reference::Surface& s = f.at(x, y);
      // 8-bit sRGB albedo and UNORM specular: the nearest step, so within half a step (plus a
      // hundredth of a step for the GPU's float encode). Textured albedo depends on the
      // sampler's level-of-detail arithmetic and is reported by `gblens error`, not checked here.
      if (!s.textured) {
        for (int c = 0; c < 3; ++c) {
          double v = s.albedo[c];
          double exact = (v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055) * 255.0;
          ASSERT_LE(std::abs(albedo.raw(x, y, c) - exact), 0.51) << "albedo " << x << "," << y;
        }
        ++untextured;
      }
      ASSERT_LE(std::abs(albedo.raw(x, y, 3) - s.specular * 255.0), 0.51) << "specular " << x << "," << y;
      // Eye depth: a float32 varying. The vertex transform rounds each term (|P| * 2^-24 each),
      // interpolation adds a few ulps, and vertex snapping moves the surface.
      double d = depth.value(x, y, 0);
      double change = changePerPixel(cache, f, x, y, [](auto& a, auto& b) { return std::abs(a.eyeDepth - b.eyeDepth); });
      double tol = 4.0 * ulp(s.eyeDepth) + 3.0 * std::ldexp(glm::length(s.eye), -24) + change * snap();
      ASSERT_LE(std::abs(d - s.eyeDepth), tol) << "eye depth " << x << "," << y;
    }
  EXPECT_GT(untextured, 2000);
}

// Reconstruction from each hardware depth format: the stored depth's quantization (D32F: a few
// float ulps of the interpolated depth; D24: one 2^-24 step) through the projection's slope.
TEST_F(Accuracy, PositionsFromEveryDepthFormatAndStoredPositionsMatchTheReference) {
  Scene scene = builtinTemple(0);
  ReferenceCache cache(scene);
  struct Case {
    const char* what;
    bool reversed;
    DepthFormat format;
    PositionSource position;
    PositionSpace space;
  };
  const Case cases[] = {{"d32 standard", false, DepthFormat::D32S8, PositionSource::Depth, PositionSpace::World},
                        {"d32 reversed", true, DepthFormat::D32S8, PositionSource::Depth, PositionSpace::World},
                        {"d24 standard", false, DepthFormat::D24S8, PositionSource::Depth, PositionSpace::World},
                        {"rgba16f world", false, DepthFormat::D32S8, PositionSource::Rgba16f, PositionSpace::World},
                        {"rgba32f camera", false, DepthFormat::D32S8, PositionSource::Rgba32f, PositionSpace::Camera}};
  for (const Case& c : cases) {
    RenderOptions o = accuracyOptions();
    o.lights = 0;
    o.reversedZ = c.reversed;
    o.depthFormat = c.format;
    o.eyeDepth = false;
    o.position = c.position;
    o.positionSpace = c.space;
    FrameError e = measureFrame(source(scene), o, cache).error;
    Renderer& r = renderer(scene);
    const reference::Frame& f = *cache.get(r.camera, o.time, kShadowBandTexels, o.shadowMapSize).frame;
    const CpuImage& hw = r.readback[size_t(Target::DepthStencil)];
    const CpuImage* stored = c.position != PositionSource::Depth ? &r.readback[size_t(Target::Position)] : nullptr;
    int checked = 0;
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        if (!surface(r, f, x, y)) continue;
        const reference::Surface& s = f.at(x, y);
        double change = changePerPixel(cache, f, x, y, [](auto& a, auto& b) { return glm::length(a.eye - b.eye); });
        double moved = change * snap();
        if (stored) {
          // Each component rounded to the format (an ulp), formed in float from the camera-relative
          // eye position (|P| * 2^-22).
          glm::dvec3 ref = c.space == PositionSpace::World ? s.world : s.world - glm::dvec3(r.camera.worldFromEye[3]);
          for (int k = 0; k < 3; ++k) {
            double v = std::abs(ref[k]);
            double step = c.position == PositionSource::Rgba16f ? std::ldexp(1.0, std::ilogb(std::max(v, 6.2e-5)) - 10)
                                                                : ulp(v);
            double tol = step + std::ldexp(glm::length(s.world) + glm::length(s.eye), -22) + moved;
            ASSERT_LE(std::abs(stored->value(x, y, k) - ref[k]), tol) << c.what << " " << x << "," << y << " axis " << k;
          }
        } else {
          double z = s.eyeDepth, eps = 1e-6 * z;
          double slope = std::abs(hardwareDepth(r.camera, {0, 0, -(z + eps)}) - hardwareDepth(r.camera, {0, 0, -z})) / eps;
          double d = hardwareDepth(r.camera, s.eye);
          double step = c.format == DepthFormat::D24S8 ? std::ldexp(1.0, -24) : 4.0 * ulp(d);
          double tol = step / slope * glm::length(s.eye) / z + 1e-6 * glm::length(s.eye) + moved;
          glm::dvec3 p = shaderEyeFromHardwareDepth(r.frameData, x, y, float(hw.value(x, y, 0)));
          ASSERT_LE(glm::length(p - s.eye), tol) << c.what << " " << x << "," << y;
        }
        ++checked;
      }
    EXPECT_GT(checked, 5000) << c.what;
    EXPECT_GT(e.used.relative.count, 5000u);
  }
}

// The lighting passes alone (the reference's formulas on the GPU's own G-buffer): each write or
// blend rounds the running sum to the accumulation format, by up to one ulp (Vulkan leaves the
// rounding mode open; llvmpipe truncates fp16): 2^-10 relative for fp16, 2^-23 for fp32. So the
// error is at most one ulp per contribution of the sum of their magnitudes, plus float shading
// (pow(n.h, 32) amplifies the float error of n.h 32 times: ~1e-5). Values below 2^-14 are
// measured against 2^-14.
TEST_F(Accuracy, LightingPassesAccumulateWithinOneRoundingPerContribution) {
  Scene scene = builtinTemple(64);
  ReferenceCache cache(scene);
  for (auto [format, rounding] : {std::pair{AccumFormat::Rgba16f, std::ldexp(1.0, -10)},
                                  std::pair{AccumFormat::Rgba32f, std::ldexp(1.0, -23)}}) {
    RenderOptions o = accuracyOptions();
    o.lights = 64;
    o.accumFormat = format;
    FrameError e = measureFrame(source(scene), o, cache).error;
    EXPECT_GT(e.lighting.perContribution.count, 5000u);
    EXPECT_GT(e.lighting.maxContributions, 3u);
    EXPECT_LE(e.lighting.perContribution.max, rounding + 1e-5) << name(format);
  }
}

TEST_F(Accuracy, PrimitiveIdIsOffByDefaultAndNamesTheReferenceTriangle) {
  Scene scene = builtinTemple(0);
  RenderOptions o = accuracyOptions();
  render(scene, o, {{Target::PrimitiveId}});
  EXPECT_EQ(renderer(scene).readback[size_t(Target::PrimitiveId)].width, 1u);  // not written: a 1x1 stand-in
  ReferenceCache cache(scene);
  FrameError e = measureFrame(source(scene), o, cache).error;
  ASSERT_TRUE(e.primitiveIds);
  const uint64_t total = uint64_t(o.width) * o.height;
  EXPECT_GT(e.surface, total / 2);
  // Silhouettes are a thin line around objects: a few percent of the pixels at this size.
  EXPECT_LT(e.silhouette + e.coverageOnlyGpu + e.coverageOnlyReference, total * 3 / 100);
}

// An open, single-sided card facing the sun must cast its shadow (the shadow pass culls faces
// turned away from the sun, so the winding of the light's projection must match the camera's),
// and the shadow term must agree with the exact ray-traced one outside the penumbra band.
// A floor under a 2x2 single-sided card at y = 2 (material 0), facing up or down, lit by a high sun.
static Scene cardOverFloor(bool facingUp) {
  Scene scene = floorScene(10.0);
  MeshBuilder b{scene};
  b.begin("card", 0);
  if (facingUp)
    b.quad({-1.0f, 2.0f, 1.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, -2.0f});
  else
    b.quad({-1.0f, 2.0f, -1.0f}, {2.0f, 0.0f, 0.0f}, {0.0f, 0.0f, 2.0f});
  b.end();
  scene.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
  computeBounds(scene);
  scene.sun.enabled = true;
  scene.sun.toSun = glm::normalize(glm::dvec3(0.2, 1.0, 0.1));
  scene.sky.ambient = glm::vec3(0.2f);
  setCamera(scene, {0.0, 6.0, 7.0}, {0.0, 0.0, 0.0});
  return scene;
}

TEST_F(Accuracy, AnOpenSingleSidedCardCastsTheExactShadow) {
  Scene scene = cardOverFloor(true);
  ReferenceCache cache(scene);
  RenderOptions o = accuracyOptions();
  o.lights = 0;
  FrameError e = measureFrame(source(scene), o, cache).error;
  Renderer& r = renderer(scene);
  // The floor point under the card's centre, along the sun: shadowed; a point 4 units aside: lit.
  glm::dvec3 under = glm::dvec3(0.0, 2.0, 0.0) - scene.sun.toSun * (2.0 / scene.sun.toSun.y);
  auto shadowAt = [&](glm::dvec3 world) {
    glm::dvec4 c = r.camera.clipFromWorld * glm::dvec4(world, 1.0);
    uint32_t x = uint32_t((c.x / c.w + 1.0) * 0.5 * o.width), y = uint32_t((c.y / c.w + 1.0) * 0.5 * o.height);
    return r.readback[size_t(Target::NormalShadow)].value(x, y, 3);
  };
  EXPECT_EQ(shadowAt(under), 0.0);
  EXPECT_EQ(shadowAt(under + glm::dvec3(4.0, 0.0, 0.0)), 1.0);
  EXPECT_GT(e.shadow.compared, 3000u);
  EXPECT_LT(e.shadow.fraction, 0.005) << e.shadow.mismatched << " of " << e.shadow.compared;
}

// The same card turned away from the sun: the shadow pass culls it (single-sided), and the
// reference's shadow rays skip single-sided faces turned away from the sun too, so neither
// shadows the floor (a sky dome seen from inside: VC's sun was blocked in the reference only).
TEST_F(Accuracy, ASingleSidedCardTurnedAwayFromTheSunCastsNoShadowInEither) {
  Scene scene = cardOverFloor(false);
  ASSERT_FALSE(scene.materials[0].doubleSided);
  ReferenceCache cache(scene);
  RenderOptions o = accuracyOptions();
  o.lights = 0;
  FrameError e = measureFrame(source(scene), o, cache).error;
  EXPECT_GT(e.shadow.compared, 3000u);
  // The card's shadow would be ~2% of the compared pixels if either side cast it.
  EXPECT_LT(e.shadow.fraction, 0.005) << e.shadow.falseLight << " false light, " << e.shadow.falseShadow
                                      << " false shadow of " << e.shadow.compared;
}

// The normal-map path (material.glsl: tangent frame, normal scale): a constant tilted normal
// texture on a floor, so texture filtering cannot differ; the GPU's normal must match the
// reference's to the normal format's bound plus float arithmetic.
TEST_F(Accuracy, NormalMappedSurfaceMatchesTheReference) {
  Scene scene = floorScene(10.0);
  Texture t;
  t.name = "tilted";
  t.width = t.height = 4;
  t.srgb = false;
  for (int i = 0; i < 16; ++i) t.rgba8.insert(t.rgba8.end(), {200, 90, 220, 255});
  scene.textures.push_back(t);
  scene.materials[0].normalTexture = 0;
  scene.materials[0].normalScale = 0.8f;
  setCamera(scene, {1.0, 4.0, 6.0}, {0.0, 0.0, 0.0});
  ReferenceCache cache(scene);
  RenderOptions o = accuracyOptions();
  o.lights = 0;
  measureFrame(source(scene), o, cache).error;
  Renderer& r = renderer(scene);
  const reference::Frame& f = *cache.get(r.camera, o.time, kShadowBandTexels, o.shadowMapSize).frame;
  const CpuImage& ns = r.readback[size_t(Target::NormalShadow)];
  const glm::dvec3 up = glm::dmat3(r.camera.eyeFromWorld) * glm::dvec3(0, 1, 0);
  int checked = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      if (!surface(r, f, x, y)) continue;
      const reference::Surface& s = f.at(x, y);
      ASSERT_GT(std::acos(std::min(1.0, glm::dot(s.normal, up))), 0.2);  // the map really tilts it
      glm::dvec3 n = decodeNormalTexel(ns, x, y, o.normalFormat).unit;
      double angle = std::atan2(glm::length(glm::cross(n, s.normal)), glm::dot(n, s.normal));
      ASSERT_LE(angle, std::sqrt(18.0) * 0.5 / 32767.0 + 1e-5) << x << "," << y;
      ++checked;
    }
  EXPECT_GT(checked, int(o.width * o.height / 2));
}

}  // namespace gb
