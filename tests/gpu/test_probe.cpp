// The pixel probe: a capture's dossier equals the live frame's, a region read-back gives the
// same dossier as whole targets, light contributions match an independent CPU evaluation and the
// GPU's hdr, the stencil prediction matches the coverage counters, the shadow-map footprint
// reproduces the stored shadow term.
#include <cmath>
#include <map>
#include <set>

#include "renderer/core/camera.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"
#include "tests/support/capture_util.h"
#include "views/analysis/probe.h"
#include "views/capture/capture.h"

namespace gb {

static RenderOptions probeOptions() {
  RenderOptions o = smallCaptureOptions();
  o.fairies = false;  // sprites add light the dossier does not attribute
  return o;
}

static FrameSnapshot renderSnapshot(GpuTest& t, const Scene& scene, const RenderOptions& o) {
  std::vector<Target> all = availableTargets(o);
  t.render(scene, o, captureRequest(all, o));
  return snapshotFromRenderer(t.renderer(scene), all);
}

// A copy of w x h texels of `full` starting at (x0, y0), clipped to the target.
static TargetImage crop(const TargetImage& full, int32_t x0, int32_t y0, uint32_t w, uint32_t h) {
  TargetImage r;
  uint32_t cx0 = uint32_t(std::max(x0, 0)), cy0 = uint32_t(std::max(y0, 0));
  uint32_t cx1 = std::min<uint32_t>(full.targetWidth, uint32_t(std::max(x0 + int32_t(w), 0)));
  uint32_t cy1 = std::min<uint32_t>(full.targetHeight, uint32_t(std::max(y0 + int32_t(h), 0)));
  r.targetWidth = full.targetWidth;
  r.targetHeight = full.targetHeight;
  r.x0 = cx0;
  r.y0 = cy0;
  r.image = full.image;
  r.image.width = cx1 - cx0;
  r.image.height = cy1 - cy0;
  r.image.data.clear();
  size_t tb = full.image.texelBytes();
  for (uint32_t y = cy0; y < cy1; ++y) {
    const uint8_t* row = full.image.data.data() + (size_t(y) * full.image.width + cx0) * tb;
    r.image.data.insert(r.image.data.end(), row, row + (cx1 - cx0) * tb);
  }
  return r;
}

TEST_F(GpuTest, ProbeOfACaptureEqualsProbeOfTheLiveFrame) {
  RenderOptions o = probeOptions();
  Scene scene = builtinTemple(o.lights);
  std::vector<Target> all = availableTargets(o);
  const FrameStats& st = render(scene, o, captureRequest(all, o));
  const Renderer& r = renderer(scene);
  FrameSnapshot live = snapshotFromRenderer(r, all);
  std::string dir = freshDir("probe_capture"), error;
  CaptureMeta meta;
  meta.stats = st;
  ASSERT_TRUE(writeCapture(dir, live, meta, error)) << error;
  Capture c;
  ASSERT_TRUE(loadCapture(dir, c, error)) << error;
  int withLights = 0;
  for (uint32_t y = 1; y < o.height; y += 5)
    for (uint32_t x = 2; x < o.width; x += 7) {
      PixelDossier d = probePixel(live, x, y);
      nlohmann::json fromLive = dossierJson(d), fromCapture = dossierJson(probePixel(c.frame, x, y));
      ASSERT_EQ(fromLive, fromCapture) << "pixel " << x << "," << y;
      ASSERT_TRUE(d.missing.empty());
      // The raw values are the renderer's read-back bits (not something the probe derived).
      for (const ProbeTarget& t : d.targets) {
        Target target;
        ASSERT_TRUE(parseTarget(t.target, target));
        if (!(targetAbsence(target, o) == Absent::No)) {  // not computed under these options
          ASSERT_FALSE(t.present) << t.target;
          continue;
        }
        ASSERT_TRUE(t.present) << t.target;
        for (size_t ch = 0; ch < t.channels.size(); ++ch)
          ASSERT_EQ(t.channels[ch].bits, r.readback[size_t(target)].raw(x, y, uint32_t(ch))) << t.target;
      }
      if (d.geometry) {
        EXPECT_EQ(d.eyeDepth, r.readback[size_t(Target::Depth)].value(x, y, 0));
      }
      withLights += !d.lights.empty();
    }
  EXPECT_GT(withLights, 5) << "the probed pixels should include some under light volumes";
  // gblens probe prints the same dossier.
  RunResult run = runGblens("probe " + dir + " 37 29 --json");
  ASSERT_EQ(run.exitCode, 0) << run.output;
  EXPECT_EQ(nlohmann::json::parse(run.output), dossierJson(probePixel(live, 37, 29)));
  EXPECT_EQ(runGblens("probe " + dir + " 96 0").exitCode, 2);  // outside the frame
}

TEST_F(GpuTest, ProbeOfARegionReadBackEqualsProbeOfWholeTargets) {
  RenderOptions o = probeOptions();
  Scene scene = builtinTemple(o.lights);
  FrameSnapshot full = renderSnapshot(*this, scene, o);
  int checked = 0;
  for (auto [x, y] : {std::pair{0u, 0u}, {95u, 53u}, {48u, 30u}, {20u, 40u}, {70u, 35u}, {10u, 5u}}) {
    FrameSnapshot region = full;
    for (size_t i = 0; i < kTargetCount; ++i)
      if (screenSpaceTarget(Target(i))) region.images[i] = crop(full.images[i], int32_t(x), int32_t(y), 1, 1);
    int32_t sx = 0, sy = 0;
    bool shadow = shadowMapFootprint(full, x, y, sx, sy);
    region.target(Target::ShadowMap) = crop(full.target(Target::ShadowMap), sx, sy, shadow ? 2 : 0, shadow ? 2 : 0);
    EXPECT_EQ(region.target(Target::Hdr).image.data.size(), region.target(Target::Hdr).image.texelBytes());
    EXPECT_EQ(dossierJson(probePixel(region, x, y)), dossierJson(probePixel(full, x, y))) << x << "," << y;
    checked += shadow;
  }
  EXPECT_GT(checked, 2);
}

// The eye-space point where the ray through a pixel centre meets the plane y = 0 (analytic).
static glm::dvec3 floorHit(const Camera& v, double px, double py) {
  glm::dvec3 o = glm::dvec3(v.worldFromEye[3]);
  glm::dvec3 d = glm::dmat3(v.worldFromEye) * eyeFromEyeDepth(v, px, py, 1.0);
  return glm::dvec3(v.eyeFromWorld * glm::dvec4(o - d * (o.y / d.y), 1.0));
}

TEST_F(GpuTest, LightContributionsMatchAnIndependentEvaluationAndTheGpu) {
  Scene s = floorScene(200.0, 0.6f);
  s.materials[0].baseColor = glm::vec4(0.8f, 0.6f, 0.4f, 1.0f);
  PointLightDesc l;
  l.center = {0.3, 1.0, -0.2};
  l.radius = 3.0;
  l.color = glm::vec3(1.0f, 0.9f, 0.7f);
  l.intensity = 2.0;
  s.lights = {l};
  setCamera(s, {0.0, 6.0, 2.0}, {0.0, 0.0, 0.0}, 0.9, 0.1, 100.0);
  RenderOptions o = probeOptions();
  o.lights = 1;
  o.sky = false;
  FrameSnapshot f = renderSnapshot(*this, s, o);
  const glm::dvec3 N = glm::dmat3(f.camera.eyeFromWorld) * glm::dvec3(0, 1, 0);
  const glm::dvec3 light = glm::dvec3(f.camera.eyeFromWorld * glm::dvec4(l.center, 1.0));
  const glm::dvec3 color = glm::dvec3(l.color) * l.intensity;
  int lit = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      PixelDossier d = probePixel(f, x, y);
      ASSERT_TRUE(d.geometry);
      // Independent: analytic surface point and normal, the attenuation and Blinn-Phong written out.
      glm::dvec3 P = floorHit(f.camera, x, y), toLight = light - P;
      double d2 = glm::dot(toLight, toLight), w = std::max(0.0, 1.0 - d2 / (l.radius * l.radius));
      glm::dvec3 L = glm::normalize(toLight), V = glm::normalize(-P), H = glm::normalize(L + V);
      glm::dvec3 expected(0.0);
      if (glm::dot(N, L) > 0.0)
        expected = color * (w * w) * (d.albedo * glm::dot(N, L) + glm::dvec3(d.specular * std::pow(std::max(glm::dot(N, H), 0.0), 32.0)));
      glm::dvec3 probe = d.lights.empty() ? glm::dvec3(0.0) : d.lights[0].contribution;
      ASSERT_LE(d.lights.size(), 1u);
      for (int c = 0; c < 3; ++c) {
        // Tolerance: the stored half normal (2^-11, amplified by the specular exponent) and the
        // float eye depth; measured worst 3e-4 relative.
        ASSERT_NEAR(probe[c], expected[c], 1e-3 * expected[c] + 1e-4) << x << "," << y << " channel " << c;
        // The GPU's sum equals the dossier's point-light total: fp16 storage (2^-11) plus the
        // GPU's sRGB decode of the stored albedo, which may differ from the exact one by half an
        // 8-bit step (0.5% of the diffuse term at albedo 0.8; see test_frame's shadow test).
        ASSERT_NEAR(d.hdr[c], d.pointLightTotal[c] + d.directional[c], 6e-3 * d.hdr[c] + 2e-4) << x << "," << y;
      }
      lit += expected.x > 1e-3;
    }
  EXPECT_GT(lit, 300);
}

TEST_F(GpuTest, StencilPredictionAndShadowFootprintAgreeWithTheGpu) {
  for (StencilMask mask : {StencilMask::PerLight, StencilMask::Shared}) {
    RenderOptions o = probeOptions();
    o.lights = 64;
    o.shadowMapSize = 512;
    o.method = Method::Deferred;  // the stencil masks are deferred's (auto may pick another method)
    o.stencilMask = mask;
    Scene scene = builtinTemple(o.lights);
    FrameSnapshot f = renderSnapshot(*this, scene, o);
    int pixels = 0, maskedWrong = 0, fullWrong = 0, geometry = 0, shadowWrong = 0, hdrWrong = 0;
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        PixelDossier d = probePixel(f, x, y);
        ++pixels;
        maskedWrong += int64_t(d.shadedLights) != d.coverageMasked;
        fullWrong += int64_t(d.lights.size()) != d.coverageFull;
        if (!d.geometry) continue;
        ++geometry;
        ASSERT_TRUE(d.shadowMap.valid);
        shadowWrong += std::abs(d.shadowMap.filtered - d.shadow) > 0.05;
        for (int c = 0; c < 3; ++c)
          hdrWrong += std::abs(d.hdr[c] - d.hdrExpected[c]) > 5e-3 * d.hdr[c] + 2e-3;
      }
    // Rasterization samples pixel centres like the probe's ray; allow a few pixels on volume
    // edges and shadow-map texel edges where float rounding decides (measured: none).
    EXPECT_LE(maskedWrong, pixels / 500) << name(mask);
    EXPECT_LE(fullWrong, pixels / 500) << name(mask);
    EXPECT_LE(shadowWrong, geometry / 500) << name(mask);
    EXPECT_LE(hdrWrong, geometry / 500) << name(mask);
  }
}

}  // namespace gb

namespace gb {

// "Why is this pixel lit" (issue 17, section 5): five point lights placed by hand around the
// surface points of a floor, each with a known fate by construction — lights it, faces away (below
// the floor, the sphere reaching the point), out of range (2.5 units above, radius 2), outside the
// frustum (two radii beyond the left edge of the view, beside a pixel of the left column), and
// sub-pixel (radius 0.001, 0.003 beside the surface point: its projection holds no pixel centre).
// The ledger lists each with that fate, and its contributions add up to the dossier's total.
TEST_F(GpuTest, TheLightLedgerSaysWhyEachConstructedLightDoesOrDoesNotLightThePixel) {
  Scene s = floorScene(200.0, 0.6f);
  setCamera(s, {0.0, 6.0, 2.0}, {0.0, 0.0, 0.0}, 0.9, 0.1, 100.0);
  RenderOptions o = probeOptions();
  o.sky = false;
  // The camera as the renderer makes it, to place the lights from pixels.
  FrameSnapshot plain = renderSnapshot(*this, s, o);
  const Camera& cam = plain.camera;
  const uint32_t cx = o.width / 2, cy = o.height / 2, ey = o.height / 2;
  auto world = [&](const glm::dvec3& eye) { return glm::dvec3(cam.worldFromEye * glm::dvec4(eye, 1.0)); };
  const glm::dvec3 P = world(floorHit(cam, cx, cy)), edge = floorHit(cam, 0, ey);  // pixel indices (centres inside)
  const glm::dmat4& p = cam.clipFromEye;
  // The left side plane (x_clip >= -w): outward normal (-P00, 0, 1 - P20) in eye space.
  const glm::dvec3 outward = glm::normalize(glm::dvec3(-p[0][0], 0.0, 1.0 - p[2][0]));
  auto light = [](glm::dvec3 c, double r) {
    PointLightDesc l;
    l.center = c;
    l.radius = r;
    l.color = glm::vec3(1.0f, 0.8f, 0.6f);
    return l;
  };
  s.lights = {light(P + glm::dvec3(0.0, 1.0, 0.0), 3.0),     // 0: lights the centre pixel
              light(P + glm::dvec3(0.0, -0.5, 0.0), 3.0),    // 1: below the floor: N.L < 0
              light(P + glm::dvec3(0.0, 2.5, 0.0), 2.0),     // 2: out of range
              light(world(edge + 1.0 * outward), 0.5),       // 3: outside the frustum
              light(P + glm::dvec3(0.003, 0.0015, 0.0), 0.001)};  // 4: sub-pixel, beside the centre ray
  o.lights = int(s.lights.size());
  FrameSnapshot f = renderSnapshot(*this, s, o);
  std::map<uint32_t, std::string> fates;
  PixelDossier d = probePixel(f, cx, cy);
  ASSERT_TRUE(d.geometry);
  ASSERT_FALSE(d.ledger.entries.empty());
  EXPECT_EQ(d.ledger.entries[0].light, "sun");
  glm::dvec3 sum(0.0);
  for (const LedgerEntry& e : d.ledger.entries)
    if (e.light == "point") {
      fates[e.index] = e.fate;
      sum += e.contribution;
    }
  EXPECT_EQ(fates[0], "shaded");
  EXPECT_EQ(fates[1], "facing_away");
  EXPECT_EQ(fates[2], "out_of_range");
  EXPECT_EQ(fates[4], "sub_pixel");
  for (int c = 0; c < 3; ++c) EXPECT_DOUBLE_EQ(sum[c], d.pointLightTotal[c]);
  EXPECT_GT(sum.r, 0.0);
  // The frustum-culled light is listed at the left edge's pixel (within 4 radii of its surface point).
  PixelDossier e = probePixel(f, 0, ey);
  bool frustum = false;
  for (const LedgerEntry& l : e.ledger.entries) frustum |= l.light == "point" && l.index == 3 && l.fate == "frustum_culled";
  EXPECT_TRUE(frustum) << dossierJson(e)["lighting"]["ledger"].dump(1);
  // The JSON (probe --json, Copy as JSON) holds the ledger.
  const nlohmann::json j = dossierJson(d)["lighting"]["ledger"];
  EXPECT_EQ(j["entries"].size(), d.ledger.entries.size());
  EXPECT_FALSE(j["rule"].get<std::string>().empty());
}

// The sun's entry: on the temple, a pixel whose stored shadow term is 0 with N.L > 0 is
// "shadowed" (the shadow-map lookup's figures in the rule), one with shadow 1 is "lit".
TEST_F(GpuTest, TheLightLedgerSaysTheSunIsShadowedWhereTheShadowMapSaysSo) {
  Scene s = builtinTemple(0);
  RenderOptions o = probeOptions();
  o.lights = 0;
  FrameSnapshot f = renderSnapshot(*this, s, o);
  int shadowed = 0, lit = 0;
  for (uint32_t y = 0; y < o.height; y += 3)
    for (uint32_t x = 0; x < o.width; x += 3) {
      PixelDossier d = probePixel(f, x, y);
      if (!d.geometry || d.ledger.entries.empty()) continue;
      const LedgerEntry& sun = d.ledger.entries[0];
      ASSERT_EQ(sun.light, "sun");
      const double nDotL = glm::dot(d.normal, f.sunEyeDirection());
      if (nDotL <= 0.0) {
        EXPECT_EQ(sun.fate, "facing_away") << x << "," << y;
      } else if (d.shadow == 0.0) {
        EXPECT_EQ(sun.fate, "shadowed") << x << "," << y;
        EXPECT_NE(sun.why.find("shadow-map lookup"), std::string::npos) << sun.why;
        ++shadowed;
      } else if (d.shadow == 1.0) {
        EXPECT_EQ(sun.fate, "lit") << x << "," << y;
        ++lit;
      }
    }
  EXPECT_GT(shadowed, 5);
  EXPECT_GT(lit, 5);
}

// Where each method put a light (issue 17, section 5): nine lights over one floor point, every
// volume covering the centre pixel. The per-light mask gives them one stencil bit each within a
// batch of 7 (renderer/passes/point_lights.cpp): without layers the light at visible position k
// has batch k / 7 and bit k % 7; with layers, volumes over the same pixel never share a layer, so
// no two of the nine may name the same batch and bit. Clustered names the pixel's tile and the
// depth slice of Olsson et al.'s formula, k = floor(ln(depth / near) / ln(1 + 2 tan(fovy / 2) / tiles)).
TEST_F(GpuTest, TheLightLedgerNamesEachLightsStencilBatchBitLayerAndCluster) {
  Scene s = floorScene(200.0, 0.6f);
  setCamera(s, {0.0, 6.0, 2.0}, {0.0, 0.0, 0.0}, 0.9, 0.1, 100.0);
  RenderOptions o = probeOptions();
  o.sky = false;
  const Camera cam = renderSnapshot(*this, s, o).camera;
  const uint32_t cx = o.width / 2, cy = o.height / 2;
  const glm::dvec3 Pe = floorHit(cam, cx, cy), P = glm::dvec3(cam.worldFromEye * glm::dvec4(Pe, 1.0));
  for (int i = 0; i < 9; ++i) {
    PointLightDesc l;
    l.center = P + glm::dvec3(0.1 * i - 0.4, 0.8, 0.05 * i);
    l.radius = 2.0;
    l.color = glm::vec3(1.0f);
    s.lights.push_back(l);
  }
  o.lights = 9;
  for (StencilLayers layers : {StencilLayers::Off, StencilLayers::On}) {
    o.stencilLayers = layers;
    FrameSnapshot f = renderSnapshot(*this, s, o);
    ASSERT_EQ(f.stencilCount, 9u) << "every light in the stencil class";
    PixelDossier d = probePixel(f, cx, cy);
    std::set<std::string> slots;
    for (const LedgerEntry& e : d.ledger.entries) {
      if (e.light != "point") continue;
      EXPECT_EQ(e.fate, "shaded") << e.index;
      const size_t at = e.drawnAs.find("batch ");
      ASSERT_NE(at, std::string::npos) << e.drawnAs;
      const std::string slot = e.drawnAs.substr(at, e.drawnAs.find(',', e.drawnAs.find("bit")) - at);
      EXPECT_TRUE(slots.insert(slot).second) << "two lights over one pixel share " << slot;
      if (layers == StencilLayers::Off) {
        const size_t k = std::find(f.visibleLights.begin(), f.visibleLights.end(), e.index) - f.visibleLights.begin();
        EXPECT_EQ(slot, "batch " + std::to_string(k / 7) + ", stencil bit " + std::to_string(k % 7)) << e.drawnAs;
      } else {
        EXPECT_NE(e.drawnAs.find("layer "), std::string::npos) << e.drawnAs;
      }
    }
    EXPECT_EQ(slots.size(), 9u);
  }
  o.method = Method::Clustered;
  o.clusterAssign = ClusterAssign::Gpu;
  FrameSnapshot f = renderSnapshot(*this, s, o);
  const double tiles = std::ceil(cam.height / 16.0);
  const double k = std::log(-Pe.z / cam.znear) / std::log(1.0 + 2.0 * std::tan(cam.yfov / 2.0) / tiles);
  ASSERT_GT(std::abs(k - std::round(k)), 1e-3) << "the point lies on a slice boundary: move it";
  const std::string cluster = "cluster (" + std::to_string(cx / 16) + ", " + std::to_string(cy / 16) +
                              ", depth slice " + std::to_string(int(std::floor(k))) + ")";
  PixelDossier d = probePixel(f, cx, cy);
  int named = 0;
  for (const LedgerEntry& e : d.ledger.entries) {
    if (e.light != "point") continue;
    EXPECT_EQ(e.drawnAs, cluster);
    ++named;
  }
  EXPECT_EQ(named, 9);

  // The cluster grid: 32-pixel tiles, 64 slices exponential over the visible lights' depths.
  o.clusterAssign = ClusterAssign::Cpu;
  f = renderSnapshot(*this, s, o);
  ASSERT_TRUE(f.clusterGrid);
  double lo = 1e30, hi = 0.0;
  for (uint32_t i : f.visibleLights) {
    const glm::vec4 l = f.eyeLights[i].eyePositionRadius;
    lo = std::min(lo, double(-l.z - l.w));
    hi = std::max(hi, double(-l.z + l.w));
  }
  lo = std::clamp(lo, cam.znear, cam.zfar);
  hi = std::clamp(hi, lo * 1.01, cam.zfar);
  const double g = 64.0 * std::log(-Pe.z / lo) / std::log(hi / lo);
  ASSERT_GT(std::abs(g - std::round(g)), 1e-3) << "the point lies on a grid slice boundary: move it";
  const std::string cell = "cluster grid cell (" + std::to_string(cx / 32) + ", " + std::to_string(cy / 32) +
                           ", depth slice " + std::to_string(int(std::floor(g))) + "), listed on the CPU";
  d = probePixel(f, cx, cy);
  named = 0;
  for (const LedgerEntry& e : d.ledger.entries) {
    if (e.light != "point") continue;
    EXPECT_EQ(e.drawnAs, cell);
    ++named;
  }
  EXPECT_EQ(named, 9);
}

}  // namespace gb
