// gblens stats (issue 17, region statistics) on an imported capture: fixture C (tests/cli/import_fixtures.h),
// a 16x8 G-buffer of constant values with a NaN, a +Inf and a -Inf planted at known pixels. A rect holding
// them counts each once, apart from the moments, which are those of the constant values; a rect that
// misses them counts none. A rect outside the frame, a malformed rect or an unknown target is one line
// naming the flag, exit 2.
#include <gtest/gtest.h>

#include "tests/cli/import_fixtures.h"
#include "tests/support/capture_util.h"

namespace gb {
namespace {

using json = nlohmann::json;

std::string importFixtureC(const std::string& dir) {
  fixtures::writeFixtureC(dir, true);
  RunResult r = runGblens("import --layout '" + dir + "/c.json' -o '" + dir + "/capture'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return dir + "/capture";
}

const json* series(const json& list, const std::string& target, const std::string& name) {
  for (const json& s : list)
    if (s["target"] == target && s["series"] == name) return &s;
  return nullptr;
}

TEST(Stats, JsonCountsPlantedNonFiniteValuesApartFromTheMoments) {
  const std::string capture = importFixtureC(freshDir("stats-json"));
  // 2,0 .. 9,4 holds the NaN in gbuf G at 3,1, the +Inf in normal Y at 5,2, the -Inf depth at 7,3 and the
  // denormal roughness at 9,4; not the 1.5 albedo at 2,5 or the short normal at 11,6.
  RunResult r = runGblens("stats '" + capture + "' --rect 2,0,8,5 --json");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json s = json::parse(r.output);
  EXPECT_EQ(s["pixels"].get<uint64_t>(), 40u);
  EXPECT_EQ(s["surface_pixels"].get<uint64_t>(), 39u);  // the -Inf depth holds no surface
  const json& ch = s["channels"];
  const json* g = series(ch, "gbuf", "Albedo.G");
  ASSERT_NE(g, nullptr) << r.output;
  EXPECT_EQ((*g)["nan"].get<uint64_t>(), 1u);
  EXPECT_EQ((*g)["count"].get<uint64_t>(), 39u);
  EXPECT_NEAR((*g)["mean"].get<double>(), 0.4, 1e-7);  // the stored float 0.4f, 39 times
  EXPECT_NEAR((*g)["stddev"].get<double>(), 0.0, 1e-12);
  const json* r0 = series(ch, "gbuf", "Albedo.R");
  ASSERT_NE(r0, nullptr);
  EXPECT_EQ((*r0)["max"].get<double>(), 0.5);  // the 1.5 at 2,5 lies outside the rect
  EXPECT_EQ((*r0)["nan"].get<uint64_t>() + (*r0)["+inf"].get<uint64_t>() + (*r0)["-inf"].get<uint64_t>(), 0u);
  const json* ny = series(ch, "normal", "N.Y");
  ASSERT_NE(ny, nullptr) << r.output;
  EXPECT_EQ((*ny)["+inf"].get<uint64_t>(), 1u);
  EXPECT_EQ((*ny)["count"].get<uint64_t>(), 39u);
  const json* z = series(ch, "depth", "Z");
  ASSERT_NE(z, nullptr) << r.output;
  EXPECT_EQ((*z)["-inf"].get<uint64_t>(), 1u);
  EXPECT_EQ((*z)["min"].get<double>(), 2.0);
  EXPECT_EQ((*z)["p99"].get<double>(), 2.0);
  uint64_t histogram = 0;
  for (const json& n : (*z)["histogram"]) histogram += n.get<uint64_t>();
  EXPECT_EQ(histogram, 39u);  // the finite values only
  // The decoded eye depth: the stored one (encoding "eye": the series is the quantity itself), over
  // the pixels with a surface.
  const json* eye = series(s["quantities"], "depth", "Z");
  ASSERT_NE(eye, nullptr) << r.output;
  EXPECT_EQ((*eye)["max"].get<double>(), 2.0);

  // --target keeps that target's series only.
  RunResult one = runGblens("stats '" + capture + "' --rect 2,0,8,5 --target normal --json");
  ASSERT_EQ(one.exitCode, 0) << one.output;
  const json parsed = json::parse(one.output);  // alive through the loop: a range-for over parse(...)[...] dangles
  for (const json& c : parsed["channels"]) EXPECT_EQ(c["target"], "normal");

  // The text table says the same.
  RunResult text = runGblens("stats '" + capture + "' --rect 2,0,8,5");
  ASSERT_EQ(text.exitCode, 0) << text.output;
  EXPECT_NE(text.output.find("region 2,0 8x5: 40 pixels"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("NaN 1"), std::string::npos) << text.output;
}

TEST(Stats, MistakesGiveOneLineNamingTheFlagAndExitTwo) {
  const std::string capture = importFixtureC(freshDir("stats-mistakes"));
  struct Case {
    std::string args, flag;
  };
  for (const Case& c : std::vector<Case>{{"--rect 10,4,8,8", "--rect"},   // past the 16x8 frame
                                         {"--rect 0,0,0,4", "--rect"},    // empty
                                         {"--rect 1,2,3", "--rect"},      // three numbers
                                         {"--rect a,b,c,d", "--rect"},
                                         {"--rect 0,0,4,4 --target nosuch", "--target"}}) {
    RunResult r = runGblens("stats '" + capture + "' " + c.args + " 2>&1");
    SCOPED_TRACE(c.args);
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find(c.flag), std::string::npos) << r.output;
    std::string line = r.output;
    while (!line.empty() && line.back() == '\n') line.pop_back();
    EXPECT_EQ(line.find('\n'), std::string::npos) << "more than one line: " << r.output;
  }
}

}  // namespace
}  // namespace gb
