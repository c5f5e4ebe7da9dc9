// The compare viewer's choices (views/ui/compare_view.h, viewSlots): the mode every view slot shows
// (FLIP only for colour views, the others |A - B|), Space flipping A and B from any mode, and the two
// dossiers as rows, checked against hand-written dossiers whose differing values are known.
#include <gtest/gtest.h>

#include "views/ui/compare_view.h"

namespace gb {

namespace {

ViewerModel compareModel() {
  ViewerModel m;
  m.source = FrameSource::Compare;
  ViewDef colour, normal;
  colour.name = "Final";
  colour.visual = Visual::Color;
  normal.name = "Normal";
  normal.visual = Visual::Normal;
  setViews(m, {colour, normal});
  m.rendered.width = 160, m.rendered.height = 90;
  return m;
}

}  // namespace

TEST(CompareView, EverySlotShowsTheModeFlipOnlyForColourViews) {
  ViewerModel m = compareModel();
  const Rect area{0, 0, 800, 600};
  m.layout = LayoutMode::Grid;
  auto sides = [&] {
    std::vector<std::pair<FrameSide, bool>> out;
    for (const ViewSlot& s : viewSlots(m, area)) out.push_back({s.side, s.split});
    return out;
  };
  using P = std::vector<std::pair<FrameSide, bool>>;
  EXPECT_EQ(sides(), (P{{FrameSide::A, false}, {FrameSide::A, false}}));
  m.compareSide = FrameSide::B;
  EXPECT_EQ(sides(), (P{{FrameSide::B, false}, {FrameSide::B, false}}));
  m.compareMode = CompareMode::Swipe;
  EXPECT_EQ(sides(), (P{{FrameSide::B, true}, {FrameSide::B, true}}));
  m.compareMode = CompareMode::Difference;
  EXPECT_EQ(sides(), (P{{FrameSide::Difference, false}, {FrameSide::Difference, false}}));
  m.compareMode = CompareMode::Flip;
  EXPECT_EQ(sides(), (P{{FrameSide::Flip, false}, {FrameSide::Difference, false}}));
  // One view in a row: A, B and |A - B| side by side.
  m.layout = LayoutMode::Single;
  m.compareMode = CompareMode::Row;
  EXPECT_EQ(sides(), (P{{FrameSide::A, false}, {FrameSide::B, false}, {FrameSide::Difference, false}}));
  // A live frame has no sides.
  m.source = FrameSource::Live;
  m.compareMode = CompareMode::Flip;
  EXPECT_EQ(sides(), (P{{FrameSide::A, false}}));
}

TEST(CompareView, SpaceFlipsAAndBAndReturnsToThemFromAnyMode) {
  ViewerModel m = compareModel();
  EXPECT_EQ(m.compareSide, FrameSide::A);
  flipCompareSide(m);
  EXPECT_EQ(m.compareSide, FrameSide::B);
  flipCompareSide(m);
  EXPECT_EQ(m.compareSide, FrameSide::A);
  m.compareMode = CompareMode::Flip;
  flipCompareSide(m);
  EXPECT_EQ(m.compareMode, CompareMode::Alternate);
  EXPECT_EQ(m.compareSide, FrameSide::B);
}

TEST(CompareView, DossierRowsPairFieldsByNameAndMarkTheDifferingOnes) {
  // Lights named by index (not position in the list), short vectors as one value, B's extra light
  // within its section, a value equal to 7 digits but not exactly shown to 17.
  const nlohmann::json a = nlohmann::json::parse(R"({
    "pixel": [3, 4],
    "lighting": {"point_lights": [{"index": 5, "distance": 1.5}, {"index": 7, "distance": 2.0}], "total": [0.1, 0.2, 0.3]},
    "final": {"stored": 0.123456789}
  })");
  const nlohmann::json b = nlohmann::json::parse(R"({
    "pixel": [3, 4],
    "lighting": {"point_lights": [{"index": 7, "distance": 2.5}, {"index": 9, "distance": 0.5}], "total": [0.1, 0.2, 0.3]},
    "final": {"stored": 0.123456781}
  })");
  const std::vector<DossierRow> rows = dossierRows(a, b);
  struct Want {
    const char *section, *field, *a, *b;
    bool differs;
  };
  // JSON objects iterate in key order (nlohmann::json): sections and fields alphabetically.
  const std::vector<Want> want = {
      {"final", "stored", "0.123456789", "0.123456781", true},
      {"lighting", "point_lights[5].distance", "1.5", "", true},
      {"lighting", "point_lights[5].index", "5", "", true},
      {"lighting", "point_lights[7].distance", "2", "2.5", true},
      {"lighting", "point_lights[7].index", "7", "7", false},
      {"lighting", "total", "[0.1, 0.2, 0.3]", "[0.1, 0.2, 0.3]", false},
      {"lighting", "point_lights[9].distance", "", "0.5", true},
      {"lighting", "point_lights[9].index", "", "9", true},
      {"pixel", "", "[3, 4]", "[3, 4]", false},
  };
  ASSERT_EQ(rows.size(), want.size());
  for (size_t i = 0; i < want.size(); ++i) {
    EXPECT_EQ(rows[i].section, want[i].section) << i;
    EXPECT_EQ(rows[i].field, want[i].field) << i;
    EXPECT_EQ(rows[i].a, want[i].a) << i;
    EXPECT_EQ(rows[i].b, want[i].b) << i;
    EXPECT_EQ(rows[i].differs, want[i].differs) << i;
  }
}

}  // namespace gb
