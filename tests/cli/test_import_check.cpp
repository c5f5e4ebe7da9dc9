// gblens check (issue 15): a G-buffer with planted NaN, +Inf, -Inf, denormal and out-of-range texels
// (tests/cli/import_fixtures.h, fixture C), imported, is reported with each at the pixel it was planted
// in and exit 1; the same G-buffer without them exits 0; a capture that cannot be read exits 2.
#include <gtest/gtest.h>

#include <map>

#include "tests/cli/import_fixtures.h"
#include "tests/support/capture_util.h"

namespace gb {
namespace {

using json = nlohmann::json;

// What was planted: (target, quantity) -> kind -> (x, y).
struct Planted {
  std::string target, quantity, kind;
  uint32_t x, y;
};
const std::vector<Planted> kPlanted = {
    {"gbuf", "Albedo", "nan", 3, 1},     {"normal", "N", "+inf", 5, 2},          {"depth", "Z", "-inf", 7, 3},
    {"gbuf", "Roughness", "denormal", 9, 4}, {"gbuf", "Albedo", "out_of_range", 2, 5}, {"normal", "N", "out_of_range", 11, 6},
    {"depth", "Z", "out_of_range", 13, 7},
};

std::string importFixtureC(const std::string& dir, bool plant) {
  fixtures::writeFixtureC(dir, plant);
  RunResult r = runGblens("import --layout '" + dir + "/c.json' -o '" + dir + "/capture'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return dir + "/capture";
}

TEST(Check, FindsEveryPlantedTexelAtItsPixel) {
  const std::string capture = importFixtureC(freshDir("check-planted"), true);
  RunResult r = runGblens("check '" + capture + "' --json 2>/dev/null");
  ASSERT_EQ(r.exitCode, 1) << r.output;
  const json report = json::parse(r.output);
  EXPECT_FALSE(report["clean"].get<bool>());
  std::map<std::string, uint64_t> expectedTotals;
  for (const Planted& p : kPlanted) expectedTotals[p.kind]++;
  for (const char* kind : {"nan", "+inf", "-inf", "denormal", "out_of_range"})
    EXPECT_EQ(report["counts"][kind].get<uint64_t>(), expectedTotals[kind]) << kind << "\n" << r.output;
  for (const json& row : report["rows"]) {
    const std::string target = row["target"], q = row["quantity"];
    for (const char* kind : {"nan", "+inf", "-inf", "denormal", "out_of_range"}) {
      const Planted* planted = nullptr;
      for (const Planted& p : kPlanted)
        if (p.target == target && p.quantity == q && p.kind == kind) planted = &p;
      SCOPED_TRACE(target + " " + q + " " + kind);
      ASSERT_EQ(row[kind]["count"].get<uint64_t>(), planted ? 1u : 0u) << row.dump();
      if (!planted) continue;
      EXPECT_EQ(row[kind]["first"]["x"].get<uint32_t>(), planted->x);
      EXPECT_EQ(row[kind]["first"]["y"].get<uint32_t>(), planted->y);
    }
  }
  // Values as they were planted: the NaN in the albedo's green, the length-0.5 normal, 1.5 albedo red.
  auto first = [&](const std::string& target, const std::string& q, const char* kind) {
    for (const json& row : report["rows"])
      if (row["target"] == target && row["quantity"] == q) return row[kind]["first"];
    return json();
  };
  EXPECT_EQ(first("gbuf", "Albedo", "nan")["channel"], "Albedo.G");
  EXPECT_EQ(first("gbuf", "Albedo", "nan")["value"], "nan");
  EXPECT_EQ(first("gbuf", "Albedo", "out_of_range")["value"].get<double>(), 1.5);
  EXPECT_NEAR(first("normal", "N", "out_of_range")["value"].get<double>(), 0.5, 1e-3);
  EXPECT_EQ(first("depth", "Z", "out_of_range")["value"].get<double>(), -1.0);

  EXPECT_EQ(first("normal", "N", "out_of_range")["channel"], "|N|");  // what was measured, not a component

  // The table names the same pixels. The default policy reports the denormal as a warning (a healthy
  // half-float G-buffer holds true subnormals); a stricter one makes it a fault, a looser one hides it.
  RunResult text = runGblens("check '" + capture + "'");
  EXPECT_EQ(text.exitCode, 1);
  EXPECT_NE(text.output.find("found 6 faults, 1 warnings"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("warn denormal  gbuf Roughness: 9,4"), std::string::npos) << text.output;
  EXPECT_NE(runGblens("check '" + capture + "' --policy denormal=fault").output.find("found 7 faults"), std::string::npos);
  RunResult loose = runGblens("check '" + capture + "' --policy denormal=ignore --policy nan=warn --policy inf=warn "
                              "--policy out_of_range=warn");
  EXPECT_EQ(loose.exitCode, 0) << loose.output;
  EXPECT_NE(loose.output.find("clean: no fault in 4 quantities (6 warnings"), std::string::npos) << loose.output;
  RunResult perQuantity = runGblens("check '" + capture + "' --policy N.out_of_range=ignore --json");
  EXPECT_EQ(json::parse(perQuantity.output)["faults"].get<uint64_t>(), 5u) << perQuantity.output;
  EXPECT_EQ(json::parse(perQuantity.output)["version"], 2) << perQuantity.output;  // normals, surfaces
  RunResult bad = runGblens("check '" + capture + "' --policy Nope.nan=warn");
  EXPECT_EQ(bad.exitCode, 2);
  EXPECT_NE(bad.output.find("--policy Nope.nan=warn: the layout has no quantity \"Nope\""), std::string::npos) << bad.output;
  EXPECT_NE(text.output.find("nan  gbuf Albedo: 3,1 Albedo.G = nan"), std::string::npos) << text.output;
  EXPECT_NE(text.output.find("-inf  depth Z: 7,3"), std::string::npos) << text.output;
}

TEST(Check, CleanCaptureExitsZeroAndUnreadableExitsTwo) {
  const std::string dir = freshDir("check-clean");
  const std::string capture = importFixtureC(dir, false);
  RunResult r = runGblens("check '" + capture + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("clean: no fault in 4 quantities"), std::string::npos) << r.output;
  RunResult missing = runGblens("check '" + dir + "/nothing'");
  EXPECT_EQ(missing.exitCode, 2) << missing.output;
  EXPECT_NE(missing.output.find("nothing: no such capture directory"), std::string::npos) << missing.output;
}

}  // namespace
}  // namespace gb
