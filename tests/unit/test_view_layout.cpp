// The viewer's view logic without a GPU: rectangles of the layouts, the linked zoom/pan transform
// (the texel under the cursor stays put), the seed's keys, and the parameters each view chooses
// (channel isolation, ranges, highlights, grid), checked against hand-worked cases.
#include <gtest/gtest.h>

#include <cmath>

#include "views/ui/viewer_model.h"

namespace gb {

TEST(ViewLayout, GridAndSideBySideTileTheAreaWithoutOverlap) {
  Rect area{100, 20, 603, 405};
  std::vector<Rect> grid = layoutViews(area, LayoutMode::Grid, 4);
  ASSERT_EQ(grid.size(), 9u);
  for (size_t i = 0; i < grid.size(); ++i) {
    const Rect& a = grid[i];
    EXPECT_GE(a.x, area.x);
    EXPECT_GE(a.y, area.y);
    EXPECT_LE(a.x + a.w, area.x + area.w);
    EXPECT_LE(a.y + a.h, area.y + area.h);
    EXPECT_GT(a.w, 190);
    for (size_t j = i + 1; j < grid.size(); ++j) {
      const Rect& b = grid[j];
      bool apart = a.x + a.w <= b.x || b.x + b.w <= a.x || a.y + a.h <= b.y || b.y + b.h <= a.y;
      EXPECT_TRUE(apart) << i << " overlaps " << j;
    }
  }
  std::vector<Rect> two = layoutViews(area, LayoutMode::SideBySide, 4);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].y, two[1].y);  // wider than tall: side by side
  EXPECT_EQ(layoutViews({0, 0, 300, 800}, LayoutMode::SideBySide)[0].x, 0.0);  // taller: stacked
  EXPECT_GT(layoutViews({0, 0, 300, 800}, LayoutMode::SideBySide)[1].y, 0.0);
}

TEST(ViewLayout, FitCentresTheImageAndTexelsMapBothWays) {
  Rect r{10, 20, 400, 300};
  Placement p = placeImage(r, 320, 180, ViewTransform{});
  EXPECT_DOUBLE_EQ(p.scale, 1.25);  // 400 / 320 < 300 / 180
  EXPECT_DOUBLE_EQ(p.originX, 10.0);
  EXPECT_DOUBLE_EQ(p.originY, std::round(20 + (300 - 180 * 1.25) / 2));  // whole pixels: no shimmer
  glm::dvec2 t = texelAt(p, windowAt(p, {17.25, 3.5}));
  EXPECT_NEAR(t.x, 17.25, 1e-12);
  EXPECT_NEAR(t.y, 3.5, 1e-12);
  // 1:1 is exact: one texel, one pixel.
  ViewTransform one;
  one.zoom = zoomForOneToOne(r, 320, 180);
  EXPECT_DOUBLE_EQ(placeImage(r, 320, 180, one).scale, 1.0);
}

TEST(ViewLayout, WheelZoomKeepsTheTexelUnderTheCursor) {
  Rect r{0, 0, 640, 360};
  ViewTransform t;
  glm::dvec2 cursor(123.0, 301.0);
  for (double factor : {1.37, 2.9, 0.61, 5.3}) {
    glm::dvec2 before = texelAt(placeImage(r, 1000, 500, t), cursor);
    zoomAbout(t, r, 1000, 500, cursor, factor);
    glm::dvec2 after = texelAt(placeImage(r, 1000, 500, t), cursor);
    // Origins are whole pixels (no shimmering): the texel moves by less than a pixel's worth.
    double pixel = 1.0 / placeImage(r, 1000, 500, t).scale;
    EXPECT_NEAR(after.x, before.x, pixel) << factor;
    EXPECT_NEAR(after.y, before.y, pixel) << factor;
  }
  glm::dvec2 before = texelAt(placeImage(r, 1000, 500, t), cursor);
  panBy(t, r, 1000, 500, {40.0, -12.0});
  glm::dvec2 after = texelAt(placeImage(r, 1000, 500, t), cursor + glm::dvec2(40.0, -12.0));
  double pixel = 1.0 / placeImage(r, 1000, 500, t).scale;
  EXPECT_NEAR(after.x, before.x, pixel);
  EXPECT_NEAR(after.y, before.y, pixel);
}

TEST(ViewLayout, SeedKeysPickTheirViews) {
  ViewerModel m;
  EXPECT_TRUE(applyViewKey(m, 1));
  EXPECT_EQ(m.layout, LayoutMode::Grid);
  EXPECT_EQ(visibleViews(m).size(), 9u);
  const std::pair<int, ViewKind> keys[] = {{2, ViewKind::Albedo},         {3, ViewKind::Normal},
                                           {4, ViewKind::Depth},          {5, ViewKind::Specular},
                                           {6, ViewKind::Shadow},         {7, ViewKind::ShadowMap},
                                           {8, ViewKind::CoverageMasked}, {9, ViewKind::CoverageFull},
                                           {0, ViewKind::Final}};
  for (auto [key, kind] : keys) {
    EXPECT_TRUE(applyViewKey(m, key));
    EXPECT_EQ(m.layout, LayoutMode::Single);
    ASSERT_EQ(visibleViews(m).size(), 1u);
    EXPECT_EQ(visibleViews(m)[0], kind) << key;
  }
}

TEST(ViewParams, EachViewChoosesItsMappingChannelsAndHighlights) {
  auto params = [](ViewKind k, ViewSettings s, const std::vector<RangeStats>* stats = nullptr, double scale = 1.0) {
    const ViewDef& d = viewDef(k);
    return viewParams(d, s, resolveRange(d, s, stats), Placement{0, 0, scale}, true, std::nullopt, {1, 1});
  };
  // Specular: the alpha channel of albedo_specular, as grey, not sRGB-encoded.
  gpu::ViewParams p = params(ViewKind::Specular, defaultSettings(ViewKind::Specular));
  EXPECT_EQ(p.mode.x, gpu::kViewMapGrey);
  EXPECT_EQ(p.mode.y, 0x8u);
  EXPECT_FALSE(p.mode.z & gpu::kViewFlagSrgb);
  // Albedo: RGB colour, sRGB-encoded; G alone becomes grey of G (still colour data: sRGB).
  p = params(ViewKind::Albedo, defaultSettings(ViewKind::Albedo));
  EXPECT_EQ(p.mode.x, gpu::kViewMapColor);
  EXPECT_EQ(p.mode.y, 0x7u);
  EXPECT_TRUE(p.mode.z & gpu::kViewFlagSrgb);
  ViewSettings g = defaultSettings(ViewKind::Albedo);
  g.channels = 0x2;
  p = params(ViewKind::Albedo, g);
  EXPECT_EQ(p.mode.x, gpu::kViewMapGrey);
  EXPECT_EQ(p.mode.y, 0x2u);
  // RGBA selected: alpha is not displayable as colour, the RGB channels are shown.
  g.channels = 0xF;
  EXPECT_EQ(params(ViewKind::Albedo, g).mode.y, 0x7u);
  // Normals: [-1, 1] to colour; negative components are data here, not flagged.
  p = params(ViewKind::Normal, defaultSettings(ViewKind::Normal));
  EXPECT_EQ(p.range.x, -1.0f);
  EXPECT_EQ(p.range.y, 1.0f);
  EXPECT_FALSE(p.mode.z & gpu::kViewFlagNegative);
  EXPECT_TRUE(params(ViewKind::Depth, defaultSettings(ViewKind::Depth)).mode.z & gpu::kViewFlagNegative);
  // Depth: the automatic range is the data's min/max over valid texels; manual when asked.
  RangeStats depth;
  depth.count = 10;
  depth.lo = 2.5;
  depth.hi = 40.0;
  std::vector<RangeStats> stats = {depth};
  p = params(ViewKind::Depth, defaultSettings(ViewKind::Depth), &stats);
  EXPECT_EQ(p.mode.x, gpu::kViewMapDepth);
  EXPECT_EQ(p.mode.w, gpu::kRangePositive);
  EXPECT_EQ(p.range.x, 2.5f);
  EXPECT_EQ(p.range.y, 40.0f);
  ViewSettings manual = defaultSettings(ViewKind::Depth);
  manual.autoRange = false;
  manual.black = 1.0f;
  manual.white = 9.0f;
  p = params(ViewKind::Depth, manual, &stats);
  EXPECT_EQ(p.range.x, 1.0f);
  EXPECT_EQ(p.range.y, 9.0f);
  // Coverage: heat map from 0 to the largest count (at least 1: the legend's scale).
  RangeStats cov;
  cov.count = 5;
  cov.lo = 0;
  cov.hi = 0;
  stats = {cov};
  p = params(ViewKind::CoverageFull, defaultSettings(ViewKind::CoverageFull), &stats);
  EXPECT_EQ(p.mode.x, gpu::kViewMapHeat);
  EXPECT_EQ(p.range.y, 1.0f);
  // The texel grid appears from 8 pixels per texel.
  EXPECT_FALSE(params(ViewKind::Final, defaultSettings(ViewKind::Final), nullptr, 7.9).mode.z & gpu::kViewFlagGrid);
  EXPECT_TRUE(params(ViewKind::Final, defaultSettings(ViewKind::Final), nullptr, 8.0).mode.z & gpu::kViewFlagGrid);
  // Automatic range requests: one per selected channel, none when manual.
  EXPECT_EQ(rangeRequests(viewDef(ViewKind::Depth), defaultSettings(ViewKind::Depth)).size(), 1u);
  EXPECT_TRUE(rangeRequests(viewDef(ViewKind::Depth), manual).empty());
  ViewSettings hdr = defaultSettings(ViewKind::Hdr);
  hdr.autoRange = true;
  EXPECT_EQ(rangeRequests(viewDef(ViewKind::Hdr), hdr).size(), 3u);
}

}  // namespace gb
