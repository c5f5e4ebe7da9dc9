// From the foreign test subject's captures (tests/subjects/foreign_deferred: unnamed textures, a
// Y-down world, view-space positions with eye depth / far in w, the projection before the view matrix
// in a uniform buffer, a perspective and an orthographic variant) to correct positions without
// reading its shaders: `import --suggest-layout` finds its targets and formats, the eye depth in w
// with its scale, and the camera at the offsets the app's own dump states; the draft imported as it
// is decodes every pixel's positions (from both depths and as stored) and normals exactly as the
// hand-written layout.json does, which test_foreign.cpp holds to the app's read-back within the
// derived fp32 bound; the rebuilt positions also equal the app's stored ones within a loose bound
// here, so a wrong camera cannot pass unnoticed. The uniform buffer also holds projection * view at
// byte 128, a plausible wrong offset: suggest does not take it.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "tests/support/capture_util.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

const std::string kOut = GBLENS_BUILD_DIR + "/foreign";
const std::string kLayout = FOREIGN_DEFERRED_DIR + "/layout.json";

Capture importWith(const std::string& rdc, const std::string& layout, const std::string& out) {
  RunResult r = runGblens("import '" + rdc + "' --layout '" + layout + "' -o '" + out + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  Capture c;
  std::string error;
  EXPECT_TRUE(loadCapture(out, c, error)) << error;
  return c;
}

const Quantity& only(const Layout& l, QuantityKind k, DepthEncoding e = DepthEncoding::Eye) {
  for (const Quantity& q : l.quantities)
    if (q.kind == k && (k != QuantityKind::Depth || q.depth == e)) return q;
  throw std::runtime_error(std::string("the layout has no ") + name(k));
}

void expectDraft(const std::string& stem, const std::string& dumpDir, bool ortho) {
  SCOPED_TRACE(stem);
  const std::string rdc = kOut + "/" + stem + ".rdc", dir = freshDir("foreign-suggest-" + stem);
  std::ifstream dumpCamera(dumpDir + "/camera.json");
  ASSERT_TRUE(dumpCamera) << "the foreign_captures fixture did not run (ctest -R Foreign runs it)";
  const nlohmann::json app = nlohmann::json::parse(dumpCamera);

  RunResult suggest = runGblens("import '" + rdc + "' --suggest-layout -o '" + dir + "/draft.json'");
  ASSERT_EQ(suggest.exitCode, 0) << suggest.output;
  const nlohmann::json draft = nlohmann::json::parse(std::ifstream(dir + "/draft.json"));
  Layout l;
  std::string error;
  ASSERT_TRUE(parseLayout(draft, "draft.json", l, error)) << error;

  // The targets and formats the app's dump lists, in its order, read from the textures it names.
  ASSERT_EQ(l.targets.size(), app["targets"].size()) << draft.dump(1);
  const char* formats[] = {"rgba32f", "rgba8_unorm", "rgba8_srgb", "d32f", "r8_unorm", "rgba16f", "rgba8_unorm"};
  for (size_t t = 0; t < l.targets.size(); ++t) EXPECT_EQ(l.targets[t].format.name, formats[t]) << t;
  const Quantity& position = only(l, QuantityKind::Position);
  EXPECT_EQ(position.space, Space::View);
  const Quantity& linear = only(l, QuantityKind::Depth, DepthEncoding::Eye);
  EXPECT_EQ(linear.target, position.target);
  EXPECT_EQ(linear.channels, std::vector<uint32_t>{3});
  EXPECT_EQ(linear.scale, app["far"].get<double>());
  EXPECT_EQ(linear.background, 1.0);
  EXPECT_EQ(only(l, QuantityKind::Normal).normal, NormalEncoding::XyzUnorm);
  EXPECT_EQ(only(l, QuantityKind::Normal).space, Space::View);
  EXPECT_EQ(only(l, QuantityKind::Occlusion).target, 4u);

  // The camera where the app's dump says its uniform buffer holds it.
  const nlohmann::json& cam = draft["camera"]["renderdoc"];
  size_t clipAt = 0, viewAt = 0;
  for (const nlohmann::json& m : app["uniform_buffer"]["members"]) {
    if (m["name"] == "clip_from_view") clipAt = m["offset"];
    if (m["name"] == "view_from_world") viewAt = m["offset"];
  }
  EXPECT_EQ(cam["clip_from_view"]["offset"], clipAt);
  EXPECT_EQ(cam["view_from_world"]["offset"], viewAt);
  EXPECT_NE(cam["view_from_world"]["offset"], 128) << "projection * view is no view matrix";
  EXPECT_EQ(draft["camera"]["up"], "-y");  // the app's world up is (0, -1, 0)
  EXPECT_EQ(draft["camera"]["projection"], ortho ? "orthographic" : "perspective");
  EXPECT_EQ(app["projection"], ortho ? "orthographic" : "perspective");

  // Imported with the draft as it is, and with the hand-written layout: the same positions and
  // normals at every pixel, and positions from the hardware depth near the app's stored ones.
  const Capture a = importWith(rdc, dir + "/draft.json", dir + "/draft-import");
  const Capture b = importWith(rdc, kLayout, dir + "/hand-import");
  const FrameSnapshot &fa = a.frame, &fb = b.frame;
  const Quantity* pairs[][2] = {
      {&only(fa.layout, QuantityKind::Position), fb.layout.findByName("P")},
      {&only(fa.layout, QuantityKind::Depth, DepthEncoding::Eye), fb.layout.findByName("LinearDepth")},
      {&only(fa.layout, QuantityKind::Depth, DepthEncoding::Hardware), fb.layout.findByName("Depth")}};
  const std::string positions = readText(dumpDir + "/position.bin");
  ASSERT_EQ(positions.size(), size_t(fa.camera.width) * fa.camera.height * 16);
  size_t surfaces = 0;
  for (uint32_t y = 0; y < fa.camera.height; ++y)
    for (uint32_t x = 0; x < fa.camera.width; ++x) {
      ASSERT_EQ(hasSurface(fa, x, y), hasSurface(fb, x, y)) << x << "," << y;
      for (auto& [qa, qb] : pairs) {
        ASSERT_TRUE(qb);
        const std::optional<glm::dvec3> pa = decodePosition(fa, *qa, x, y), pb = decodePosition(fb, *qb, x, y);
        ASSERT_EQ(pa.has_value(), pb.has_value()) << qa->name << " " << x << "," << y;
        if (pa) {
          EXPECT_EQ(*pa, *pb) << qa->name << " " << x << "," << y;
        }
      }
      if (!hasSurface(fa, x, y)) continue;
      ++surfaces;
      EXPECT_EQ(decodeNormal(fa, only(fa.layout, QuantityKind::Normal), x, y).unit,
                decodeNormal(fb, *fb.layout.findByName("N"), x, y).unit);
      float stored[4];
      std::memcpy(stored, positions.data() + (size_t(y) * fa.camera.width + x) * 16, 16);
      const glm::dvec3 p(stored[0], stored[1], stored[2]);
      // Loose on purpose (test_foreign.cpp derives the tight bound): a wrong camera is metres off.
      EXPECT_LT(glm::length(*decodePosition(fa, *pairs[2][0], x, y) - p), 1e-3 * glm::length(p)) << x << "," << y;
    }
  EXPECT_GT(surfaces, size_t(fa.camera.width) * fa.camera.height / 4);
}

TEST(ForeignSuggest, PerspectiveDraftFindsTargetsCameraAndLinearDepth) {
  expectDraft("foreign", kOut + "/dump", false);
}

TEST(ForeignSuggest, OrthographicDraftFindsTargetsCameraAndLinearDepth) {
  expectDraft("foreign_ortho", kOut + "/dump_ortho", true);
}

}  // namespace
}  // namespace gb
