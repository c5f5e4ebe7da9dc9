// The viewer's GPU view mapping against the CPU mapping of `render --target` (views/visualize.cpp,
// an independent implementation): every view of a real frame, texel for texel within one 8-bit
// step; the NaN/Inf/negative highlights; automatic ranges against a CPU min/max; region
// read-back against whole-target read-back.
#include <cmath>
#include <cstring>

#include "renderer/core/layout_json.h"
#include "renderer/frame/region_readback.h"
#include "renderer/gpu/upload_targets.h"
#include "renderer/scene/builtin.h"
#include "renderer/vk/check.h"
#include "tests/gpu/gpu_test.h"
#include "tests/gpu/view_canvas.h"
#include "views/analysis/probe.h"
#include "views/analysis/shadow_marks.h"
#include "views/analysis/visualize.h"
#include "views/ui/view_params.h"

namespace gb {

namespace {

const std::vector<Target> kAll = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth, Target::DepthStencil,
                                  Target::ShadowMap,      Target::Hdr,          Target::Final, Target::CoverageMasked,
                                  Target::CoverageFull};

RenderOptions smallFrame() {
  RenderOptions o;
  o.width = 96;
  o.height = 54;
  o.shadowMapSize = 128;
  o.coverage = true;
  o.time = 0.75;
  return o;
}

}  // namespace

namespace {

// The GPU params of a view of gblens's live frame (the views of its layout, read from its targets).
struct LiveView {
  ViewDef def;
  ViewSource source;
  ViewGpuSource gpu;
};
LiveView liveView(const RenderOptions& o, const char* name) {
  const Layout& l = nativeLayout(o);
  std::vector<ViewDef> views = layoutViews(l);
  LiveView v{views[size_t(findView(views, name))], {}, {}};
  v.source = *nativeSource(l, v.def, &v.gpu);
  return v;
}

}  // namespace

// Every view of gblens's layout drawn on the GPU two ways, as the viewer draws them: from the live
// target (encodings decoded in the shader) and from the decoded view image (a capture's path); both
// against the CPU mapping within one 8-bit step.
TEST_F(GpuTest, EveryViewOnTheGpuMatchesTheCpuMapping) {
  Scene scene = builtinTemple(48);
  RenderOptions o = smallFrame();
  o.normalFormat = NormalFormat::OctRg16;  // an encoding the shader decodes
  FrameRequest request;
  request.readback = kAll;
  request.sampleAfter = kAll;
  render(scene, o, request);
  Renderer& r = renderer(scene);
  ViewMapper mapper;
  initViewMapper(mapper, r);
  FrameSnapshot frame = snapshotFromRenderer(r, kAll);
  Canvas screen(ctx(), o.width, o.height), shadow(ctx(), o.shadowMapSize, o.shadowMapSize);
  const std::vector<ViewDef> views = layoutViews(frame.layout);
  std::vector<CpuImage> decoded;
  for (const ViewDef& d : views) decoded.push_back(viewImage(frame, d));
  ViewImages uploaded;
  uploadViewImages(uploaded, ctx(), decoded);
  int drawn = 0;
  for (size_t k = 0; k < views.size(); ++k) {
    const ViewDef& def = views[k];
    if (decoded[k].empty()) continue;  // not rendered under these options (position, primitive id)
    ViewSettings s = defaultSettings(def);
    // The range both draws use: the CPU's over the decoded image (the GPU reduction is tested below).
    std::vector<RangeStats> stats = {imageRange(decoded[k], def, viewMapping(def, s).mask)};
    ResolvedRange range = resolveRange(def, s, &stats);
    Canvas& canvas = def.sun ? shadow : screen;
    Rgba8Image cpu = visualize(frame, def, s);
    ASSERT_EQ(cpu.width, canvas.image.desc.width) << def.name;
    ViewGpuSource live;
    ViewSource source = *nativeSource(frame.layout, def, &live);
    for (bool fromDecoded : {false, true}) {
      const ViewImage image = fromDecoded ? viewImageOf(uploaded, k) : targetImage(r, source);
      std::vector<uint8_t> gpu = canvas.draw(mapper, r, image, viewParams(def, s, fromDecoded ? ViewGpuSource{} : live, range,
                                                                           Placement{0, 0, 1}, false, std::nullopt, {1, 1}));
      int worst = 0, differing = 0;
      for (size_t i = 0; i < gpu.size(); ++i) {
        if (i % 4 == 3) continue;
        int d = std::abs(int(gpu[i]) - int(cpu.pixels[i]));
        worst = std::max(worst, d);
        differing += d > 0;
      }
      EXPECT_LE(worst, 1) << def.name << (fromDecoded ? " (decoded)" : " (live)") << ": " << differing << " channel values differ";
    }
    ++drawn;
  }
  EXPECT_GE(drawn, 12);
  destroyViewImages(uploaded, ctx());
  screen.destroy(ctx());
  shadow.destroy(ctx());
  destroyViewMapper(mapper, r);
}

TEST_F(GpuTest, AutomaticRangesEqualTheCpuMinMaxOverValidTexels) {
  Scene scene = builtinTemple(48);
  RenderOptions o = smallFrame();
  FrameRequest request;
  request.readback = kAll;
  request.sampleAfter = kAll;
  render(scene, o, request);
  Renderer& r = renderer(scene);
  ViewMapper mapper;
  initViewMapper(mapper, r);
  struct Case {
    Target t;
    uint32_t channel, predicate;
  };
  for (Case c : {Case{Target::Depth, 0, gpu::kRangePositive}, Case{Target::ShadowMap, 0, gpu::kRangeBelowOne},
                 Case{Target::DepthStencil, 0, gpu::kRangeNotFar}, Case{Target::CoverageFull, 0, gpu::kRangeAll},
                 Case{Target::NormalShadow, 1, gpu::kRangeAll}, Case{Target::Hdr, 2, gpu::kRangeAll}}) {
    const CpuImage& img = r.readback[size_t(c.t)];
    double lo = 1e300, hi = -1e300;
    uint64_t count = 0, negative = 0;
    for (uint32_t y = 0; y < img.height; ++y)
      for (uint32_t x = 0; x < img.width; ++x) {
        double v = img.value(x, y, c.channel);
        bool valid = c.predicate == gpu::kRangePositive ? v > 0.0
                     : c.predicate == gpu::kRangeBelowOne ? v < 1.0
                     : c.predicate == gpu::kRangeNotFar  ? v != 1.0
                                                         : true;
        if (!valid || !std::isfinite(v)) continue;
        lo = std::min(lo, v);
        hi = std::max(hi, v);
        ++count;
        negative += v < 0.0;
      }
    RangeStats s = computeRanges(mapper, r, {{{c.t}, c.channel, c.predicate, 0.0f}}, kAll)[0];
    EXPECT_EQ(s.count, count) << targetName(c.t);
    // Float equality within 4 ulps: the GPU converts SNORM16 (oct-rg16 normals) to float with its own
    // rounding of c / 32767, the CPU in double.
    EXPECT_FLOAT_EQ(s.lo, lo) << targetName(c.t);
    EXPECT_FLOAT_EQ(s.hi, hi) << targetName(c.t);
    EXPECT_EQ(s.negative, negative) << targetName(c.t);
    EXPECT_EQ(s.nan + s.inf, 0u) << targetName(c.t);
  }
  destroyViewMapper(mapper, r);
}

// Lights with a NaN, an infinite and a negative colour put NaN, +Inf and negative values into
// hdr (as a broken light setup would): the range pass counts exactly the texels the CPU finds,
// and the HDR view paints each in its highlight colour (stripes of full and 35% intensity).
TEST_F(GpuTest, NanInfAndNegativeValuesAreHighlightedAndCounted) {
  Scene scene = floorScene(10.0);
  setCamera(scene, {0, 6, 6}, {0, 0, 0});
  auto light = [&](double x, glm::vec3 colour) {
    PointLightDesc l;
    l.center = {x, 0.4, 0.0};
    l.radius = 1.5;
    l.color = colour;
    scene.lights.push_back(l);
  };
  light(-3.5, glm::vec3(NAN));
  light(0.0, glm::vec3(INFINITY));
  light(3.5, glm::vec3(-4.0f));
  RenderOptions o = smallFrame();
  o.fairies = false;  // their sprites would carry the same colours
  render(scene, o, {{Target::Hdr}, kAll});
  Renderer& r = renderer(scene);
  const CpuImage& hdr = r.readback[size_t(Target::Hdr)];
  uint64_t nan = 0, inf = 0, negative = 0;
  for (uint32_t y = 0; y < hdr.height; ++y)
    for (uint32_t x = 0; x < hdr.width; ++x) {
      double v = hdr.value(x, y, 0);
      nan += std::isnan(v);
      inf += std::isinf(v);
      negative += v < 0.0;
    }
  ASSERT_GT(nan, 0u);
  ASSERT_GT(inf, 0u);
  ASSERT_GT(negative, 0u);

  ViewMapper mapper;
  initViewMapper(mapper, r);
  RangeStats s = computeRanges(mapper, r, {{{Target::Hdr}, 0, gpu::kRangeAll, 0.0f}}, kAll)[0];
  EXPECT_EQ(s.nan, nan);
  EXPECT_EQ(s.inf, inf);
  EXPECT_EQ(s.negative, negative);

  const LiveView hdrView = liveView(o, "HDR");
  const ViewDef& def = hdrView.def;
  ViewSettings settings = defaultSettings(def);
  Canvas canvas(ctx(), o.width, o.height);
  auto drawHdr = [&] {
    return canvas.draw(mapper, r, targetImage(r, hdrView.source),
                       viewParams(def, settings, hdrView.gpu, resolveRange(def, settings, nullptr), Placement{0, 0, 1}, false,
                                  std::nullopt, {1, 1}));
  };
  std::vector<uint8_t> out = drawHdr();
  auto painted = [&](uint32_t x, uint32_t y, const uint8_t (&colour)[3]) {
    const uint8_t* p = &out[(size_t(y) * o.width + x) * 4];
    bool full = true, dim = true;
    for (int c = 0; c < 3; ++c) {
      full &= p[c] == colour[c];
      dim &= std::abs(int(p[c]) - int(std::lround(colour[c] * 0.35))) <= 1;
    }
    return full || dim;
  };
  const uint8_t nanColour[3] = {255, 0, 255}, infColour[3] = {0, 255, 255}, negColour[3] = {255, 89, 0};
  int checked[3] = {};
  for (uint32_t y = 0; y < hdr.height; ++y)
    for (uint32_t x = 0; x < hdr.width; ++x) {
      bool n = false, i = false, g = false;
      for (uint32_t c = 0; c < 3; ++c) {
        double v = hdr.value(x, y, c);
        n |= std::isnan(v);
        i |= std::isinf(v);
        g |= v < 0.0;
      }
      if (n) {
        EXPECT_TRUE(painted(x, y, nanColour)) << "NaN at " << x << "," << y;
        ++checked[0];
      } else if (i) {
        EXPECT_TRUE(painted(x, y, infColour)) << "Inf at " << x << "," << y;
        ++checked[1];
      } else if (g) {
        EXPECT_TRUE(painted(x, y, negColour)) << "negative at " << x << "," << y;
        ++checked[2];
      }
    }
  EXPECT_GT(checked[0] * checked[1] * checked[2], 0);
  // Highlights off: negative values clamp to black like any value below the black point.
  settings.specials = settings.negative = false;
  out = drawHdr();
  for (uint32_t y = 0; y < hdr.height; ++y)
    for (uint32_t x = 0; x < hdr.width; ++x)
      if (hdr.value(x, y, 0) < 0 && hdr.value(x, y, 1) < 0 && hdr.value(x, y, 2) < 0) {
        const uint8_t* p = &out[(size_t(y) * o.width + x) * 4];
        EXPECT_EQ(int(p[0]) + int(p[1]) + int(p[2]), 0) << x << "," << y;
      }
  canvas.destroy(ctx());
  destroyViewMapper(mapper, r);
}

TEST_F(GpuTest, RegionReadBackEqualsTheWholeTargetsTexels) {
  Scene scene = builtinTemple(48);
  RenderOptions o = smallFrame();
  o.depthFormat = DepthFormat::D24S8;  // the packed depth/stencil path too
  FrameRequest request;
  request.readback = kAll;
  request.sampleAfter = kAll;
  render(scene, o, request);
  Renderer& r = renderer(scene);
  std::vector<RegionRequest> windows;
  for (Target t : kAll) {
    windows.push_back({t, 5, 7, 3, 2});
    windows.push_back({t, -2, -1, 4, 4});  // clamped at the top-left corner
    windows.push_back({t, int32_t(r.targets[size_t(t)].image.desc.width) - 2, 0, 5, 1});  // clamped right
  }
  std::vector<RegionImage> regions = readbackRegions(r, windows, kAll);
  ASSERT_EQ(regions.size(), windows.size());
  for (const RegionImage& ri : regions) {
    const CpuImage& whole = r.readback[size_t(ri.target)];
    ASSERT_FALSE(ri.image.empty()) << targetName(ri.target);
    EXPECT_EQ(ri.targetWidth, whole.width);
    for (uint32_t y = 0; y < ri.image.height; ++y)
      for (uint32_t x = 0; x < ri.image.width; ++x)
        for (uint32_t c = 0; c < whole.channelCount(); ++c)
          ASSERT_EQ(ri.image.raw(x, y, c), whole.raw(ri.x0 + x, ri.y0 + y, c))
              << targetName(ri.target) << " texel " << ri.x0 + x << "," << ri.y0 + y << " channel " << c;
  }
  EXPECT_EQ(regions[1].x0, 0u);
  EXPECT_EQ(regions[1].image.width, 2u);  // x in [-2, 2) clamped to [0, 2)
  EXPECT_EQ(regions[2].image.width, 2u);
}

}  // namespace gb

namespace gb {

// A capture opened in the viewer is uploaded back into targets: pack -> upload -> read back must
// return every stored bit, for every target and the formats whose packing is not a plain copy.
TEST_F(GpuTest, UploadedTargetsReadBackBitForBit) {
  Scene scene = builtinTemple(32);
  for (auto [normal, depth] : {std::pair{NormalFormat::Rgb10a2, DepthFormat::D24S8},
                               std::pair{NormalFormat::Rgba16f, DepthFormat::D32S8}}) {
    RenderOptions o = smallFrame();
    o.normalFormat = normal;
    o.depthFormat = depth;
    render(scene, o, {kAll, kAll});
    Renderer& live = renderer(scene);
    std::array<const CpuImage*, kTargetCount> images{};
    for (Target t : kAll) images[size_t(t)] = &live.readback[size_t(t)];
    Scene empty = floorScene();
    Renderer& uploaded = renderer(empty);
    uploadTargets(uploaded, o, images);
    std::vector<RegionRequest> whole;
    for (Target t : kAll) whole.push_back({t, 0, 0, images[size_t(t)]->width, images[size_t(t)]->height});
    std::vector<RegionImage> back = readbackRegions(uploaded, whole, kAll);
    for (const RegionImage& ri : back) {
      const CpuImage& original = *images[size_t(ri.target)];
      ASSERT_EQ(ri.image.data.size(), original.data.size()) << targetName(ri.target);
      EXPECT_EQ(ri.image.data, original.data) << targetName(ri.target) << " with " << name(normal) << ", " << name(depth);
    }
  }
}

// Clicking a shadow-map texel marks the screen pixels whose shadow lookup reads it: mark the
// texel the dossier says a pixel read (the 2x2 footprint's top-left) and that pixel is marked,
// while pixels far from it are drawn as without the mark.
TEST_F(GpuTest, ShadowTexelMarksThePixelsThatSampleIt) {
  Scene scene = builtinTemple(8);
  RenderOptions o = smallFrame();
  render(scene, o, {kAll, kAll});
  Renderer& r = renderer(scene);
  FrameSnapshot snap = snapshotFromRenderer(r, kAll);
  const uint32_t px = 48, py = 44;
  PixelDossier d = probePixel(snap, px, py);
  ASSERT_TRUE(d.shadowMap.valid) << d.shadowMap.note;
  ViewMapper mapper;
  initViewMapper(mapper, r);
  const LiveView normal = liveView(o, "Normal");
  const ViewDef& def = normal.def;
  ViewSettings s = defaultSettings(def);
  Canvas canvas(ctx(), o.width, o.height);
  auto draw = [&](std::optional<glm::ivec2> mark) {
    return canvas.draw(mapper, r, targetImage(r, normal.source),
                       viewParams(def, s, normal.gpu, resolveRange(def, s, nullptr), Placement{0, 0, 1}, false, mark,
                                  {o.shadowMapSize, o.shadowMapSize}));
  };
  std::vector<uint8_t> plain = draw(std::nullopt), marked = draw(glm::ivec2(d.shadowMap.x0, d.shadowMap.y0));
  auto at = [&](const std::vector<uint8_t>& img, uint32_t x, uint32_t y) { return &img[(size_t(y) * o.width + x) * 4]; };
  const uint8_t *p = at(plain, px, py), *q = at(marked, px, py);
  EXPECT_TRUE(p[0] != q[0] || p[1] != q[1] || p[2] != q[2]) << "the pixel that reads the texel is not marked";
  EXPECT_GT(int(q[0]) + int(q[2]) - 2 * int(q[1]), int(p[0]) + int(p[2]) - 2 * int(p[1])) << "the mark is magenta";
  int markedPixels = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) markedPixels += std::memcmp(at(plain, x, y), at(marked, x, y), 3) != 0;
  EXPECT_LT(markedPixels, int(o.width * o.height / 4)) << "one texel is read by a few pixels, not most";

  // The viewer's count, box and reason (views/analysis/shadow_marks.h, double precision on the CPU)
  // against the shader's marks (float on the GPU): the same pixels, but for lookups on a texel's edge.
  const glm::ivec2 texel(d.shadowMap.x0, d.shadowMap.y0);
  const ShadowMarks cpu = shadowMarks(snap, texel);
  ASSERT_TRUE(cpu.box.has_value());
  EXPECT_NEAR(double(cpu.pixels), double(markedPixels), std::max(2.0, 0.1 * markedPixels));
  int gpuOutsideBox = 0, cpuUnmarkedOnGpu = 0;
  for (uint32_t y = 0; y < o.height; ++y)
    for (uint32_t x = 0; x < o.width; ++x) {
      const bool gpu = std::memcmp(at(plain, x, y), at(marked, x, y), 3) != 0;
      const RegionRect& b = *cpu.box;
      gpuOutsideBox += gpu && (x + 1 < b.x || x > b.x + b.width || y + 1 < b.y || y > b.y + b.height);
    }
  for (const glm::ivec2& q : cpu.some) cpuUnmarkedOnGpu += std::memcmp(at(plain, q.x, q.y), at(marked, q.x, q.y), 3) == 0;
  EXPECT_EQ(gpuOutsideBox, 0) << "the box holds every pixel the shader marks (one pixel of slack)";
  EXPECT_LE(cpuUnmarkedOnGpu, std::max(1, int(cpu.some.size() / 10)));
  EXPECT_EQ(cpu.note, "");
  // A texel past every lookup of the frame: none marked, and the sentence says why.
  const bool after = cpu.readMax.x + 3 < int(o.shadowMapSize) && cpu.readMax.y + 3 < int(o.shadowMapSize);
  ASSERT_TRUE(after || (cpu.readMin.x >= 3 && cpu.readMin.y >= 3)) << "the frame reads the whole shadow map";
  const glm::ivec2 past = after ? cpu.readMax + 3 : cpu.readMin - 3;
  {
    const ShadowMarks none = shadowMarks(snap, past);
    EXPECT_EQ(none.pixels, 0);
    EXPECT_FALSE(none.box.has_value());
    EXPECT_NE(none.note.find("outside the texels the frame's surfaces read (x " + std::to_string(cpu.readMin.x) + ".."),
              std::string::npos) << none.note;
  }
  canvas.destroy(ctx());
  destroyViewMapper(mapper, r);
}

// The viewer's reference maps are views of no quantity (-1): they have no live target (under
// `make test-asan` the viewer read past the layout's quantities here once the maps were shown).
TEST(ViewMap, AViewOfNoQuantityHasNoNativeSource) {
  const Layout& layout = nativeLayout(smallFrame());
  ViewDef map;
  map.name = "error/shadow";
  EXPECT_FALSE(nativeSource(layout, map).has_value());
  map.quantity = int(layout.quantities.size());
  EXPECT_FALSE(nativeSource(layout, map).has_value());
  ViewDef normal = liveView(smallFrame(), "Normal").def;
  EXPECT_TRUE(nativeSource(layout, normal).has_value());
  normal.target = uint32_t(layout.targets.size());
  EXPECT_FALSE(nativeSource(layout, normal).has_value());
}

}  // namespace gb
