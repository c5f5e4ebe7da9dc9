// clustered_lighting's two variants (Renderer::lightingPixels, GBLENS_LIGHTING_PIXELS): one pixel
// an invocation (clustered_lighting.comp) and two (clustered_lighting2.comp) give the same hdr and
// the same coverage_masked counts, bit for bit: each pixel sums its cluster's lights in list order
// either way. The cases reach what the two-pixel variant does differently: lists of one staging
// round and of several (more than kTileSize^2 lights, both halves of a round staged), the two
// pixels of an invocation in different clusters (the temple's edges), a tile cut by the viewport
// (the second pixel outside it), each accumulation format, lights set up on the GPU, and lists
// that overflowed (their pixels shaded from the bin).
#include <algorithm>
#include <deque>

#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace {

RenderOptions clusteredOptions(uint32_t w, uint32_t h, int lights) {
  RenderOptions o;
  o.width = w;
  o.height = h;
  o.lights = lights;
  o.method = Method::Clustered;
  o.clusterAssign = ClusterAssign::Gpu;  // the compute pass (a CPU device would pick the grid's raster pass)
  o.fairies = false;
  o.coverage = true;
  return o;
}

struct Shaded {
  CpuImage hdr, coverage;
  ClusterStats clusters;
};

// One frame with `pixels` pixels an invocation. overflow: no room for any list, so every cluster
// is shaded from its bin (were some to fit, which ones would depend on the order cluster_lists'
// workgroups ran in, and two frames could differ).
Shaded shade(GpuTest& t, const Scene& scene, const RenderOptions& o, uint32_t pixels, bool overflow) {
  Renderer& r = t.renderer(scene);
  r.lightingPixels = pixels;
  r.clusters.listsFull = overflow;
  const FrameStats& st = t.render(scene, o, {{Target::Hdr, Target::CoverageMasked}});
  EXPECT_TRUE(passRan(st, "clustered_lighting"));
  EXPECT_EQ(st.clusterAssign, "gpu");
  return {r.readback[size_t(Target::Hdr)], r.readback[size_t(Target::CoverageMasked)], st.clusters};
}

uint32_t mostEvaluated(const CpuImage& coverage) {
  uint32_t most = 0;
  for (uint32_t y = 0; y < coverage.height; ++y)
    for (uint32_t x = 0; x < coverage.width; ++x) most = std::max(most, uint32_t(coverage.raw(x, y, 0)));
  return most;
}

}  // namespace

TEST_F(GpuTest, TwoPixelsAnInvocationShadeAsOneDoes) {
  struct Case {
    const char* what;
    Scene scene;
    RenderOptions o;
    bool overflow = false;
  };
  std::deque<Case> cases;  // a renderer per scene, kept by address
  for (int lights : {0, 16, 256}) cases.push_back({"temple", builtinTemple(lights), clusteredOptions(96, 54, lights)});
  cases.push_back({"4096 lights, odd height", builtinTemple(4096), clusteredOptions(97, 61, 4096)});
  cases.push_back({"rgba16f", builtinTemple(256), clusteredOptions(96, 54, 256)});
  cases.back().o.accumFormat = AccumFormat::Rgba16f;
  cases.push_back({"rgba8", builtinTemple(256), clusteredOptions(96, 54, 256)});
  cases.back().o.accumFormat = AccumFormat::Rgba8;
  cases.push_back({"light setup gpu", builtinTemple(1024), clusteredOptions(96, 54, 1024)});
  cases.back().o.lightSetup = LightSetup::Gpu;
  cases.push_back({"lists overflowed", builtinTemple(1024), clusteredOptions(96, 54, 1024), true});
  for (Case& c : cases) {
    const Shaded one = shade(*this, c.scene, c.o, 1, c.overflow);
    const Shaded two = shade(*this, c.scene, c.o, 2, c.overflow);
    EXPECT_EQ(differingTexels(one.hdr, two.hdr), 0u) << c.what;
    EXPECT_EQ(one.coverage.data, two.coverage.data) << c.what;
    // The premise of the overflow case: every cluster overflowed, in both frames.
    for (const Shaded* s : {&one, &two})
      EXPECT_EQ(s->clusters.listOverflows, c.overflow ? s->clusters.clusters : 0u) << c.what;
    for (const Shaded* s : {&one, &two}) EXPECT_EQ(s->clusters.tilesWithoutRoom, 0u) << c.what;
  }
  // The premises: the 4096-light frame has lists longer than one round of kTileSize^2 staged lights,
  // and the other frames' lists fit in one.
  EXPECT_GT(mostEvaluated(shade(*this, cases[3].scene, cases[3].o, 2, false).coverage), 256u);
  EXPECT_LE(mostEvaluated(shade(*this, cases[1].scene, cases[1].o, 2, false).coverage), 256u);
}

}  // namespace gb
