// The lighting methods (deferred with per-light or shared stencil masks or without culling,
// tiled deferred, clustered deferred, forward) give the same image within the accumulation bound,
// and their coverage_masked counts say what each evaluated: every light that reaches a pixel at
// least. `--method auto` runs one of them and says which and why.
//
// The bound. A conversion to fp16 may land on either neighbour (Vulkan; llvmpipe truncates),
// an error below one ulp, at most 2^-10 of the value. Deferred stores hdr after the directional
// pass and after every light that adds something (m lights); tiled and forward sum in fp32
// registers and store once. With non-negative contributions every partial sum is at most the
// total E, so each result is within (m + 1) 2^-10 E of E and two of them within (m + 2) 2^-10 E.
// m is at most n = coverage_masked of the unculled deferred frame (fragments that ran there);
// fp32 summation (n 2^-24) and fp32 differences between shaders are inside the 1e-6 floor.
#include <algorithm>
#include <map>
#include <cmath>

#include "renderer/core/camera.h"
#include "renderer/core/codec.h"
#include "renderer/frame/light_culling.h"
#include "renderer/readback/srgb_probe.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace {

struct Method3 {
  const char* label;
  Method method;
  bool stencilCulling;
  StencilMask mask;
  ClusterAssign assign = ClusterAssign::Auto;
};
const Method3 kMethods[] = {
    {"deferred per-light", Method::Deferred, true, StencilMask::PerLight},
    {"deferred shared", Method::Deferred, true, StencilMask::Shared},
    {"tiled", Method::Tiled, true, StencilMask::PerLight},
    {"clustered (occupied clusters, gpu)", Method::Clustered, true, StencilMask::PerLight, ClusterAssign::Gpu},
    {"clustered (cluster grid, cpu)", Method::Clustered, true, StencilMask::PerLight, ClusterAssign::Cpu},
    {"forward", Method::Forward, true, StencilMask::PerLight}};

RenderOptions methodOptions(uint32_t w, uint32_t h, int lights) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.lights = lights;
  o.fairies = false;  // sprites are the same in every method; they would only hide pixels
  o.coverage = true;
  return o;
}

// Pixels (per channel) outside (n + 2) 2^-10 max(|a|, |b|) + 1e-6, n from `coverage`.
int outOfBound(const CpuImage& a, const CpuImage& b, const CpuImage& coverage, double* worst = nullptr) {
  int bad = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      double n = coverage.value(x, y, 0);
      for (int c = 0; c < 3; ++c) {
        double va = a.value(x, y, c), vb = b.value(x, y, c);
        double bound = (n + 2.0) * std::ldexp(1.0, -10) * std::max(std::abs(va), std::abs(vb)) + 1e-6;
        if (worst && bound > 0) *worst = std::max(*worst, std::abs(va - vb) / bound);
        if (!(std::abs(va - vb) <= bound)) ++bad;
      }
    }
  return bad;
}

// Renders every method and compares each hdr with the unculled deferred frame's. Forward only
// where the G-buffer stores exact values: elsewhere deferred shades values rounded to 8-bit
// albedo and fp16 normals, which forward does not (that difference is the G-buffer's storage
// error, measured against the reference by gblens error, not an accumulation difference).
void expectMethodsAgree(GpuTest& t, const Scene& scene, RenderOptions o, const std::string& what, bool forward,
                        const std::vector<Method>& only = {}) {
  o.method = Method::Deferred;
  o.stencilCulling = false;
  t.render(scene, o, {{Target::Hdr, Target::CoverageMasked}});
  CpuImage reference = t.renderer(scene).readback[size_t(Target::Hdr)];
  CpuImage coverage = t.renderer(scene).readback[size_t(Target::CoverageMasked)];
  double sum = 0.0;
  for (uint32_t y = 0; y < reference.height; ++y)
    for (uint32_t x = 0; x < reference.width; ++x) sum += reference.value(x, y, 0);
  EXPECT_GT(sum, 0.0) << what << ": a black frame compares equal to anything";
  for (const Method3& m : kMethods) {
    if (m.method == Method::Forward && !forward) continue;
    if (!only.empty() && std::find(only.begin(), only.end(), m.method) == only.end()) continue;
    o.method = m.method;
    o.stencilCulling = m.stencilCulling;
    o.stencilMask = m.mask;
    o.clusterAssign = m.assign;
    const FrameStats& st = t.render(scene, o, {{Target::Hdr}});
    EXPECT_EQ(st.method, name(m.method)) << what;
    if (m.method == Method::Clustered) EXPECT_EQ(st.clusterAssign, name(m.assign)) << what;
    if (st.clusters.valid) {
      EXPECT_EQ(st.clusters.listOverflows + st.clusters.tilesWithoutRoom, 0u) << what << ": the first frame had room";
    }
    double worst = 0.0;
    EXPECT_EQ(outOfBound(t.renderer(scene).readback[size_t(Target::Hdr)], reference, coverage, &worst), 0)
        << what << ": " << m.label << " (worst |difference| / bound " << worst << ")";
  }
}

// A floor and two boxes seen straight down, lit by point lights and ambient light: every value
// a G-buffer stores is exact here (normals along the eye-space axes, albedo on the device's own
// sRGB decode table, specular k/255, no sun), so forward, which shades unrounded values, must
// agree with deferred to the accumulation bound too.
Scene exactStorageScene(const std::vector<float>& srgbDecode, int lights) {
  Scene s = floorScene(30.0, 0.0f);
  s.materials[0].baseColor = glm::vec4(srgbDecode[200], srgbDecode[150], srgbDecode[90], 1.0f);
  s.materials[0].specular = 64.0f / 255.0f;
  MaterialDesc box = s.materials[0];
  box.baseColor = glm::vec4(srgbDecode[120], srgbDecode[220], srgbDecode[180], 1.0f);
  box.specular = 200.0f / 255.0f;
  s.materials.push_back(box);
  addBox(s, {-4, 0, -3}, {-1, 1.5f, 2}, 1);
  addBox(s, {2, 0, 1}, {5, 0.7f, 4}, 1);
  s.sky.ambient = glm::vec3(0.2f, 0.15f, 0.1f);
  generateLights(s, lights);
  setCamera(s, {0.0, 14.0, 0.0}, {0.0, 0.0, 0.0}, 1.2, 0.5, 40.0);
  return s;
}

// A long floor seen at a grazing angle, so surface points run from the near plane to beyond the
// far plane (clipped there), with lights around the camera (containing it), straddling the near
// plane, spread over the depth range, and straddling the far plane.
Scene nearFarScene() {
  Scene s = floorScene(200.0, 0.3f);
  addBox(s, {-1.5f, 0.0f, -6.0f}, {1.5f, 2.5f, -4.0f});
  s.sky.ambient = glm::vec3(0.05f);
  const glm::dvec3 eye(0.0, 1.5, 0.0);
  const double znear = 0.1, zfar = 40.0;
  setCamera(s, eye, {0.0, 0.0, -30.0}, 0.9, znear, zfar);
  auto light = [&](glm::dvec3 p, double radius, glm::vec3 color) {
    PointLightDesc l;
    l.center = p;
    l.radius = radius;
    l.color = color;
    l.intensity = 1.5;
    s.lights.push_back(l);
  };
  light(eye, 3.0, {1.0f, 0.9f, 0.8f});                        // contains the camera
  light(eye + glm::dvec3(0.4, -0.3, -0.05), 1.6, {0.3f, 0.6f, 1.0f});  // straddles the near plane
  light(eye + glm::dvec3(-0.2, -1.2, 0.3), 1.5, {1.0f, 0.4f, 0.3f});   // behind the camera, reaching the floor ahead
  for (int i = 0; i < 24; ++i) {                              // along the view, near to far
    const double z = -0.5 - 1.8 * i;
    light({(i % 5 - 2) * 1.7, 0.2 + 0.1 * (i % 3), z}, 1.2 + 0.15 * (i % 4), {0.9f, 0.7f, 0.5f + 0.02f * i});
  }
  for (int i = 0; i < 6; ++i) light({-10.0 + 4.0 * i, 0.5, -zfar * 0.75}, 6.0, {0.6f, 1.0f, 0.6f});  // across the far plane
  s.generatedLights = false;
  return s;
}

}  // namespace

TEST_F(GpuTest, ClusteredAgreesAroundTheCameraAndAcrossNearAndFar) {
  Scene scene = nearFarScene();
  RenderOptions o = methodOptions(128, 72, 0);
  expectMethodsAgree(*this, scene, o, "near/far", false, {Method::Clustered, Method::Tiled});
  o.reversedZ = true;
  expectMethodsAgree(*this, scene, o, "near/far reversed z", false, {Method::Clustered});
}

TEST_F(GpuTest, ClusteredAgreesAtManyLights) {
  Scene scene = builtinTemple(4096);
  expectMethodsAgree(*this, scene, methodOptions(96, 54, 4096), "4096 lights", false, {Method::Clustered});
}

// The two clusterings list different lights (the grid's cells hold lights that reach their box,
// Olsson's clusters those that reach the box of their own surface points), but both list every
// light that reaches a pixel's point and add them in visible-list order, and a light that does not
// reach adds exactly zero: the same sums, bit for bit, whatever the position source.
TEST_F(GpuTest, TheClusterGridShadesAsTheOccupiedClustersDo) {
  struct Case {
    const char* what;
    Scene scene;
    RenderOptions o;
  };
  std::vector<Case> cases;
  for (int lights : {0, 16, 256, 4096}) cases.push_back({"temple", builtinTemple(lights), methodOptions(96, 54, lights)});
  cases.push_back({"near/far", nearFarScene(), methodOptions(128, 72, 0)});
  cases.push_back({"near/far reversed z", nearFarScene(), methodOptions(128, 72, 0)});
  cases.back().o.reversedZ = true;
  cases.push_back({"hardware depth", builtinTemple(256), methodOptions(96, 54, 256)});
  cases.back().o.eyeDepth = false;
  cases.push_back({"stored fp16 world position", builtinTemple(256), methodOptions(96, 54, 256)});
  cases.back().o.position = PositionSource::Rgba16f;
  cases.push_back({"stored fp32 camera-relative position", builtinTemple(256), methodOptions(96, 54, 256)});
  cases.back().o.position = PositionSource::Rgba32f;
  cases.back().o.positionSpace = PositionSpace::Camera;
  for (Case& c : cases) {
    c.o.method = Method::Clustered;
    c.o.clusterAssign = ClusterAssign::Gpu;
    render(c.scene, c.o, {{Target::Hdr, Target::CoverageMasked}});
    const CpuImage clusters = renderer(c.scene).readback[size_t(Target::Hdr)];
    const CpuImage clusterCounts = renderer(c.scene).readback[size_t(Target::CoverageMasked)];
    c.o.clusterAssign = ClusterAssign::Cpu;
    const FrameStats& st = render(c.scene, c.o, {{Target::Hdr, Target::CoverageMasked}});
    EXPECT_EQ(st.clusterAssign, "cpu") << c.what;
    for (const char* pass : {"cluster_bounds", "cluster_lists"})
      for (const PassStat& p : st.passes)
        if (p.name == pass) EXPECT_TRUE(p.skipped) << c.what << ": " << pass;
    const Renderer& r = renderer(c.scene);
    EXPECT_EQ(r.readback[size_t(Target::Hdr)].data, clusters.data) << c.what;
    // Each geometry pixel evaluated its cell's lights: at least those its cluster listed.
    uint64_t grid = 0, occupied = 0;
    const CpuImage& counts = r.readback[size_t(Target::CoverageMasked)];
    for (uint32_t y = 0; y < counts.height; ++y)
      for (uint32_t x = 0; x < counts.width; ++x) {
        grid += counts.raw(x, y, 0);
        occupied += clusterCounts.raw(x, y, 0);
      }
    EXPECT_GE(grid, occupied) << c.what;
  }
}

// Auto runs a real method, says why, and gives the image of the method it names.
TEST_F(GpuTest, AutoPicksAMethodAndSaysWhy) {
  Scene scene = builtinTemple(64);
  RenderOptions o = methodOptions(96, 54, 64);
  ASSERT_EQ(RenderOptions{}.method, Method::Auto);  // the default
  o.method = Method::Auto;
  const FrameStats& st = render(scene, o, {{Target::Hdr}});
  Method ran;
  ASSERT_TRUE(parse(st.method, ran)) << st.method;
  EXPECT_NE(ran, Method::Auto);
  EXPECT_NE(ran, Method::Forward);  // never picked: slowest from 256 lights on every device measured
  EXPECT_EQ(st.methodReason.rfind("auto: ", 0), 0u) << st.methodReason;
  EXPECT_NE(st.methodReason.find(name(ran)), std::string::npos) << st.methodReason;
  const CpuImage autoHdr = renderer(scene).readback[size_t(Target::Hdr)];
  o.method = ran;
  render(scene, o, {{Target::Hdr}});
  EXPECT_EQ(autoHdr.data, renderer(scene).readback[size_t(Target::Hdr)].data) << "auto is " << name(ran) << " exactly";
  // The single-pass path is deferred's.
  o.method = Method::Auto;
  o.path = Path::SinglePass;
  EXPECT_EQ(render(scene, o).method, std::string("deferred"));
}

TEST_F(GpuTest, DeferredAndTiledGiveTheSameImageWithinTheAccumulationBound) {
  for (int lights : {0, 16, 256}) {
    Scene scene = builtinTemple(lights);
    expectMethodsAgree(*this, scene, methodOptions(128, 72, lights), std::to_string(lights) + " lights", false);
  }
  // Positions from hardware depth, and a stored position target, in the tiled compute pass too.
  Scene scene = builtinTemple(64);
  RenderOptions o = methodOptions(96, 54, 64);
  o.eyeDepth = false;
  expectMethodsAgree(*this, scene, o, "hardware depth", false);
  o.eyeDepth = true;
  o.position = PositionSource::Rgba32f;
  expectMethodsAgree(*this, scene, o, "stored position", false);
}

// Tiled and clustered write the sky from their compute pass (on a GPU whose raster units are few,
// as the H100's, a full-screen raster pass costs more than the compute work): no skybox pass,
// and every sky pixel equals the skybox pass's within float rounding of the pixel's direction.
TEST_F(GpuTest, ComputeMethodsWriteTheSkyTheSkyboxPassWouldDraw) {
  Scene scene = builtinTemple(16);
  RenderOptions o = methodOptions(96, 54, 16);
  o.method = Method::Deferred;
  render(scene, o, {{Target::Hdr, Target::Depth}});
  const CpuImage sky = renderer(scene).readback[size_t(Target::Hdr)];
  const CpuImage depth = renderer(scene).readback[size_t(Target::Depth)];
  for (Method m : {Method::Tiled, Method::Clustered}) {
    o.method = m;
    const FrameStats& st = render(scene, o, {{Target::Hdr}});
    auto skybox = std::find_if(st.passes.begin(), st.passes.end(), [](const PassStat& p) { return p.name == "skybox"; });
    ASSERT_NE(skybox, st.passes.end());
    EXPECT_TRUE(skybox->skipped) << name(m);
    EXPECT_NE(skybox->reason.find("writes the sky"), std::string::npos) << skybox->reason;
    const CpuImage& hdr = renderer(scene).readback[size_t(Target::Hdr)];
    size_t skyPixels = 0;
    for (uint32_t y = 0; y < hdr.height; ++y)
      for (uint32_t x = 0; x < hdr.width; ++x) {
        if (depth.value(x, y, 0) != 0.0) continue;  // geometry (eye depth 0: none)
        ++skyPixels;
        for (int c = 0; c < 4; ++c)
          EXPECT_NEAR(hdr.value(x, y, c), sky.value(x, y, c), 1e-5 * std::max(1.0, std::abs(sky.value(x, y, c))))
              << name(m) << " sky pixel " << x << "," << y << " channel " << c;
      }
    EXPECT_GT(skyPixels, 500u) << "the temple's camera sees the sky above the columns";
  }
  o.sky = false;  // and no sky: nothing where no geometry was drawn
  o.method = Method::Clustered;
  render(scene, o, {{Target::Hdr}});
  const CpuImage& dark = renderer(scene).readback[size_t(Target::Hdr)];
  for (uint32_t y = 0; y < dark.height; ++y)
    for (uint32_t x = 0; x < dark.width; ++x)
      if (depth.value(x, y, 0) == 0.0) ASSERT_EQ(dark.value(x, y, 0), 0.0) << x << "," << y;
}

TEST_F(GpuTest, ForwardAgreesWithDeferredWhereTheGBufferStoresExactValues) {
  Scene probe = floorScene();
  const std::vector<float> decode = probeSrgbDecode(renderer(probe));
  Scene scene = exactStorageScene(decode, 96);
  RenderOptions o = methodOptions(120, 80, 96);
  // The premise: the G-buffer holds exactly what forward shades with.
  render(scene, o, {{Target::AlbedoSpecular, Target::NormalShadow, Target::Depth}});
  const Renderer& r = renderer(scene);
  int geometry = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      if (r.readback[size_t(Target::Depth)].value(x, y, 0) <= 0.0) continue;
      ++geometry;
      const CpuImage& n = r.readback[size_t(Target::NormalShadow)];
      double axis = 0.0;  // an eye-space axis: components -1, 0, 1 (box sides face +-x, +-y)
      const glm::dvec3 stored = decodeNormalTexel(n, x, y, o.normalFormat).stored;  // oct-rg16 decodes axes exactly
      for (int c = 0; c < 3; ++c) {
        double v = stored[c];
        ASSERT_TRUE(v == 0.0 || v == 1.0 || v == -1.0) << x << "," << y << ": N." << c << " = " << v;
        axis += v * v;
      }
      ASSERT_EQ(axis, 1.0);
      const CpuImage& a = r.readback[size_t(Target::AlbedoSpecular)];
      for (int c = 0; c < 3; ++c) {
        uint32_t byte = a.raw(x, y, uint32_t(c));
        ASSERT_TRUE(byte == 200 || byte == 150 || byte == 90 || byte == 120 || byte == 220 || byte == 180) << byte;
      }
    }
  ASSERT_EQ(geometry, int(o.width * o.height));  // the floor fills the view
  expectMethodsAgree(*this, scene, o, "exact storage", true);
}

// What coverage_masked counts per method, checked against the lights that reach each pixel's
// surface point (brute force in double): deferred counts point-light fragment shader runs,
// tiled the lights in the pixel's tile list (the same for every geometry pixel of a tile),
// clustered the lights in its cluster's list (a cluster's box lies inside its tile's, so never
// more than tiled's count there) or in its cluster grid cell's (the same for every pixel of a tile
// at one depth slice), forward the lights each fragment looped over (all visible lights, for every
// fragment shaded there, hidden ones included). None may count fewer than the lights that reach
// the pixel.
TEST_F(GpuTest, CoverageCountsWhatEachMethodEvaluatedAndNeverLessThanTheLightsThatReach) {
  Scene scene = builtinTemple(128);
  RenderOptions o = methodOptions(96, 54, 128);
  CpuImage tiledCoverage;
  const std::pair<Method, ClusterAssign> kRuns[] = {{Method::Deferred, ClusterAssign::Auto},
                                                    {Method::Tiled, ClusterAssign::Auto},
                                                    {Method::Clustered, ClusterAssign::Gpu},
                                                    {Method::Clustered, ClusterAssign::Cpu},
                                                    {Method::Forward, ClusterAssign::Auto}};
  for (auto [method, assign] : kRuns) {
    o.method = method;
    o.clusterAssign = assign;
    const bool grid = assign == ClusterAssign::Cpu;
    std::map<std::pair<uint32_t, uint32_t>, uint32_t> cellCounts;  // (tile, slice) -> count
    std::vector<Target> readback = {Target::CoverageMasked, Target::DepthStencil};
    if (grid) readback.push_back(Target::Depth);
    const FrameStats& st = render(scene, o, {readback, {}, true});
    const Renderer& r = renderer(scene);
    const CpuImage& coverage = r.readback[size_t(Target::CoverageMasked)];
    const CpuImage eye = eyeDepthFromHardware(r.camera, r.readback[size_t(Target::DepthStencil)]);
    const uint32_t visible = uint32_t(r.lights.visible.size());
    ASSERT_GT(visible, 16u);
    EXPECT_GE(st.culling.invocations, st.culling.idealPairs) << name(method);
    int surface = 0;
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        const uint32_t count = coverage.raw(x, y, 0);
        const double d = eye.value(x, y, 0);
        if (d <= 0.0) {
          if (method != Method::Deferred) {
            ASSERT_EQ(count, 0u) << name(method) << " sky " << x << "," << y;
          }
          continue;
        }
        ++surface;
        const glm::dvec3 p = eyeFromHardwareDepth(r.camera, x, y, r.readback[size_t(Target::DepthStencil)].value(x, y, 0));
        uint32_t reaching = 0;
        for (uint32_t i : r.lights.visible) {
          glm::dvec3 v = p - glm::dvec3(r.lights.eye[i].eyePositionRadius);
          double radius = r.lights.eye[i].eyePositionRadius.w;
          reaching += glm::dot(v, v) < radius * radius * (1.0 - 1e-5);  // clear of rounding at the edge
        }
        ASSERT_GE(count, reaching) << name(method) << " pixel " << x << "," << y;
        if (method == Method::Forward) {
          ASSERT_GE(count, visible) << x << "," << y;
          ASSERT_EQ(count % visible, 0u) << x << "," << y;
        }
        if (method == Method::Clustered && !grid) {
          ASSERT_LE(count, tiledCoverage.raw(x, y, 0)) << "clustered pixel " << x << "," << y;
        }
        if (grid) {  // one list per cell: tile and depth slice (of the eye depth the shader reads)
          const GridShape& g = r.clusters.grid.shape;
          const uint32_t tile = (y / g.tile) * g.tilesX + x / g.tile;
          const double eyeDepth = r.readback[size_t(Target::Depth)].value(x, y, 0);  // as the shader reads it
          const auto [it, fresh] = cellCounts.insert({{tile, gridSlice(g, eyeDepth)}, count});
          if (!fresh) ASSERT_EQ(it->second, count) << "grid pixel " << x << "," << y;
        }
        if (method == Method::Tiled) {  // one list per tile
          uint32_t tx = x - x % gpu::kTileSize, ty = y - y % gpu::kTileSize;
          for (uint32_t yy = ty; yy < std::min(ty + gpu::kTileSize, o.height); ++yy)
            for (uint32_t xx = tx; xx < std::min(tx + gpu::kTileSize, o.width); ++xx)
              if (eye.value(xx, yy, 0) > 0.0) {
                ASSERT_EQ(coverage.raw(xx, yy, 0), count) << xx << "," << yy;
              }
        }
      }
    EXPECT_GT(surface, int(o.width * o.height / 2));
    if (grid) EXPECT_GT(cellCounts.size(), 20u);
    if (method == Method::Tiled) tiledCoverage = coverage;
  }
}

// Forward has no G-buffer: its targets are unavailable by name, and the frame says why.
TEST_F(GpuTest, ForwardMarksTheGBufferTargetsUnavailable) {
  RenderOptions o = methodOptions(32, 18, 4);
  o.method = Method::Forward;
  for (Target t : {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth})
    EXPECT_EQ(targetAbsence(t, o), Absent::ForwardNoGBuffer) << targetName(t);
  for (Target t : {Target::DepthStencil, Target::ShadowMap, Target::Hdr, Target::Final, Target::CoverageMasked})
    EXPECT_EQ(targetAbsence(t, o), Absent::No) << targetName(t);
  Scene scene = builtinTemple(4);
  const FrameStats& st = render(scene, o, {{Target::Final}});
  for (const PassStat& p : st.passes)
    if (p.name == "gbuffer" || p.name == "directional_light" || p.name == "point_lights") {
      EXPECT_TRUE(p.skipped) << p.name;
      EXPECT_NE(p.reason.find("forward"), std::string::npos) << p.name;
    }
}

}  // namespace gb
