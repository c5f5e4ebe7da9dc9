// Blender through an orthographic camera, in full float (tests/data/blender/ortho, rendered by
// assets/blender/render_gbuffer.py --ortho --full-float, `make fixtures`): the shipped layout reads
// float32 colour passes as well as half ones, the projection is recognised as orthographic, and
// positions rebuilt from Cycles' Depth pass through it equal Cycles' own Position pass. Also: the
// sidecar is looked for only beside the images, and --suggest-layout drafts both Blender fixtures
// from their channel names into layouts that decode every pixel as the shipped layout does.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "renderer/core/assets.h"
#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "tests/support/capture_util.h"
#include "views/import/import.h"
#include "views/infer/suggest.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
const std::string kBlender = std::string(GBLENS_SOURCE_DIR) + "/tests/data/blender";
const std::string kOrtho = kBlender + "/ortho";

Layout shippedLayout() {
  Layout l;
  std::string error, dir;
  EXPECT_TRUE(loadImportLayout("builtin:blender-cycles", {}, l, dir, error)) << error;
  return l;
}

bool importExr(const std::string& exr, const Layout& layout, FrameSnapshot& f, std::string& error) {
  ImportInput in;
  in.layout = layout;
  in.files = {exr};
  return importFrame(in, f, error);
}

const Quantity& orthoQuantity(const FrameSnapshot& f, const char* name) {
  const Quantity* q = f.layout.findByName(name);
  if (!q) throw std::runtime_error(std::string("no quantity ") + name);
  return *q;
}

// Float32 rounding of the scene's numbers (16 roundings of S = |eye| + max |P|, as the perspective
// fixture's test argues) plus Cycles' ray start within 0.005 px of the pixel centre (its 0.01 px
// filter): for an orthographic camera a fixed distance, half a pixel's width times 0.01.
double bound(const FrameSnapshot& f) {
  const Quantity& position = orthoQuantity(f, "Position");
  double s = 0.0;
  for (uint32_t y = 0; y < f.camera.height; ++y)
    for (uint32_t x = 0; x < f.camera.width; ++x) {
      const std::array<double, 4> p = storedValues(f, position, x, y);
      s = std::max(s, glm::length(glm::dvec3(p[0], p[1], p[2])));
    }
  s += glm::length(glm::dvec3(f.camera.worldFromEye[3]));
  const glm::dmat4& p = f.camera.clipFromEye;
  return 16.0 * std::ldexp(1.0, -24) * s +
         0.005 * std::hypot(2.0 / (f.camera.width * p[0][0]), 2.0 / (f.camera.height * p[1][1]));
}

TEST(BlenderOrtho, FullFloatPassesImportAndPositionsFromDepthMatchThePositionPass) {
  FrameSnapshot f;
  std::string error;
  ASSERT_TRUE(importExr(kOrtho + "/cycles.exr", shippedLayout(), f, error)) << error;
  EXPECT_EQ(f.layout.targets[size_t(f.layout.findTarget("combined"))].format.name, "rgba32f");
  EXPECT_EQ(f.layout.targets[size_t(f.layout.findTarget("diffuse_color"))].format.name, "rgb32f");
  ASSERT_TRUE(orthographic(f.camera));
  EXPECT_EQ(f.camera.width, 96u);
  EXPECT_NEAR(f.camera.znear, 0.1, 1e-6);
  EXPECT_NEAR(f.camera.zfar, 100.0, 1e-4);
  EXPECT_NE(f.layout.camera.from.find("sidecar "), std::string::npos) << f.layout.camera.from;
  EXPECT_NE(f.layout.camera.from.find("ortho/camera.json"), std::string::npos) << f.layout.camera.from;

  const Quantity &depth = orthoQuantity(f, "Depth"), &position = orthoQuantity(f, "Position");
  const double b = bound(f);
  double worst = 0.0, worstAxial = 0.0;
  int surfaces = 0;
  for (uint32_t y = 0; y < f.camera.height; ++y)
    for (uint32_t x = 0; x < f.camera.width; ++x) {
      std::optional<glm::dvec3> fromDepth = decodePosition(f, depth, x, y);
      if (!fromDepth) continue;
      const glm::dvec3 stored = *decodePosition(f, position, x, y);
      worst = std::max(worst, glm::length(*fromDepth - stored));
      worstAxial = std::max(worstAxial, std::abs(-stored.z - *decodeEyeDepth(f, depth, x, y)));
      ++surfaces;
    }
  std::printf("blender ortho: %d surface pixels; positions from Depth vs the Position pass max %.3g m (bound %.3g m); "
              "Depth vs -z of Position max %.3g m\n", surfaces, worst, b, worstAxial);
  EXPECT_GT(surfaces, 96 * 54 / 3);  // the floor and the objects; sky around them
  EXPECT_LE(worst, b);
  EXPECT_LE(worstAxial, b);
}

TEST(BlenderOrtho, AHalfOnlyLayoutRefusesFullFloatWithAHint) {
  const std::string* text = assetText("layouts/blender-cycles.json");
  ASSERT_NE(text, nullptr);
  nlohmann::json j = nlohmann::json::parse(*text);
  j["targets"][0]["format"] = "rgba16f";
  Layout l;
  std::string error;
  ASSERT_TRUE(parseLayout(j, "half.json", l, error)) << error;
  FrameSnapshot f;
  EXPECT_FALSE(importExr(kOrtho + "/cycles.exr", l, f, error));
  EXPECT_NE(error.find("\"ViewLayer.Combined.R\" is float; rgba16f holds only half exactly (a full-float file: give the "
                       "target's format as [\"rgba16f\", \"rgba32f\"] to accept both)"),
            std::string::npos)
      << error;
  // The shipped layout takes the half fixture's colour passes as half.
  ASSERT_TRUE(importExr(kBlender + "/cycles.exr", shippedLayout(), f, error)) << error;
  EXPECT_EQ(f.layout.targets[size_t(f.layout.findTarget("combined"))].format.name, "rgba16f");
}

// A sidecar is looked for beside the images only: a camera.json beside the layout is not taken,
// and the error names every place looked.
TEST(BlenderOrtho, TheSidecarIsLookedForBesideTheImagesOnly) {
  const std::string dir = freshDir("blender_sidecar");
  fs::create_directories(dir + "/images");
  fs::create_directories(dir + "/layouts");
  fs::copy_file(kOrtho + "/cycles.exr", dir + "/images/cycles.exr");
  fs::copy_file(kOrtho + "/camera.json", dir + "/layouts/camera.json");  // stale, beside the layout
  std::ofstream(dir + "/layouts/blender.json") << *assetText("layouts/blender-cycles.json");
  Layout l;
  std::string error, layoutDir;
  ASSERT_TRUE(loadImportLayout(dir + "/layouts/blender.json", {}, l, layoutDir, error)) << error;
  ImportInput in;
  in.layout = l;
  in.layoutDir = layoutDir;
  in.files = {dir + "/images/cycles.exr"};
  FrameSnapshot f;
  EXPECT_FALSE(importFrame(in, f, error));
  EXPECT_NE(error.find("camera: sidecar \"camera.json\": not found beside the imported files (looked for " + dir +
                       "/images/camera.json); give it with --camera FILE"),
            std::string::npos)
      << error;
  // A bare layout name that is a built-in one says so.
  EXPECT_FALSE(loadImportLayout("blender-cycles", {}, l, layoutDir, error));
  EXPECT_EQ(error, "blender-cycles: no such layout file; the layout gblens carries is --layout builtin:blender-cycles");
}

// --suggest-layout on Blender's EXRs: targets from the layer names, formats from the channel types,
// the camera from the sidecar (checked against the Position pass); the draft imported decodes every
// pixel's position, normal and ids exactly as the shipped layout does.
void expectDraftDecodesAsShipped(const std::string& dir) {
  SCOPED_TRACE(dir);
  SuggestRequest r;
  r.inputs = {dir + "/cycles.exr"};
  Suggestion draft;
  std::string error;
  ASSERT_TRUE(suggestLayout(r, draft, error)) << error;
  Layout l;
  ASSERT_TRUE(parseLayout(draft.layout, "draft", l, error)) << error << "\n" << draft.layout.dump(1);
  const std::map<std::string, QuantityKind> kinds = {
      {"combined", QuantityKind::Radiance}, {"depth", QuantityKind::Depth},  {"normal", QuantityKind::Normal},
      {"position", QuantityKind::Position}, {"index_ob", QuantityKind::Id},  {"index_ma", QuantityKind::Id},
      {"diff_col", QuantityKind::Albedo},   {"emit", QuantityKind::Emission}};
  for (const auto& [target, kind] : kinds) {
    const int t = l.findTarget(target);
    ASSERT_GE(t, 0) << target << " in " << draft.layout.dump(1);
    ASSERT_FALSE(l.quantitiesOf(uint32_t(t)).empty()) << target;
    EXPECT_EQ(l.quantitiesOf(uint32_t(t))[0]->kind, kind) << target;
  }
  ASSERT_NE(l.find(QuantityKind::Position), nullptr);
  EXPECT_EQ(l.find(QuantityKind::Position)->space, Space::World);
  EXPECT_EQ(l.find(QuantityKind::Normal)->space, Space::World);
  FrameSnapshot a, b;
  ASSERT_TRUE(importExr(dir + "/cycles.exr", l, a, error)) << error;
  ASSERT_TRUE(importExr(dir + "/cycles.exr", shippedLayout(), b, error)) << error;
  const Quantity *da = surfaceDepth(a.layout), *db = surfaceDepth(b.layout);
  const Quantity* objectId = a.layout.quantitiesOf(uint32_t(l.findTarget("index_ob")))[0];
  size_t compared = 0;
  for (uint32_t y = 0; y < a.camera.height; ++y)
    for (uint32_t x = 0; x < a.camera.width; ++x) {
      ASSERT_EQ(hasSurface(a, x, y), hasSurface(b, x, y)) << x << "," << y;
      EXPECT_EQ(decodeInteger(a, *objectId, x, y), decodeInteger(b, orthoQuantity(b, "IndexOB"), x, y));
      if (!hasSurface(a, x, y)) continue;
      EXPECT_EQ(*decodePosition(a, *da, x, y), *decodePosition(b, *db, x, y)) << x << "," << y;
      EXPECT_EQ(*decodePosition(a, *a.layout.find(QuantityKind::Position), x, y), *decodePosition(b, orthoQuantity(b, "Position"), x, y));
      EXPECT_EQ(decodeNormal(a, *a.layout.find(QuantityKind::Normal), x, y).unit, decodeNormal(b, orthoQuantity(b, "Normal"), x, y).unit);
      ++compared;
    }
  EXPECT_GT(compared, a.camera.width * a.camera.height / 3);
}

TEST(BlenderOrtho, SuggestLayoutDraftsBothBlenderFixtures) {
  expectDraftDecodesAsShipped(kBlender);
  expectDraftDecodesAsShipped(kOrtho);
}

}  // namespace
}  // namespace gb
