// A property of import (issue 29): every import that succeeds writes a capture that probe, check,
// stats and compare accept. Layouts are mutated at random (seeded: the same 300 every run) from a
// valid one with a camera, lights and three targets: a value replaced by one of a pool of hostile
// values (overflowing and negative integers, 1e308, denormals, paths, long strings, null, arrays,
// objects), a member deleted, an element duplicated, a value wrapped. Each is imported as `gblens
// import` does (in-process, to run hundreds in a few seconds; a few also through the binary) and,
// when it succeeds, read back by the same functions the four commands call. A refusal must be one
// line; an accepted import must read back.
#include <gtest/gtest.h>

#include <filesystem>
#include <random>

#include "renderer/core/layout_json.h"
#include "tests/cli/import_fixtures.h"
#include "tests/support/capture_util.h"
#include "views/analysis/check.h"
#include "views/analysis/compare.h"
#include "views/analysis/probe.h"
#include "views/analysis/region_stats.h"
#include "views/capture/capture.h"
#include "views/import/import.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

json baseLayout(const std::string& dir) {
  json l = fixtures::writeFixtureC(dir, false);
  l["size"] = {16, 8};
  l["camera"] = {{"view_from_world", {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1}},
                 {"clip_from_view", {1.2, 0, 0, 0, 0, 2.4, 0, 0, 0, 0, -1.004, -1, 0, 0, -0.2004, 0}},
                 {"convention", "gl"}};
  l["lights"] = {{"model", "gblens"},
                 {"points", {{{"position", {0, 1, -2}}, {"radius", 3}, {"color", {1, 1, 1}}, {"intensity", 2}}}},
                 {"sun", {{"direction", {0.3, 1, 0.2}}, {"color", {1, 1, 1}}}},
                 {"ambient", {0.1, 0.1, 0.1}}};
  return l;
}

// Every path to a value in the document (object keys and array indices).
void paths(const json& v, std::vector<json::json_pointer>& out, const json::json_pointer& at = {}) {
  if (!at.empty()) out.push_back(at);
  if (v.is_object())
    for (auto& [k, e] : v.items()) paths(e, out, at / k);
  else if (v.is_array())
    for (size_t i = 0; i < v.size(); ++i) paths(v[i], out, at / i);
}

json mutated(const json& base, std::mt19937& rng) {
  static const json pool = json::parse(R"([0, -1, 1, 2, 3, 4, 255, 256, 65536, 65537, 4294967296, 18446744073709551615,
      -9223372036854775808, 1e308, -1e308, 1e-320, 0.5, -0.0, "", "x", "x/../../escaped", "/", ".", "/dev/zero",
      null, true, false, [], {}, [1, 2, 3], [0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0], {"offset": 1}])");
  json doc = base;
  const int edits = rng() % 4 ? 1 : 2;
  for (int e = 0; e < edits; ++e) {
    std::vector<json::json_pointer> all;
    paths(doc, all);
    const json::json_pointer p = all[rng() % all.size()];
    json& parent = doc[p.parent_pointer()];
    const unsigned op = rng() % 10;
    if (op < 6) {
      doc[p] = pool[rng() % pool.size()];
    } else if (op < 8) {
      if (parent.is_object()) parent.erase(p.back());
      else parent.erase(size_t(std::stoul(p.back())));
    } else if (op < 9 && parent.is_array()) {
      parent.push_back(doc[p]);
    } else {
      doc[p] = json::array({doc[p]});
    }
  }
  return doc;
}

// `gblens import --layout FILE -o OUT` as cmd_import.cpp runs it.
bool importLikeTheCommand(const std::string& layoutFile, const std::string& out, std::string& error) {
  RenderOptions options;
  ImportInput in;
  if (!loadImportLayout(layoutFile, layoutParameters(options), in.layout, in.layoutDir, error)) return false;
  FrameSnapshot frame;
  if (!importFrame(in, frame, error)) return false;
  const RenderOptions imported = frame.options;
  frame.options = options;
  frame.options.width = imported.width, frame.options.height = imported.height;
  frame.options.reversedZ = imported.reversedZ;
  CaptureMeta meta;
  meta.scene = "import: property test";
  return writeCapture(out, frame, meta, error);
}

TEST(ImportProperty, EveryImportThatSucceedsReadsBackInEveryReader) {
  const std::string dir = freshDir("import-property");
  const json base = baseLayout(dir);
  fixtures::writeJson(dir + "/base.json", base);
  std::string error;
  ASSERT_TRUE(importLikeTheCommand(dir + "/base.json", dir + "/base", error)) << error;
  Capture reference;
  ASSERT_TRUE(loadCapture(dir + "/base", reference, error)) << error;

  std::mt19937 rng(29);
  size_t accepted = 0, refused = 0;
  for (int i = 0; i < 300; ++i) {
    const json layout = mutated(base, rng);
    SCOPED_TRACE("mutation " + std::to_string(i) + ": " + layout.dump().substr(0, 400));
    const std::string file = dir + "/case.json", out = dir + "/out";
    fixtures::writeJson(file, layout);
    fs::remove_all(out);
    error.clear();
    if (!importLikeTheCommand(file, out, error)) {
      ++refused;
      EXPECT_FALSE(error.empty());
      EXPECT_EQ(error.find('\n'), std::string::npos) << error;
      EXPECT_FALSE(fs::exists(out));
      continue;
    }
    ++accepted;
    Capture c;
    ASSERT_TRUE(loadCapture(out, c, error)) << "import wrote what the readers refuse: " << error;
    EXPECT_EQ(probePixel(c.frame, 3, 3).error, "");                  // gblens probe
    checkFrame(c.frame);                                              // gblens check
    RegionRect rect;                                                  // gblens stats
    ASSERT_TRUE(parseRegionRect("0,0,4,4", c.frame.camera.width, c.frame.camera.height, rect, error)) << error;
    regionStats(c.frame, rect);
    CompareReport report;                                             // gblens compare
    EXPECT_TRUE(compareCaptures(reference, c, ThresholdSettings{}, report, error)) << error;
  }
  // Both outcomes are exercised (the pool is hostile; about a third still import).
  EXPECT_GE(accepted, 30u);
  EXPECT_GE(refused, 100u);
  std::printf("[ property ] 300 mutated layouts: %zu imported and read back, %zu refused in one line\n", accepted, refused);

  // A few through the binary, exit status and all (the same functions behind `gblens import/probe`).
  std::mt19937 again(29);
  for (int i = 0; i < 6; ++i) {
    fixtures::writeJson(dir + "/bin.json", mutated(base, again));
    fs::remove_all(dir + "/bin");
    RunResult r = runGblens("import --layout '" + dir + "/bin.json' -o '" + dir + "/bin'");
    if (r.exitCode != 0) {
      EXPECT_EQ(r.exitCode, 2) << r.output;
      EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
      continue;
    }
    EXPECT_EQ(runGblens("probe '" + dir + "/bin' 3 3").exitCode, 0);
    EXPECT_NE(runGblens("check '" + dir + "/bin'").exitCode, 2);
    EXPECT_EQ(runGblens("stats '" + dir + "/bin' --rect 0,0,4,4").exitCode, 0);
    EXPECT_NE(runGblens("compare '" + dir + "/base' '" + dir + "/bin'").exitCode, 4);
  }
}

}  // namespace
}  // namespace gb
