// A manifest that contradicts its images or itself is refused by the one validation every reader
// shares (views/capture/manifest_sanity.cpp), naming the field (issue 36, item 2): a 64x48 capture
// whose manifest says 65536x65536 (or 46341, whose square passes 2^31), a camera matrix entry edited
// to 1e5, a light at -1e308, a shadow map of another size than options.shadow_map_size. And a file
// name in messages is quoted once (item 7).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <functional>

#include "renderer/core/sha256.h"
#include "tests/support/capture_util.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

// A 64x48 synthetic capture with one light, written as gblens writes captures.
std::string writeOriginal(const std::string& dir) {
  FrameSnapshot f = syntheticFrame(64, 48);
  gpu::PointLight light{};
  light.eyePositionRadius = glm::vec4(0.5f, 1.0f, -3.0f, 2.0f);
  light.color = glm::vec4(1.0f, 0.5f, 0.25f, 0.0f);
  f.eyeLights = {light};
  f.visibleLights = {0};
  f.stencilCount = 1;
  std::string error;
  EXPECT_TRUE(writeCapture(dir, f, CaptureMeta{}, error)) << error;
  return dir;
}

json readJson(const std::string& path) { return json::parse(readText(path)); }
void writeJson(const std::string& path, const json& j) { std::ofstream(path) << j.dump(1); }

// A copy of `original` with its manifest (or lights.json, which is checksummed) edited by `edit`.
std::string edited(const std::string& original, const std::string& dir, const std::function<void(json&, json&)>& edit) {
  fs::remove_all(dir);
  fs::copy(original, dir);
  json m = readJson(dir + "/manifest.json"), lights = readJson(dir + "/lights.json");
  const std::string lightsBefore = lights.dump();
  edit(m, lights);
  if (lights.dump() != lightsBefore) {  // re-listed with its new size and digest, as a careful forger would
    const std::string text = lights.dump(1) + "\n";
    std::ofstream(dir + "/lights.json", std::ios::binary) << text;
    m["files"]["lights.json"] = {{"bytes", text.size()}, {"sha256", sha256Hex(text)}};
    m["lights"]["sha256"] = sha256Hex(text);
  }
  writeJson(dir + "/manifest.json", m);
  return dir;
}

std::string refusal(const std::string& dir) {
  Capture c;
  std::string error;
  return loadCapture(dir, c, error) ? std::string() : error;
}

TEST(ManifestSanity, ManifestsThatContradictTheirImagesAreRefused) {
  const std::string root = freshDir("manifest_sanity");
  const std::string original = writeOriginal(root + "/original");
  ASSERT_EQ(refusal(original), "");  // the original reads

  struct Case {
    const char* name;
    std::function<void(json&, json&)> edit;
    std::vector<const char*> words;  // in the message, in order
  };
  const std::vector<Case> cases = {
      {"size 65536", [](json& m, json&) {
         m["size"] = {65536, 65536};
         m["camera"]["width"] = m["camera"]["height"] = 65536;
       }, {"camera", "65536x65536", "more than a capture holds"}},
      {"size field 46341", [](json& m, json&) { m["size"] = {46341, 46341}; }, {"size", "[46341,46341]", "not the camera's 64x48"}},
      {"camera 46341", [](json& m, json&) {
         m["camera"]["width"] = 46341;
         m["size"] = {46341, 48};
         m["options"].erase("size");
       },
       {"targets[0]", "64x48", "not the camera's 46341x48"}},
      {"clipFromEye entry 1e5", [](json& m, json&) { m["camera"]["clipFromEye"][0] = 1e5; },
       {"camera.eyeFromClip", "not the inverse of clipFromEye"}},
      {"eyeFromWorld entry 1e5", [](json& m, json&) { m["camera"]["eyeFromWorld"][12] = 1e5; },
       {"camera.worldFromEye", "not the inverse of eyeFromWorld"}},
      {"light at -1e308", [](json&, json& l) { l["lights"][0]["eye_position"][0] = -1e308; },
       {"lights.json", "lights[0].eye_position", "outside -3.4e38..3.4e38"}},
      {"negative radius", [](json&, json& l) { l["lights"][0]["radius"] = -2.0; }, {"lights[0].radius", "outside 0..3.4e38"}},
      {"sun colour 1e300", [](json& m, json&) { m["sun"]["color"][1] = 1e300; }, {"sun.color", "outside"}},
      {"znear beyond zfar", [](json& m, json&) { m["camera"]["znear"] = 500.0; }, {"camera.zfar", "not beyond znear"}},
      {"lights.count", [](json& m, json&) { m["lights"]["count"] = 7; }, {"lights.count", "lights.json holds 1 lights"}},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.name);
    const std::string message = refusal(edited(original, root + "/edited", c.edit));
    ASSERT_NE(message, "") << "accepted";
    EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    size_t at = 0;
    for (const char* w : c.words) {
      const size_t found = message.find(w, at);
      EXPECT_NE(found, std::string::npos) << "'" << w << "' missing in: " << message;
      if (found != std::string::npos) at = found;
    }
  }
  // The writer runs the same check: a frame whose shadow map is not options.shadow_map_size is not written.
  FrameSnapshot f = syntheticFrame(16, 8);
  TargetImage& sm = f.target(Target::ShadowMap);
  describeReadback(Target::ShadowMap, f.options, sm.image);
  sm.image.width = sm.targetWidth = sm.image.height = sm.targetHeight = 32;  // options say 2048
  sm.image.data.assign(32 * 32 * sm.image.texelBytes(), 0);
  f.setAbsence(Target::ShadowMap, Absent::No);
  std::string error;
  EXPECT_FALSE(writeCapture(root + "/shadow", f, CaptureMeta{}, error));
  EXPECT_NE(error.find("\"shadow_map\" is 32x32, not options.shadow_map_size's 2048x2048"), std::string::npos) << error;
  EXPECT_FALSE(fs::exists(root + "/shadow"));
  f.options.shadowMapSize = 32;
  EXPECT_TRUE(writeCapture(root + "/shadow", f, CaptureMeta{}, error)) << error;
}

// Names in messages are quoted once: `"../depth.exr": not a file`, never `""../depth.exr""`.
TEST(ManifestSanity, FileNamesAreQuotedOnce) {
  const std::string root = freshDir("manifest_quotes");
  const std::string original = writeOriginal(root + "/original");
  const std::string message = refusal(edited(original, root + "/edited", [](json& m, json&) {
    m["files"]["../depth.exr"] = m["files"]["depth.exr"];
  }));
  EXPECT_NE(message.find("files: \"../depth.exr\": not a file of the capture folder"), std::string::npos) << message;
  EXPECT_EQ(message.find("\"\""), std::string::npos) << message;
}

}  // namespace
}  // namespace gb
