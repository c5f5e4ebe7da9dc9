// `gblens check` on frames of a renderer nobody here wrote (tests/subjects/gbuffer_zoo, its own dump of
// the frame, raw texels as the GPU stored them, and the matrices it used): a layout written here from
// the subject's README and truth file passes clean; each planted mistake — the camera read from the
// wrong offset, normals declared in the wrong space, two normal channels swapped, a NaN, a normal
// component negated — is flagged and named.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>

#include "tests/cli/zoo_truth.h"
#include "tests/support/capture_util.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const std::string kDump = GBLENS_BUILD_DIR + "/zoo/world_tbn_dump";

// world_tbn as its truth file says: world positions and not-renormalised world normals in rgba16f,
// linear albedo, D16 depth; the camera as the matrices the app used (its clip space is D3D's: y up,
// drawn through a negative viewport), Z up.
json layout(const json& dump) {
  json targets = json::array();
  auto raw = [](const char* file) { return json{{"file", file}, {"raw", true}}; };
  targets.push_back({{"name", "position"}, {"format", "rgba16f"}, {"source", raw("pass0_att0_position.bin")},
                     {"quantities", {{{"quantity", "position"}, {"name", "P"}, {"channels", {0, 1, 2}}, {"space", "world"}}}}});
  targets.push_back({{"name", "normal"}, {"format", "rgba16f"}, {"source", raw("pass0_att1_normal.bin")},
                     {"quantities", {{{"quantity", "normal"}, {"name", "N"}, {"channels", {0, 1, 2}}, {"encoding", "xyz"},
                                      {"space", "world"}, {"normalized", false}}}}});
  targets.push_back({{"name", "depth"}, {"format", "d16"}, {"source", raw("pass0_att3_depth.bin")},
                     {"quantities", {{{"quantity", "depth"}, {"name", "Depth"}, {"channels", {0}}, {"encoding", "hardware"},
                                      {"background", 1}}}}});
  return {{"format", "gblens-layout"}, {"version", 1}, {"size", {dump["width"], dump["height"]}}, {"targets", targets},
          {"camera", {{"view_from_world", dump["view_from_world"]}, {"clip_from_view", dump["clip_from_view"]},
                      {"matrix_order", "column_major"}, {"convention", "d3d"}, {"up", "z"}}}};
}

struct CheckRun {
  int exit = -1;
  std::string output;
};

// Imports the dump's files with `l` into DIR/NAME and checks it.
CheckRun importAndCheck(const std::string& dir, const std::string& name, const json& l) {
  std::ofstream(dir + "/" + name + ".json") << l.dump(1);
  RunResult imported = runGblens("import --layout '" + dir + "/" + name + ".json' -o '" + dir + "/" + name + "'");
  if (imported.exitCode != 0) return {-2, imported.output};
  RunResult check = runGblens("check '" + dir + "/" + name + "'");
  return {check.exitCode, check.output};
}

// The dump's files copied beside the layouts (sources are read beside the layout).
std::string copyDump(const std::string& name) {
  const std::string dir = freshDir(name);
  for (const auto& e : fs::directory_iterator(kDump)) fs::copy_file(e.path(), dir + "/" + e.path().filename().string());
  return dir;
}

// Rewrites every texel's half-float channel `c` of an rgba16f dump (`f`: the new bits from the old).
void rewriteHalves(const std::string& path, int c, const std::function<uint16_t(uint16_t, size_t)>& f) {
  std::string bytes = readText(path);
  for (size_t i = 0; i * 8 + 8 <= bytes.size(); ++i) {
    uint16_t h;
    std::memcpy(&h, bytes.data() + i * 8 + size_t(c) * 2, 2);
    h = f(h, i);
    std::memcpy(bytes.data() + i * 8 + size_t(c) * 2, &h, 2);
  }
  std::ofstream(path, std::ios::binary | std::ios::trunc) << bytes;
}

TEST(ZooCheck, TheCorrectFrameIsCleanAndEachPlantedMistakeIsNamed) {
  const json dump = zoo::readJson(kDump + "/dump.json");
  ASSERT_TRUE(dump.is_object()) << "the zoo_captures fixture did not run";
  const std::string dir = copyDump("zoo_check");
  const json good = layout(dump);
  const CheckRun clean = importAndCheck(dir, "good", good);
  EXPECT_EQ(clean.exit, 0) << clean.output;

  // The camera read from the wrong offset: world_from_view (byte 128 of its buffer) as the view.
  json wrongCamera = good;
  const std::string camera = readText(kDump + "/camera.bin");
  json worldFromView = json::array();
  for (int i = 0; i < 16; ++i) {
    float v;
    std::memcpy(&v, camera.data() + 128 + 4 * i, 4);
    worldFromView.push_back(v);
  }
  wrongCamera["camera"]["view_from_world"] = worldFromView;
  const CheckRun camRun = importAndCheck(dir, "camera", wrongCamera);
  EXPECT_EQ(camRun.exit, 1) << camRun.output;
  EXPECT_NE(camRun.output.find("the camera looks wrong"), std::string::npos) << camRun.output;

  json viewSpace = good;  // world-space normals declared as view space
  viewSpace["targets"][1]["quantities"][0]["space"] = "view";
  const CheckRun spaceRun = importAndCheck(dir, "space", viewSpace);
  EXPECT_EQ(spaceRun.exit, 1) << spaceRun.output;
  EXPECT_NE(spaceRun.output.find("fits far better with stored in world space"), std::string::npos) << spaceRun.output;

  json swapped = good;  // x and y read from each other's channels
  swapped["targets"][1]["quantities"][0]["channels"] = {1, 0, 2};
  const CheckRun swapRun = importAndCheck(dir, "swap", swapped);
  EXPECT_EQ(swapRun.exit, 1) << swapRun.output;
  EXPECT_NE(swapRun.output.find("fits far better with x and y swapped"), std::string::npos) << swapRun.output;

  const std::string nanDir = copyDump("zoo_check_nan");  // one position texel NaN (half 0x7e00), on the floor
  rewriteHalves(nanDir + "/pass0_att0_position.bin", 0, [](uint16_t h, size_t i) { return i == 90 * 192 + 96 ? uint16_t(0x7e00) : h; });
  const CheckRun nanRun = importAndCheck(nanDir, "nan", good);
  EXPECT_EQ(nanRun.exit, 1) << nanRun.output;
  EXPECT_NE(nanRun.output.find("fault nan"), std::string::npos) << nanRun.output;

  const std::string flipDir = copyDump("zoo_check_flip");  // every normal's y negated (the half's sign bit)
  rewriteHalves(flipDir + "/pass0_att1_normal.bin", 1, [](uint16_t h, size_t) { return uint16_t(h ^ 0x8000); });
  const CheckRun flipRun = importAndCheck(flipDir, "flip", good);
  EXPECT_EQ(flipRun.exit, 1) << flipRun.output;
  EXPECT_NE(flipRun.output.find("fits far better with its y negated"), std::string::npos) << flipRun.output;
}

}  // namespace
}  // namespace gb
