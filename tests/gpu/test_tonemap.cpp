// The tone map in compute (tonemap_compute, --tonemap-pass compute: sRGB encoded in the shader,
// final written through its UNORM storage view) against the raster pass (the sRGB attachment
// encodes): the same final image within one code per channel, and both against shading.h's
// toneMap and the sRGB curve computed in double for every pixel, NaN, Inf and overexposed
// pixels included.
#include <cmath>
#include <cstdio>
#include <limits>

#include "renderer/scene/builtin.h"
#include "shaders/shading.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace {

// How far final's code may be from the exact code, in 8-bit steps: half a step of rounding plus
// the sRGB transfer's own error. Raster: the attachment's encoder; Vulkan names the curve (the
// Khronos Data Format Specification) but no bound, Direct3D 10+ requires 0.1 beyond rounding, and
// llvmpipe documents its approximation as within +-0.17 (lp_bld_format_srgb.c), the larger.
// Compute: our fp32 curve (GLSL pow: ~1e-6 relative, below 0.01 of a step), then the UNORM store
// (Vulkan: implementations should round to nearest).
constexpr double kRasterSteps = 0.5 + 0.17;
constexpr double kComputeSteps = 0.5 + 0.01;

double srgbEncode(double c) { return c <= 0.0031308 ? 12.92 * c : 1.055 * std::pow(c, 1.0 / 2.4) - 0.055; }

// final's code for one hdr channel, in double: NaN -> 0 as both passes do, then toneMap.
double exactCode(float hdr, double exposure) {
  const double x = std::isnan(hdr) ? 0.0 : double(hdr);
  return 255.0 * srgbEncode(shading::toneMap(glm::dvec3(x), exposure).x);
}

struct Deviation {
  double worst = 0.0;  // |code - exact code|, 8-bit steps
  size_t nan = 0, overexposed = 0;
};

Deviation againstDouble(const CpuImage& hdr, const CpuImage& final, double exposure, double bound,
                        const std::string& what) {
  Deviation d;
  for (uint32_t y = 0; y < hdr.height; ++y)
    for (uint32_t x = 0; x < hdr.width; ++x) {
      for (uint32_t c = 0; c < 3; ++c) {
        const float h = float(hdr.value(x, y, c));
        d.nan += std::isnan(h);
        d.overexposed += !std::isnan(h) && h * exposure > 20.0;
        const double err = std::abs(double(final.raw(x, y, c)) - exactCode(h, exposure));
        d.worst = std::max(d.worst, err);
        EXPECT_LE(err, bound) << what << " pixel " << x << "," << y << " channel " << c << " hdr " << h;
      }
      EXPECT_EQ(final.raw(x, y, 3), 255u) << what;
    }
  return d;
}

}  // namespace

TEST_F(GpuTest, ComputeToneMapMatchesTheRasterPassAndToneMapInDouble) {
  Scene scene = builtinTemple(32);
  scene.generatedLights = false;
  // A light of NaN colour and one far too bright over the floor in view: NaN, Inf and overexposed hdr.
  PointLightDesc bad;
  bad.center = {-2.0, 0.8, 3.0};
  bad.radius = 2.0;
  bad.color = glm::vec3(std::numeric_limits<float>::quiet_NaN(), 1.0f, 1.0f);
  scene.lights.push_back(bad);
  bad.center = {3.0, 0.8, 2.0};
  bad.color = glm::vec3(1.0f);
  bad.intensity = 1e36;
  scene.lights.push_back(bad);
  RenderOptions o;
  o.width = 96;
  o.height = 54;
  o.exposure = 1.7;
  o.fairies = true;
  o.lightSetup = LightSetup::Cpu;
  const double exposure = double(float(o.exposure));  // as the shaders get it
  const std::vector<Target> targets = {Target::Hdr, Target::Final};
  for (Method m : {Method::Tiled, Method::Clustered, Method::Deferred}) {
    const std::string what = name(m);
    o.method = m;
    o.tonemapPass = TonemapPass::Raster;
    const FrameStats raster = render(scene, o, {targets});
    ASSERT_TRUE(passRan(raster, "tonemap") && !passRan(raster, "tonemap_compute")) << what;
    const CpuImage hdrA = renderer(scene).readback[size_t(Target::Hdr)];
    const CpuImage finalA = renderer(scene).readback[size_t(Target::Final)];
    o.tonemapPass = TonemapPass::Compute;
    const FrameStats compute = render(scene, o, {targets});
    ASSERT_TRUE(passRan(compute, "tonemap_compute") && !passRan(compute, "tonemap")) << what;
    const CpuImage& hdrB = renderer(scene).readback[size_t(Target::Hdr)];
    const CpuImage& finalB = renderer(scene).readback[size_t(Target::Final)];
    size_t differing = 0, sameHdr = 0;
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        bool differs = false;
        for (uint32_t c = 0; c < 4; ++c) {
          const uint32_t a = finalA.raw(x, y, c), b = finalB.raw(x, y, c);
          EXPECT_LE(a > b ? a - b : b - a, 1u) << what << " pixel " << x << "," << y << " channel " << c;
          differs |= a != b;
          sameHdr += hdrA.raw(x, y, c) == hdrB.raw(x, y, c);
        }
        differing += differs;
      }
    ASSERT_EQ(sameHdr, size_t(o.width) * o.height * 4) << what << ": both frames tone-map the same hdr";
    const Deviation dr = againstDouble(hdrA, finalA, exposure, kRasterSteps, what + " raster");
    const Deviation dc = againstDouble(hdrB, finalB, exposure, kComputeSteps, what + " compute");
    EXPECT_GT(dr.nan, 0u) << what << ": the NaN light shows in hdr";
    EXPECT_GT(dr.overexposed, 0u) << what;
    std::printf("[tonemap] %s: %zu of %u pixels differ by one code; worst vs double: raster %.3f, compute %.3f steps "
                "(%zu NaN, %zu overexposed channels)\n",
                what.c_str(), differing, o.width * o.height, dr.worst, dc.worst, dr.nan, dr.overexposed);
    RecordProperty(what + "_differing_pixels", int(differing));
  }
}

// Where the tone map runs and why, in the pass list: auto is compute only for tiled and clustered
// on a GPU device; the single-pass path always tone-maps in its last subpass.
TEST_F(GpuTest, TheToneMapSaysWhereItRan) {
  Scene scene = builtinTemple(8);
  RenderOptions o;
  o.width = 64;
  o.height = 36;
  o.method = Method::Clustered;
  const FrameStats& autoPick = render(scene, o);
  EXPECT_EQ(passRan(autoPick, "tonemap_compute"), !ctx().isCpu);
  EXPECT_EQ(passRan(autoPick, "tonemap"), ctx().isCpu);
  for (const PassStat& p : autoPick.passes)
    if (p.skipped && (p.name == "tonemap" || p.name == "tonemap_compute")) EXPECT_FALSE(p.reason.empty());
  o.method = Method::Deferred;
  o.path = Path::SinglePass;
  o.tonemapPass = TonemapPass::Compute;
  const FrameStats& single = render(scene, o);
  EXPECT_TRUE(passRan(single, "tonemap"));
  for (const PassStat& p : single.passes)
    if (p.name == "tonemap_compute") EXPECT_NE(p.reason.find("single-pass"), std::string::npos) << p.reason;
}

}  // namespace gb
