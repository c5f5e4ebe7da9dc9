// Issue 36 through the command line, import and compare:
// - a layout may read only files beside it or beside the files given (item 10): /etc/passwd, a
//   "../" path and a link leaving the folder are refused, --allow-outside-sources lets them;
// - a refusal read through a pipe is one line, no progress line before it (item 9);
// - debris of a killed import (.NAME.partial-PID-START-N of a process that is gone) is removed by the
//   next import of that name, which says so (item 4);
// - compare checks every destination before any work and writes nothing when one is bad (item 6),
//   and --json replaces a symbolic link at FILE as output folders do (item 7).
#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>

#include "tests/cli/import_fixtures.h"
#include "tests/support/capture_util.h"
#include "views/analysis/compare.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

size_t lines(const std::string& text) { return size_t(std::count(text.begin(), text.end(), '\n')); }

// Fixture C (16x8) in dir/in, its layout with `edit` applied written as dir/in/c.json.
std::string layoutC(const std::string& dir, const std::function<void(json&)>& edit = {}) {
  fs::create_directories(dir + "/in");
  json l = fixtures::writeFixtureC(dir + "/in", false);
  if (edit) edit(l);
  fixtures::writeJson(dir + "/in/c.json", l);
  return dir + "/in/c.json";
}

TEST(RobustImport, SourcesStayBesideTheLayoutOrTheFilesGiven) {
  const std::string dir = freshDir("robust_outside");
  fs::create_directories(dir + "/elsewhere");
  // The depth file moved out of the layout's folder, named three ways.
  layoutC(dir);
  fs::rename(dir + "/in/depth.exr", dir + "/elsewhere/depth.exr");
  fs::create_symlink(fs::absolute(dir + "/elsewhere/depth.exr"), dir + "/in/link.exr");
  const std::vector<std::pair<std::string, std::string>> named = {
      {"/etc/passwd", "\"/etc/passwd\": outside"},
      {"../elsewhere/depth.exr", "/in/../elsewhere/depth.exr\": outside"},
      {"link.exr", "link.exr\": outside"}};
  for (const auto& [file, words] : named) {
    SCOPED_TRACE(file);
    const std::string layout = layoutC(dir, [&](json& l) { l["targets"][2]["source"]["file"] = file; });
    const RunResult r = runGblens("import --layout '" + layout + "' -o '" + dir + "/out'");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(lines(r.output), 1u) << r.output;
    EXPECT_NE(r.output.find("c.json: targets[2]: \"depth\": source.file \""), std::string::npos) << r.output;
    EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("--allow-outside-sources"), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(dir + "/out"));
  }
  // Given on the command line, the file is the user's: read. The flag lets the layout read it too.
  const std::string layout = layoutC(dir, [&](json& l) { l["targets"][2]["source"]["file"] = "../elsewhere/depth.exr"; });
  RunResult given = runGblens("import '" + dir + "/in/gbuf.exr' '" + dir + "/in/normal.exr' '" + dir +
                              "/elsewhere/depth.exr' --layout '" + layout + "' -o '" + dir + "/given'");
  EXPECT_EQ(given.exitCode, 0) << given.output;
  RunResult allowed = runGblens("import --layout '" + layout + "' --allow-outside-sources -o '" + dir + "/allowed'");
  EXPECT_EQ(allowed.exitCode, 0) << allowed.output;
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/allowed", c, error)) << error;
  const CpuImage& depth = c.frame.images[2].image;  // fixture C's eye depth: 2 everywhere
  float v = 0.0f;
  std::memcpy(&v, depth.data.data(), 4);
  EXPECT_EQ(v, 2.0f);
}

TEST(RobustImport, ARefusalThroughAPipeIsOneLine) {
  const std::string dir = freshDir("robust_one_line");
  const std::string layout = layoutC(dir);
  const std::vector<std::string> mistakes = {
      "--layout '" + dir + "/nope.json' -o '" + dir + "/o'",
      "--layout '" + layout + "' --param normal_format=nope -o '" + dir + "/o'",
      "--layout '" + layout + "' --size 3x3 -o '" + dir + "/o'",
      "'" + dir + "/bad/gbuf.exr' --layout '" + layout + "' -o '" + dir + "/o'",
  };
  fs::create_directories(dir + "/bad");
  std::ofstream(dir + "/bad/gbuf.exr") << "not an EXR";
  for (const std::string& m : mistakes) {
    SCOPED_TRACE(m);
    const RunResult r = runGblens("import " + m + " 2>&1 | cat");
    EXPECT_EQ(lines(r.output), 1u) << r.output;
    EXPECT_EQ(r.output.rfind("gblens import: ", 0), 0u) << r.output;
  }
}

// The stamp (PID-START) of a process that has ended: a shell that printed its pid and exited.
std::string goneStamp() {
  const RunResult r = runShell("sh -c 'echo $$'");
  return r.output.substr(0, r.output.find('\n')) + "-1";
}

TEST(RobustImport, AKilledImportsDebrisIsRemovedByTheNext) {
  const std::string dir = freshDir("robust_debris");
  const std::string layout = layoutC(dir);
  const std::string stamp = goneStamp();
  ASSERT_EQ(std::count(stamp.begin(), stamp.end(), '-'), 1) << stamp;
  const std::string debris = dir + "/.frame.partial-" + stamp + "-123456";
  fs::create_directories(debris);
  std::ofstream(debris + "/depth.exr") << "half a file";
  const RunResult r = runGblens("import --layout '" + layout + "' -o '" + dir + "/frame'");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_FALSE(fs::exists(debris));
  EXPECT_NE(r.output.find("gblens import: removed " + fs::absolute(debris).lexically_normal().string() +
                          " (left by process " + stamp.substr(0, stamp.find('-')) + ", which is gone)"),
            std::string::npos) << r.output;
}

TEST(RobustCompare, EveryDestinationIsCheckedBeforeAnyWork) {
  const std::string root = freshDir("robust_compare");
  std::string error;
  ASSERT_TRUE(writeCapture(root + "/a", syntheticFrame(16, 8), CaptureMeta{}, error)) << error;
  const std::string a = root + "/a";
  fs::create_directories(root + "/notes");
  std::ofstream(root + "/notes/mine.txt") << "not a report";
  const std::vector<std::pair<std::string, std::string>> bad = {
      {"--report '" + root + "/notes'", "--report " + root + "/notes: exists, is not empty and holds no compare report"},
      {"--junit '" + root + "/missing/x.xml'", "--junit " + root + "/missing/x.xml: no folder"},
      {"--json '" + root + "/notes'", "--json " + root + "/notes: is a folder"},
  };
  for (const auto& [flag, words] : bad) {
    SCOPED_TRACE(flag);
    const std::string json = flag.rfind("--json", 0) == 0 ? "" : " --json '" + root + "/r.json'";
    const RunResult r = runGblens("compare " + a + " " + a + " -o '" + root + "/diff'" + json + " " + flag);
    EXPECT_EQ(r.exitCode, kCompareFileError) << r.output;
    EXPECT_EQ(lines(r.output), 1u) << r.output;  // said before any progress line
    EXPECT_NE(r.output.find(words), std::string::npos) << r.output;
    EXPECT_FALSE(fs::exists(root + "/diff"));
    EXPECT_FALSE(fs::exists(root + "/r.json"));
    EXPECT_FALSE(fs::exists(root + "/missing"));
  }
  EXPECT_EQ(readText(root + "/notes/mine.txt"), "not a report");

  // A symbolic link at --json FILE is replaced, as one at an output folder is: its target is untouched.
  std::ofstream(root + "/target.json") << "keep";
  fs::create_symlink(root + "/target.json", root + "/link.json");
  const RunResult r = runGblens("compare " + a + " " + a + " -q --json '" + root + "/link.json'");
  EXPECT_EQ(r.exitCode, kComparePass) << r.output;
  EXPECT_EQ(readText(root + "/target.json"), "keep");
  EXPECT_FALSE(fs::is_symlink(root + "/link.json"));
  EXPECT_EQ(json::parse(readText(root + "/link.json"))["result"], "pass");
}

}  // namespace
}  // namespace gb
