// Blender's Cycles passes through the shipped layout assets/layouts/blender-cycles.json: the fixture in
// tests/data/blender (rendered by assets/blender/render_gbuffer.py, `make fixtures`; Blender is not
// needed here) is imported, and what gblens decodes is checked against what Cycles wrote beside it:
// positions from Depth and the camera against the Position pass, unit normals, the indices the script
// assigned. Everything is compared in gblens's eye space after the layout's conversions (Z up, GL).
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>

#include "renderer/core/assert.h"
#include "renderer/core/assets.h"
#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "tests/support/capture_util.h"
#include "views/capture/capture.h"
#include "views/import/import.h"

namespace gb {

namespace {

const std::string kDir = std::string(GBLENS_SOURCE_DIR) + "/tests/data/blender";

// What render_gbuffer.py builds (keep in step with its OBJECTS and MATERIALS): a point of each
// object's surface or interior, Blender world coordinates (Z up), its object and material index.
struct Known {
  const char* name;
  glm::dvec3 point;
  uint32_t object, material;
};
const Known kObjects[] = {{"Floor", {0.0, -3.0, 0.0}, 1, 1},  {"Cube", {-1.2, 0.4, 0.5}, 2, 2},
                          {"Sphere", {1.1, -0.2, 0.7}, 3, 3}, {"Cone", {2.4, 1.2, 0.6}, 4, 2},
                          {"Lamp", {-0.3, -1.6, 0.25}, 5, 4}};

// The shipped layout as the binary carries it.
Layout blenderLayout() {
  const std::string* text = assetText("layouts/blender-cycles.json");
  EXPECT_NE(text, nullptr) << "cmake/Assets.cmake does not embed layouts/blender-cycles.json";
  Layout l;
  std::string error;
  EXPECT_TRUE(text && parseLayout(nlohmann::json::parse(*text), "blender-cycles.json", l, error)) << error;
  return l;
}

// The fixture as `gblens import cycles.exr --layout blender-cycles.json [--camera CAMERA]` reads it
// (without --camera: the layout's sidecar "camera.json", found beside the EXR).
bool importFixture(FrameSnapshot& f, std::string& error, const std::string& camera = "") {
  ImportInput in;
  in.layout = blenderLayout();
  in.files = {kDir + "/cycles.exr"};
  in.cameraFile = camera;
  return importFrame(in, f, error);
}

const Quantity& quantity(const FrameSnapshot& f, const char* name) {
  const Quantity* q = f.layout.findByName(name);
  GB_ASSERT(q);
  return *q;
}

class BlenderImport : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    frame_ = new FrameSnapshot;
    std::string error;
    ASSERT_TRUE(importFixture(*frame_, error)) << error;
  }
  static void TearDownTestSuite() { delete frame_; }
  void SetUp() override { ASSERT_FALSE(frame_->images.empty()) << "the fixture did not import"; }
  static const FrameSnapshot& frame() { return *frame_; }
  static FrameSnapshot* frame_;
};
FrameSnapshot* BlenderImport::frame_ = nullptr;

// Blender world (Z up) -> eye space through the imported camera.
glm::dvec3 eyeOf(const FrameSnapshot& f, const glm::dvec3& blender) {
  return glm::dvec3(f.camera.eyeFromWorld * glm::dvec4(blender.x, blender.z, -blender.y, 1.0));
}

// The scene scale S = |eye| + max |P| (world units): what float32 rounding is relative to.
double sceneScale(const FrameSnapshot& f) {
  const Quantity& position = quantity(f, "Position");
  double scale = 0.0;
  for (uint32_t y = 0; y < f.camera.height; ++y)
    for (uint32_t x = 0; x < f.camera.width; ++x) {
      std::array<double, 4> p = storedValues(f, position, x, y);
      scale = std::max(scale, glm::length(glm::dvec3(p[0], p[1], p[2])));
    }
  return scale + glm::length(glm::dvec3(f.camera.worldFromEye[3]));
}

// Float32 rounding between Cycles' numbers and gblens's: Cycles' hit point and its world-to-camera
// transform, the stored Position and Depth, the sidecar's float32 matrices each err by at most 2^-24
// of S per operation; 16 of them.
double floatBound(const FrameSnapshot& f) { return 16.0 * std::ldexp(1.0, -24) * sceneScale(f); }


TEST_F(BlenderImport, ReadsEveryPassAtTheRenderedSize) {
  const FrameSnapshot& f = frame();
  EXPECT_EQ(f.camera.width, 160u);
  EXPECT_EQ(f.camera.height, 90u);
  ASSERT_EQ(f.images.size(), f.layout.targets.size());
  for (size_t t = 0; t < f.images.size(); ++t) {
    ASSERT_NE(layoutImage(f, uint32_t(t)), nullptr) << f.layout.targets[t].name;
    EXPECT_EQ(f.images[t].image.width, 160u) << f.layout.targets[t].name;
  }
  // Cycles' near and far clip (0.1, 100) come back from the projection.
  EXPECT_NEAR(f.camera.znear, 0.1, 1e-6);
  EXPECT_NEAR(f.camera.zfar, 100.0, 1e-3);
}

// Depth.Z is planar eye depth (the distance along the view axis), not the distance to the eye: the
// Position pass, taken into eye space, has -z equal to Depth to float32 precision, while its
// distance from the eye differs by up to the 1/cos of the field of view (~16 % in the corners).
// Bound: floatBound (S = 13.1 m here: 1.25e-5 m).
TEST_F(BlenderImport, DepthIsPlanarEyeDepth) {
  const FrameSnapshot& f = frame();
  const Quantity &depth = quantity(f, "Depth"), &position = quantity(f, "Position");
  const double scale = sceneScale(f), bound = floatBound(f);
  double maxAxial = 0.0, maxRadialRelative = 0.0;
  int surfaces = 0;
  for (uint32_t y = 0; y < 90; ++y)
    for (uint32_t x = 0; x < 160; ++x) {
      std::optional<double> d = decodeEyeDepth(f, depth, x, y);
      if (!d) continue;
      ++surfaces;
      const glm::dvec3 stored = *decodePosition(f, position, x, y);
      maxAxial = std::max(maxAxial, std::abs(-stored.z - *d));
      maxRadialRelative = std::max(maxRadialRelative, std::abs(glm::length(stored) - *d) / *d);
    }
  std::printf("blender: %d surface pixels; Depth vs Position's -z: max %.3g m (bound %.3g m, S = %.2f m); "
              "Depth vs |Position - eye|: max %.3g relative\n", surfaces, maxAxial, bound, scale, maxRadialRelative);
  EXPECT_GT(surfaces, 160 * 90 / 2);
  EXPECT_LE(maxAxial, bound);
  EXPECT_GT(maxRadialRelative, 0.05) << "radial and planar depth would be indistinguishable here";
}

// Positions reconstructed from Depth through the pixel centre (the decoder, with the imported camera)
// against the Position pass. Besides floatBound, Cycles traced each pixel's ray through
// a point within half the pixel filter's width (0.005 px) of the centre, which moves the point
// sideways by up to 0.005 px at its depth. The same comparison in pixels: the Position pass
// projected with the imported camera lands within 0.005 px of the pixel's centre.
TEST_F(BlenderImport, PositionsFromDepthMatchThePositionPass) {
  const FrameSnapshot& f = frame();
  const Quantity &depth = quantity(f, "Depth"), &position = quantity(f, "Position");
  const glm::dmat4& p = f.camera.clipFromEye;
  const double perDepth = 0.005 * std::hypot(2.0 / (160.0 * p[0][0]), 2.0 / (90.0 * p[1][1]));
  const double floatTerm = floatBound(f);
  double maxError = 0.0, worstRatio = 0.0, maxPixels = 0.0;
  for (uint32_t y = 0; y < 90; ++y)
    for (uint32_t x = 0; x < 160; ++x) {
      std::optional<glm::dvec3> fromDepth = decodePosition(f, depth, x, y);
      if (!fromDepth) continue;
      const glm::dvec3 stored = *decodePosition(f, position, x, y);
      const double error = glm::length(*fromDepth - stored), bound = floatTerm + perDepth * -fromDepth->z;
      maxError = std::max(maxError, error);
      worstRatio = std::max(worstRatio, error / bound);
      EXPECT_LE(error, bound) << "pixel " << x << "," << y;
      const glm::dvec4 clip = p * glm::dvec4(stored, 1.0);  // Vulkan clip space: y down, rows top first
      const glm::dvec2 pixel((clip.x / clip.w + 1.0) * 0.5 * 160.0, (clip.y / clip.w + 1.0) * 0.5 * 90.0);
      maxPixels = std::max(maxPixels, glm::length(pixel - glm::dvec2(x + 0.5, y + 0.5)));
    }
  std::printf("blender: positions from Depth vs the Position pass: max %.3g m (worst error/bound %.2f); "
              "Position projected: max %.3g px from the pixel centre\n", maxError, worstRatio, maxPixels);
  EXPECT_LE(maxPixels, 0.005 * std::sqrt(2.0) + 1e-3);  // 1e-3 px: the float32 term at 3 m, the nearest
}

// The Normal pass (world space, Z up) decodes to unit vectors: Cycles normalises in float32 and one
// sample per pixel is stored, so |n| is 1 within three float32 roundings of the components (1e-6 with
// margin). The floor's normal is world +Z, i.e. gblens's +Y in eye space; every normal faces the eye.
TEST_F(BlenderImport, NormalsAreUnitWorldSpaceAndFaceTheCamera) {
  const FrameSnapshot& f = frame();
  const Quantity &normal = quantity(f, "Normal"), &object = quantity(f, "IndexOB"), &position = quantity(f, "Position");
  const glm::dvec3 up = glm::dmat3(f.camera.eyeFromWorld) * glm::dvec3(0.0, 1.0, 0.0);
  double maxLength = 0.0, maxFloor = 0.0;
  int floorPixels = 0;
  for (uint32_t y = 0; y < 90; ++y)
    for (uint32_t x = 0; x < 160; ++x) {
      if (!hasSurface(f, x, y)) continue;
      const NormalSample n = decodeNormal(f, normal, x, y);
      maxLength = std::max(maxLength, std::abs(glm::length(n.stored) - 1.0));
      EXPECT_LT(glm::dot(n.unit, *decodePosition(f, position, x, y)), 0.0) << "pixel " << x << "," << y;
      if (decodeInteger(f, object, x, y) == 1) {
        maxFloor = std::max(maxFloor, glm::length(n.unit - up));
        ++floorPixels;
      }
    }
  std::printf("blender: normal length error max %.3g; floor normal vs world up max %.3g (%d pixels)\n", maxLength,
              maxFloor, floorPixels);
  EXPECT_LE(maxLength, 1e-6);
  EXPECT_GT(floorPixels, 1000);
  EXPECT_LE(maxFloor, 1e-6);
}

// Object and material indices are exact: at each object's known point, projected with the imported
// camera, the indices the script assigned; everywhere, the material index is the one the object's
// material has, and pixels without a surface hold 0.
TEST_F(BlenderImport, IndicesAreTheOnesTheScriptAssigned) {
  const FrameSnapshot& f = frame();
  const Quantity &object = quantity(f, "IndexOB"), &material = quantity(f, "IndexMA");
  for (const Known& k : kObjects) {
    const glm::dvec4 clip = f.camera.clipFromEye * glm::dvec4(eyeOf(f, k.point), 1.0);
    const uint32_t x = uint32_t((clip.x / clip.w + 1.0) * 0.5 * 160.0), y = uint32_t((clip.y / clip.w + 1.0) * 0.5 * 90.0);
    ASSERT_TRUE(x < 160 && y < 90) << k.name;
    EXPECT_EQ(decodeInteger(f, object, x, y), k.object) << k.name << " at " << x << "," << y;
    EXPECT_EQ(decodeInteger(f, material, x, y), k.material) << k.name << " at " << x << "," << y;
  }
  std::map<uint32_t, int> count;
  for (uint32_t y = 0; y < 90; ++y)
    for (uint32_t x = 0; x < 160; ++x) {
      const double stored = storedValues(f, object, x, y)[0];
      EXPECT_EQ(stored, std::round(stored)) << "pixel " << x << "," << y;
      const uint32_t id = decodeInteger(f, object, x, y);
      ++count[id];
      EXPECT_EQ(id != 0, hasSurface(f, x, y)) << "pixel " << x << "," << y;
      uint32_t expected = 0;
      for (const Known& k : kObjects)
        if (k.object == id) expected = k.material;
      EXPECT_EQ(decodeInteger(f, material, x, y), expected) << "pixel " << x << "," << y;
    }
  for (const Known& k : kObjects) EXPECT_GT(count[k.object], 20) << k.name;
  EXPECT_EQ(count.size(), 6u);  // the background and five objects
}

// The import is an ordinary capture: written and read back, every pixel decodes to the same
// position (from Depth and from the Position pass), normal and indices, bit for bit.
TEST_F(BlenderImport, SurvivesACaptureRoundTrip) {
  const FrameSnapshot& f = frame();
  const std::string dir = freshDir("blender_capture") + "/capture";
  std::string error;
  ASSERT_TRUE(writeCapture(dir, f, CaptureMeta{}, error)) << error;
  Capture c;
  ASSERT_TRUE(loadCapture(dir, c, error)) << error;
  const FrameSnapshot& g = c.frame;
  ASSERT_EQ(layoutJson(g.layout), layoutJson(f.layout));
  int compared = 0;
  for (uint32_t y = 0; y < 90; ++y)
    for (uint32_t x = 0; x < 160; ++x) {
      ASSERT_EQ(hasSurface(g, x, y), hasSurface(f, x, y)) << x << "," << y;
      for (const char* id : {"IndexOB", "IndexMA"})
        EXPECT_EQ(decodeInteger(g, quantity(g, id), x, y), decodeInteger(f, quantity(f, id), x, y)) << id;
      if (!hasSurface(f, x, y)) continue;
      for (const char* q : {"Depth", "Position"})
        EXPECT_EQ(*decodePosition(g, quantity(g, q), x, y), *decodePosition(f, quantity(f, q), x, y)) << q << " " << x << "," << y;
      EXPECT_EQ(decodeNormal(g, quantity(g, "Normal"), x, y).unit, decodeNormal(f, quantity(f, "Normal"), x, y).unit);
      ++compared;
    }
  EXPECT_GT(compared, 8000);
}

// The sidecar's size guards the projection's aspect ratio: matrices made for another size are refused,
// naming the sidecar and the field.
TEST(BlenderImportErrors, ACameraForAnotherSizeIsRefused) {
  nlohmann::json side = nlohmann::json::parse(std::ifstream(kDir + "/camera.json"));
  side["size"] = {320, 180};
  const std::string path = freshDir("blender_camera") + "/camera_320.json";
  std::ofstream(path) << side.dump();
  FrameSnapshot f;
  std::string error;
  EXPECT_FALSE(importFixture(f, error, path));
  EXPECT_NE(error.find(path + ": camera: size: the matrices are for 320x180, the images are 160x90"), std::string::npos)
      << error;
}

// The layouts docs/import.md shows are valid layouts (the page cannot drift from the format).
TEST(ImportDocs, EveryLayoutInImportMdParses) {
  std::ifstream in(std::string(GBLENS_SOURCE_DIR) + "/docs/import.md");
  ASSERT_TRUE(in);
  std::string text((std::istreambuf_iterator<char>(in)), {}), block;
  int layouts = 0;
  for (size_t at = 0; (at = text.find("```json\n", at)) != std::string::npos; at += block.size()) {
    at += 8;
    block = text.substr(at, text.find("```", at) - at);
    if (block.find("gblens-layout") == std::string::npos) continue;
    Layout l;
    std::string error;
    EXPECT_TRUE(parseLayout(nlohmann::json::parse(block), "import.md", l, error)) << error << "\n" << block;
    ++layouts;
  }
  EXPECT_GE(layouts, 2);
}

}  // namespace

}  // namespace gb
