// The viewer's view logic without a GPU: rectangles of the layouts, the linked zoom/pan transform
// (the texel under the cursor stays put), the seed's keys, and the parameters each view chooses
// (channel isolation, ranges, highlights, grid), checked against hand-worked cases.
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/core/layout_json.h"
#include "views/ui/view_map.h"
#include "views/ui/viewer_model.h"

namespace gb {

TEST(ViewLayout, GridAndSideBySideTileTheAreaWithoutOverlap) {
  Rect area{100, 20, 1203, 405};
  for (size_t count : {3u, 9u, 12u, 14u}) {
    std::vector<Rect> grid = layoutViews(area, LayoutMode::Grid, count, 16.0 / 9.0);
    ASSERT_EQ(grid.size(), count);
    for (size_t i = 0; i < grid.size(); ++i) {
      const Rect& a = grid[i];
      EXPECT_GE(a.x, area.x);
      EXPECT_GE(a.y, area.y);
      EXPECT_LE(a.x + a.w, area.x + area.w);
      EXPECT_LE(a.y + a.h, area.y + area.h);
      for (size_t j = i + 1; j < grid.size(); ++j) {
        const Rect& b = grid[j];
        bool apart = a.x + a.w <= b.x || b.x + b.w <= a.x || a.y + a.h <= b.y || b.y + b.h <= a.y;
        EXPECT_TRUE(apart) << i << " overlaps " << j;
      }
    }
  }
  // The columns that show a 16:9 image largest, worked by hand: 12 views in 1203x405 (gap 4):
  // 4 columns x 3 rows: cells 297.75 x 132.3 -> 16:9 fits 235 wide; 6 x 2: 197.2 x 200.5 -> 197.2;
  // 3 x 4: 398.3 x 98.25 -> 174.7; so 4 columns.
  std::vector<Rect> twelve = layoutViews(area, LayoutMode::Grid, 12, 16.0 / 9.0);
  EXPECT_EQ(twelve[3].y, twelve[0].y);
  EXPECT_GT(twelve[4].y, twelve[0].y);
  // "Two" is side by side whatever the area's shape (people compare left and right).
  std::vector<Rect> two = layoutViews({0, 0, 300, 800}, LayoutMode::SideBySide, 2, 16.0 / 9.0);
  ASSERT_EQ(two.size(), 2u);
  EXPECT_EQ(two[0].y, two[1].y);
  EXPECT_GT(two[1].x, two[0].x);
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

// gblens's own layout under its default options: its views in the order its keys follow.
ViewerModel gblensModel() {
  ViewerModel m;
  setViews(m, layoutViews(nativeLayout(RenderOptions{})));
  return m;
}

TEST(ViewLayout, KeysFollowTheLayoutsViews) {
  ViewerModel m = gblensModel();
  // The first view is the display colour (Final), then the layout's quantities in order.
  const std::vector<std::string> expected = {"Final", "Albedo", "Specular", "Normal", "Shadow", "Depth",
                                             "HardwareDepth", "Stencil", "ShadowMap", "HDR"};
  ASSERT_GE(m.views.size(), expected.size());
  for (size_t i = 0; i < expected.size(); ++i) EXPECT_EQ(m.views[i].name, expected[i]) << i;
  EXPECT_TRUE(applyViewKey(m, 1));
  EXPECT_EQ(m.layout, LayoutMode::Grid);
  EXPECT_EQ(visibleViews(m).size(), m.views.size());  // none unavailable here
  m.unavailable[2] = "not captured";
  EXPECT_EQ(visibleViews(m).size(), m.views.size() - 1);  // the grid shows what the frame holds
  const std::pair<int, const char*> keys[] = {{2, "Albedo"}, {3, "Specular"}, {4, "Normal"}, {9, "ShadowMap"}, {0, "Final"}};
  for (auto [key, view] : keys) {
    EXPECT_TRUE(applyViewKey(m, key));
    EXPECT_EQ(m.layout, LayoutMode::Single);
    ASSERT_EQ(visibleViews(m).size(), 1u);
    EXPECT_EQ(m.views[size_t(visibleViews(m)[0])].name, view) << key;
  }
  // Names are found ignoring case and underscores (the command line's old view names too).
  EXPECT_EQ(m.views[size_t(findView(m.views, "hardware_depth"))].name, "HardwareDepth");
  EXPECT_EQ(m.views[size_t(findView(m.views, "shadowmap"))].name, "ShadowMap");
  EXPECT_EQ(findView(m.views, "Occlusion"), -1);
}

TEST(ViewLayout, AnotherLayoutsViewsAreItsQuantitiesOnly) {
  // A foreign layout: position, occlusion, ids, no shadow, specular or stencil.
  Layout l;
  l.targets.resize(3);
  auto add = [&](QuantityKind k, const char* name, uint32_t target) {
    Quantity q;
    q.kind = k;
    q.name = name;
    q.target = target;
    q.channels = k == QuantityKind::Position || k == QuantityKind::Radiance ? std::vector<uint32_t>{0, 1, 2} : std::vector<uint32_t>{0};
    l.quantities.push_back(q);
  };
  add(QuantityKind::Position, "ViewPos", 0);
  add(QuantityKind::Occlusion, "AO", 1);
  add(QuantityKind::Radiance, "Lit", 2);
  add(QuantityKind::Id, "Object", 1);
  std::vector<ViewDef> views = layoutViews(l);
  ASSERT_EQ(views.size(), 4u);
  EXPECT_EQ(views[0].name, "Lit");  // the first colour quantity first
  EXPECT_EQ(views[0].visual, Visual::Color);
  EXPECT_TRUE(views[0].hdr);
  EXPECT_EQ(views[1].visual, Visual::Position);
  EXPECT_EQ(views[2].visual, Visual::Scalar);
  EXPECT_EQ(views[3].visual, Visual::Id);
  for (const ViewDef& v : views) EXPECT_TRUE(v.name != "Shadow" && v.name != "Specular" && v.name != "Stencil");
}

TEST(ViewParams, EachViewChoosesItsMappingChannelsAndHighlights) {
  ViewerModel m = gblensModel();
  auto view = [&](const char* name) { return m.views[size_t(findView(m.views, name))]; };
  auto params = [&](const char* name, ViewSettings s, const std::vector<RangeStats>* stats = nullptr, double scale = 1.0) {
    const ViewDef d = view(name);
    ViewGpuSource src;
    nativeSource(nativeLayout(RenderOptions{}), d, &src);
    return viewParams(d, s, src, resolveRange(d, s, stats), Placement{0, 0, scale}, true, std::nullopt, {1, 1});
  };
  auto defaults = [&](const char* name) { return defaultSettings(view(name)); };
  // Specular: the alpha channel of albedo_specular, as grey, not sRGB-encoded.
  gpu::ViewParams p = params("Specular", defaults("Specular"));
  EXPECT_EQ(p.mode.x, gpu::kViewMapGrey);
  EXPECT_EQ(p.mode.y, 0x8u);
  EXPECT_FALSE(p.mode.z & gpu::kViewFlagSrgb);
  // Albedo: RGB colour, sRGB-encoded; G alone becomes grey of G.
  p = params("Albedo", defaults("Albedo"));
  EXPECT_EQ(p.mode.x, gpu::kViewMapColor);
  EXPECT_EQ(p.mode.y, 0x7u);
  EXPECT_TRUE(p.mode.z & gpu::kViewFlagSrgb);
  ViewSettings g = defaults("Albedo");
  g.channels = 0x2;
  p = params("Albedo", g);
  EXPECT_EQ(p.mode.x, gpu::kViewMapGrey);
  EXPECT_EQ(p.mode.y, 0x2u);
  // Exposure: 2^EV as the colour mapping's gain.
  g = defaults("HDR");
  g.exposure = 2.0f;
  EXPECT_EQ(params("HDR", g).range.w, 4.0f);
  // Normals: [-1, 1] to colour, decoded from the live target's encoding; negatives are data here.
  p = params("Normal", defaults("Normal"));
  EXPECT_EQ(p.range.x, -1.0f);
  EXPECT_EQ(p.range.y, 1.0f);
  EXPECT_TRUE(p.mode.z & gpu::kViewFlagNativeNormal);
  EXPECT_FALSE(p.mode.z & gpu::kViewFlagNegative);
  EXPECT_TRUE(params("Depth", defaults("Depth")).mode.z & gpu::kViewFlagNegative);
  // Depth: the automatic range is the data's min/max; manual when asked; false colour and log.
  RangeStats depth;
  depth.count = 10;
  depth.lo = 2.5;
  depth.hi = 40.0;
  std::vector<RangeStats> stats = {depth};
  p = params("Depth", defaults("Depth"), &stats);
  EXPECT_EQ(p.mode.x, gpu::kViewMapDepth);
  EXPECT_EQ(p.mode.w, gpu::kRangeNotValue);  // gblens's eye depth: background 0
  EXPECT_EQ(p.range.x, 2.5f);
  EXPECT_EQ(p.range.y, 40.0f);
  ViewSettings manual = defaults("Depth");
  manual.autoRange = false;
  manual.black = 1.0f;
  manual.white = 9.0f;
  manual.falseColor = true;
  manual.log = true;
  p = params("Depth", manual, &stats);
  EXPECT_EQ(p.range.x, 1.0f);
  EXPECT_EQ(p.range.y, 9.0f);
  EXPECT_TRUE(p.mode.z & gpu::kViewFlagFalseColor);
  EXPECT_TRUE(p.mode.z & gpu::kViewFlagLog);
  // Stencil: a colour per value, the chosen bits only.
  ViewSettings bits = defaults("Stencil");
  bits.stencilBits = 0x80;
  p = params("Stencil", bits);
  EXPECT_EQ(p.mode.x, gpu::kViewMapStencil);
  EXPECT_EQ(p.extra.x, 0x80u);
  // Coverage: heat map from 0 to the largest count (at least 1: the legend's scale).
  RangeStats cov;
  cov.count = 5;
  stats = {cov};
  p = params("CoverageFull", defaults("CoverageFull"), &stats);
  EXPECT_EQ(p.mode.x, gpu::kViewMapHeat);
  EXPECT_EQ(p.range.y, 1.0f);
  // The texel grid appears from 8 pixels per texel.
  EXPECT_FALSE(params("Final", defaults("Final"), nullptr, 7.9).mode.z & gpu::kViewFlagGrid);
  EXPECT_TRUE(params("Final", defaults("Final"), nullptr, 8.0).mode.z & gpu::kViewFlagGrid);
}

}  // namespace gb
