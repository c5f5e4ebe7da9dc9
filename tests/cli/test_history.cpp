// gblens history and check SEQ's class history (issue 38) on tests/subjects/motion_rig: its lit colour's
// history target, reprojected by the rig's own true motion, and three planted history bugs, each
// mode's answer in a hand-written truth file ("history": current, stale, previous, this_frame). Every
// mode must be detected and named as its truth says; a layout whose history_of names no quantity of
// the layout is refused in one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include <nlohmann/json.hpp>

#include "tests/support/capture_util.h"
#include "tests/support/test_paths.h"

namespace gb {
namespace {

using json = nlohmann::json;

std::string historyRigDir() { return GBLENS_SOURCE_DIR + "/tests/subjects/motion_rig"; }

json historyReadJson(const std::string& path) {
  std::ifstream in(path);
  return json::parse(in);
}

// The rig's frames for a mode under a layout (the rig's own by default), imported as a sequence.
std::string historyRigSequence(const std::string& dir, const std::string& mode, const json* layout = nullptr) {
  RunResult r = runShell("'" + GBLENS_BUILD_DIR + "/tests/subjects/motion_rig/motion_rig' --out '" + dir +
                         "/frames' --frames 5 --bug " + mode);
  EXPECT_EQ(r.exitCode, 0) << r.output;
  std::ofstream(dir + "/frames/layout.json") << (layout ? *layout : historyReadJson(historyRigDir() + "/layout.json")).dump(2);
  r = runGblens("import --layout '" + dir + "/frames/layout.json' --frames 0..4 -o '" + dir + "/seq'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  return dir + "/seq";
}

TEST(HistoryCli, EveryHistoryModeOfTheRigIsDetectedAndNamed) {
  // The words of each finding (history.h historyDifferences), by what the truth says the history holds.
  const std::map<std::string, std::string> named = {{"stale", "one frame stale"},
                                                    {"previous", "not reprojected"},
                                                    {"this_frame", "this frame's X, not the previous one's"}};
  for (const std::string mode : {"none", "history_stale", "history_not_reprojected", "history_current", "y_flipped"}) {
    SCOPED_TRACE(mode);
    const std::string seq = historyRigSequence(freshDir("history-rig-" + mode), mode);
    const std::string truth = historyReadJson(historyRigDir() + "/truth/" + mode + ".json").at("history");
    const RunResult r = runGblens("history '" + seq + "' --json");
    ASSERT_EQ(r.exitCode, truth == "current" ? 0 : 1) << r.output;
    const json report = json::parse(r.output);
    EXPECT_EQ(report["format"], "gblens-history");
    EXPECT_EQ(report["verdict"], truth == "current" ? "agrees" : "differs");
    ASSERT_EQ(report["histories"].size(), 1u);
    EXPECT_EQ(report["histories"][0]["history_of"], "color");
    EXPECT_EQ(report["histories"][0]["history_space"], "current");
    // Every decided pair finds the truth; only an empty history (frame 1 of the stale mode, which
    // holds frame 0's zero history) may be undecided.
    int decided = 0;
    for (const json& p : report["pairs"]) {
      if (p["found"].is_null()) {
        EXPECT_NE(p["undecided"].get<std::string>().find("empty"), std::string::npos) << p.dump();
        continue;
      }
      ++decided;
      EXPECT_EQ(p["found"], truth) << "pair " << p["current"];
      EXPECT_TRUE(p["hypotheses"][truth]["fits"]) << p.dump();
      EXPECT_GT(p["comparable_pixels"].get<int>(), 160 * 96 / 3);
    }
    EXPECT_GE(decided, truth == "stale" ? 3 : 4);
    if (truth == "current") {
      EXPECT_TRUE(report["findings"].empty()) << r.output;
    } else {
      ASSERT_EQ(report["findings"].size(), 1u) << r.output;
      EXPECT_NE(report["findings"][0].get<std::string>().find(named.at(truth)), std::string::npos) << r.output;
      EXPECT_EQ(report["findings"][0].get<std::string>().rfind("hist (history of color): ", 0), 0u) << "the names first";
    }
    // The text report names the same.
    const RunResult text = runGblens("history '" + seq + "'");
    EXPECT_EQ(text.exitCode, r.exitCode);
    EXPECT_NE(text.output.find(truth == "current" ? "verdict: agrees" : named.at(truth)), std::string::npos) << text.output;
  }
}

// The same files under a layout that declares history_space previous: the rig's unreprojected
// history now agrees, and its reprojected one is named as reprojected.
TEST(HistoryCli, ADeclaredPreviousSpaceIsCheckedToo) {
  json layout = historyReadJson(historyRigDir() + "/layout.json");
  for (json& t : layout["targets"])
    if (t["name"] == "history") t["quantities"][0]["history_space"] = "previous";
  for (const std::string mode : {"history_not_reprojected", "none"}) {
    SCOPED_TRACE(mode);
    const std::string seq = historyRigSequence(freshDir("history-previous-" + mode), mode, &layout);
    const RunResult r = runGblens("history '" + seq + "' --json");
    const json report = json::parse(r.output);
    if (mode == "none") {
      EXPECT_EQ(r.exitCode, 1) << r.output;
      ASSERT_EQ(report["findings"].size(), 1u) << r.output;
      EXPECT_NE(report["findings"][0].get<std::string>().find("reprojected into this frame's pixels"), std::string::npos);
    } else {
      EXPECT_EQ(r.exitCode, 0) << r.output;
      EXPECT_EQ(report["verdict"], "agrees");
    }
    for (const json& p : report["pairs"]) EXPECT_EQ(p["declared"], "previous");
  }
}

TEST(HistoryCli, CheckSeqFaultsAStaleHistoryAndThePolicyLowersIt) {
  const std::string stale = historyRigSequence(freshDir("history-check-stale"), "history_stale");
  RunResult r = runGblens("check '" + stale + "' --json");
  ASSERT_EQ(r.exitCode, 1) << r.output;
  json j = json::parse(r.output);
  EXPECT_EQ(j["temporal"]["history"]["verdict"], "differs");
  EXPECT_EQ(j["temporal"]["history_severity"], "fault");
  EXPECT_EQ(j["temporal"]["motion"]["verdict"], "agrees");  // the vectors are right: the history alone faults
  r = runGblens("check '" + stale + "'");
  EXPECT_EQ(r.exitCode, 1);
  EXPECT_NE(r.output.find("temporal, history (a finding is a fault)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("one frame stale"), std::string::npos) << r.output;
  for (const std::string rule : {"history=warn", "hist.history=warn"}) {
    r = runGblens("check '" + stale + "' --json --policy " + rule);
    EXPECT_EQ(r.exitCode, 0) << rule << ": " << r.output;
    EXPECT_EQ(json::parse(r.output)["temporal"]["history_severity"], "warn") << rule;
  }
  const std::string right = historyRigSequence(freshDir("history-check-none"), "none");
  r = runGblens("check '" + right + "'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
}

TEST(HistoryCli, ALayoutWhoseHistoryNamesNoQuantityFailsInOneLine) {
  const std::string dir = freshDir("history-bad-layout");
  RunResult r = runShell("'" + GBLENS_BUILD_DIR + "/tests/subjects/motion_rig/motion_rig' --out '" + dir + "/frames' --frames 2");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json good = historyReadJson(historyRigDir() + "/layout.json");
  struct Case {
    const char* field;
    json value;
    const char* words;
  };
  const Case cases[] = {{"history_of", "colour", "history_of: \"colour\" is not a quantity of the layout"},
                        {"history_of", "mv", "history_of: \"mv\" has 2 components, \"hist\" 3"},
                        {"history_of", "hist", "cannot be its own history"},
                        {"history_space", "reprojected", "history_space: \"reprojected\" is not one of previous, current"}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.words);
    json layout = good;
    for (json& t : layout["targets"])
      if (t["name"] == "history") t["quantities"][0][c.field] = c.value;
    std::ofstream(dir + "/frames/layout.json") << layout.dump(2);
    r = runGblens("import --layout '" + dir + "/frames/layout.json' --frames 0..1 -o '" + dir + "/seq'");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_NE(r.output.find(c.words), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("quantities[0] \"hist\""), std::string::npos) << r.output;
    EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "one line: " << r.output;
    EXPECT_FALSE(std::filesystem::exists(dir + "/seq"));
  }
  // A layout without a history: `gblens history` says so in one line, exit 2.
  json plain = good;
  plain["targets"].erase(plain["targets"].size() - 1);
  const std::string seq = historyRigSequence(dir + "/plain", "none", &plain);
  r = runGblens("history '" + seq + "'");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("no history quantity"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find('\n'), r.output.size() - 1) << "one line: " << r.output;
  r = runGblens("history '" + historyRigSequence(dir + "/named", "none") + "' --history color");
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("--history color: not a history"), std::string::npos) << r.output;
}

}  // namespace
}  // namespace gb
