// Issue 36 through gblens attach:
// - --stats with an application that never makes a Vulkan device (/bin/true), or that is killed
//   mid-stream, prints its figures and exits 2 with why, never `terminate called ...` (item 1);
// - a killed attach's $TMPDIR/gblens-attach-PID-START-* folder and socket are removed by the next
//   attach there, which says so (item 4); a TMPDIR too long for a socket is refused by name;
// - a live capture states only what its source said: compared with `gblens capture` of the same
//   frame, every texel passes and so does the verdict; what only one side holds (the capture's
//   lights, sun, options; targets the application did not draw in that frame) is reported apart (item 8).
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <signal.h>

#include <chrono>
#include <filesystem>
#include <thread>

#include "tests/gui/gui_util.h"
#include "tests/support/capture_util.h"
#include "views/analysis/compare.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

std::string app(const std::string& args) { return std::string("'") + GBLENS_BINARY + "' " + args; }

// The JSON object --stats prints (from the first "{" line to the last "}").
json statsOf(const std::string& output) {
  const size_t start = output.find("{\n"), end = output.rfind("\n}");
  if (start == std::string::npos || end == std::string::npos) return json();
  return json::parse(output.substr(start, end + 2 - start), nullptr, false);
}

TEST(RobustAttach, StatsWithoutAFrameExitTwoWithWhy) {
  const std::string dir = freshDir("robust_attach_stats");
  for (const std::string& args : {std::string("--frames 5 --stats"), "--capture-frame 1 -o '" + dir + "/D' --stats"}) {
    SCOPED_TRACE(args);
    const RunResult r = runGblens("attach --layout builtin:gblens " + args + " -- /bin/true");
    EXPECT_EQ(r.exitCode, 2) << r.output;
    EXPECT_EQ(r.output.find("terminate called"), std::string::npos) << r.output;
    EXPECT_NE(r.output.find("gblens attach: the application ended without creating a Vulkan device under the layer"),
              std::string::npos) << r.output;
    const json stats = statsOf(r.output);
    ASSERT_TRUE(stats.is_object()) << r.output;
    EXPECT_EQ(stats["received"], 0);
    EXPECT_TRUE(stats["application"].is_null()) << "nobody said which application: " << stats.dump();
    EXPECT_FALSE(fs::exists(dir + "/D"));
  }
  // The application killed before the frame asked for: its figures so far, exit 2.
  const RunResult killed = runGblens("attach --layout builtin:gblens --frames 100000 --stats -- sh -c \"" +
                                     app("render --size 32x18 --lights 2 --frames 100000 -o '" + dir + "/f.png'") +
                                     " & sleep 1; kill -9 \\$!\"");
  EXPECT_EQ(killed.exitCode, 2) << killed.output;
  EXPECT_EQ(killed.output.find("terminate called"), std::string::npos) << killed.output;
  EXPECT_TRUE(statsOf(killed.output).is_object()) << killed.output;
}

// Socket folders of attach processes in `tmp`.
std::vector<std::string> socketFolders(const std::string& tmp) {
  std::vector<std::string> out;
  for (const auto& e : fs::directory_iterator(tmp))
    if (e.path().filename().string().rfind("gblens-attach-", 0) == 0) out.push_back(e.path().string());
  return out;
}

TEST(RobustAttach, AKilledAttachsSocketFolderIsRemovedByTheNext) {
  // Both attaches in a TMPDIR of their own: under ctest -j the attaches of other tests, which
  // clean /tmp, never see (and remove) this debris first.
  const std::string dir = freshDir("robust_attach_debris"), tmp = dir + "/tmp";
  fs::create_directories(tmp);
  const pid_t attach = gui::spawn({GBLENS_BINARY, "attach", "--layout", "builtin:gblens", "--frames", "1", "--", "sleep", "2"},
                                  {"TMPDIR=" + tmp}, dir + "/attach.log");
  std::string left;  // its folder, once made
  for (int i = 0; i < 500 && left.empty(); ++i) {
    for (const std::string& f : socketFolders(tmp))
      if (f.find("gblens-attach-" + std::to_string(attach) + "-") != std::string::npos && fs::exists(f + "/socket"))
        left = f;
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
  ASSERT_FALSE(left.empty()) << "no socket folder named by pid " << attach;
  kill(attach, SIGKILL);
  int status = 0;
  gui::waitExit(attach, 10.0, status);
  ASSERT_TRUE(fs::exists(left)) << "a killed attach leaves its folder";
  const RunResult next = runShell("TMPDIR='" + tmp + "' " + app("attach --layout builtin:gblens --frames 1 -- /bin/true"));
  EXPECT_FALSE(fs::exists(left));
  EXPECT_NE(next.output.find("gblens attach: removed " + left + " (left by process " + std::to_string(attach) +
                             ", which is gone)"),
            std::string::npos) << next.output;
}

TEST(RobustAttach, ATmpdirTooLongForASocketIsRefusedByName) {
  const std::string dir = freshDir("robust_attach_tmpdir"), tmp = dir + "/" + std::string(110, 't');
  fs::create_directories(tmp);
  const RunResult r = runShell("TMPDIR='" + tmp + "' " + app("attach --layout builtin:gblens --frames 1 -- /bin/true"));
  EXPECT_EQ(r.exitCode, 2) << r.output;
  EXPECT_NE(r.output.find("TMPDIR: " + tmp + " is too long a path for a socket"), std::string::npos) << r.output;
  EXPECT_TRUE(fs::is_empty(tmp)) << "nothing made there";
}

TEST(RobustAttach, ALiveCaptureStatesOnlyWhatItsSourceSaid) {
  const std::string dir = freshDir("robust_attach_live");
  const std::string frame = "--size 48x27 --lights 4 --time 1 --shadow-map-size 64";
  const RunResult live = runGblens("attach --layout builtin:gblens --capture-frame 2 -o '" + dir + "/live' -- " +
                                   app("render " + frame + " --frames 6 -o '" + dir + "/f.png'"));
  ASSERT_EQ(live.exitCode, 0) << live.output;
  ASSERT_EQ(runGblens("capture " + frame + " -o '" + dir + "/ref'").exitCode, 0);
  const json m = json::parse(readText(dir + "/live/manifest.json"));
  for (const char* field : {"sun", "time", "lightClipFromWorld", "driver"}) EXPECT_FALSE(m.contains(field)) << field;
  EXPECT_FALSE(m["lights"].contains("count"));
  EXPECT_FALSE(m["options"].contains("time"));
  EXPECT_FALSE(m["options"].contains("coverage"));
  EXPECT_EQ(m["options"]["size"], "48x27");  // what the streamed images say
  for (const char* field : {"sun", "lights", "options", "time"}) EXPECT_TRUE(m["unknown"].contains(field)) << field;

  const RunResult r = runGblens("compare '" + dir + "/live' '" + dir + "/ref' --json '" + dir + "/r.json'");
  EXPECT_EQ(r.exitCode, kComparePass) << r.output;
  const json report = json::parse(readText(dir + "/r.json"));
  auto names = [](const json& list) {
    std::vector<std::string> n;
    for (const json& d : list) n.push_back(d["name"]);
    return n;
  };
  const std::vector<std::string> onlyRef = names(report["only_in_b"]), differ = names(report["differences"]);
  for (const char* field : {"sun.enabled", "lights.count", "options.time", "options.coverage"}) {
    EXPECT_NE(std::find(onlyRef.begin(), onlyRef.end(), field), onlyRef.end()) << field << " in " << report["only_in_b"];
    EXPECT_EQ(std::find(differ.begin(), differ.end(), field), differ.end()) << field << " in " << report["differences"];
  }
  EXPECT_TRUE(report["mismatches"].empty()) << report["mismatches"];
  bool shadowApart = false;  // the application renders its shadow map in its first frame only
  for (const json& s : report["skipped"]) shadowApart |= s["target"] == "shadow_map" && s["reason"].get<std::string>().find("not in the source") != std::string::npos;
  EXPECT_TRUE(shadowApart) << report["skipped"];
  for (const json& g : report["groups"]) EXPECT_EQ(g["result"], "pass") << g["key"];
}

}  // namespace
}  // namespace gb
