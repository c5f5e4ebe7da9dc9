// The command line as a user or CI job meets it: exit codes for mistakes, the --stats JSON
// shape every later tool reads (frame_ms, passes with skip reasons, culling, what auto picked),
// and the PNG written.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

namespace gb {

struct CliRun {
  int status = -1;
  std::string out;  // stdout only; stderr goes to the test log
};

static CliRun runGblens(const std::string& args) {
  CliRun r;
  std::string cmd = std::string(GBLENS_BINARY) + " " + args;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) r.out.append(buf.data(), n);
  int st = pclose(p);
  r.status = WIFEXITED(st) ? WEXITSTATUS(st) : -1;
  return r;
}

TEST(Cli, MistakesExitWithTwoAndNameTheFlag) {
  EXPECT_EQ(runGblens("render --no-such-flag").status, 2);
  EXPECT_EQ(runGblens("render --size 12").status, 2);
  EXPECT_EQ(runGblens("render --lights 70000").status, 2);
  EXPECT_EQ(runGblens("render --path three-pass").status, 2);
  EXPECT_EQ(runGblens("render does-not-exist.gltf").status, 2);
  EXPECT_EQ(runGblens("render builtin:nothing").status, 2);
  EXPECT_EQ(runGblens("no-such-command").status, 2);
}

TEST(Cli, RenderStatsReportEveryPassAndTheCullingEfficiency) {
  std::filesystem::path png = std::filesystem::temp_directory_path() / "gblens_cli_stats.png";
  std::filesystem::remove(png);
  CliRun r = runGblens("render --validate --size 96x54 --lights 32 --frames 3 --stats -o " + png.string());
  ASSERT_EQ(r.status, 0);
  EXPECT_TRUE(std::filesystem::exists(png));
  nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_GT(j["frame_ms"].get<double>(), 0.0);
  EXPECT_EQ(j["frames"].get<int>(), 3);
  // Frames 1 and 2 in flight (2 counted after the first), frame 3 read back for the PNG.
  EXPECT_EQ(j["frames_in_flight"].get<int>(), 2);
  EXPECT_NE(j["frame_ms_measured"].get<std::string>().find("throughput of frames in flight: wall time per frame of 1 timed"), std::string::npos);
  std::vector<std::string> names;
  for (const auto& p : j["passes"]) {
    names.push_back(p["name"]);
    if (p["skipped"].get<bool>()) {
      EXPECT_FALSE(p["reason"].get<std::string>().empty()) << p["name"];
      EXPECT_EQ(p["ms"].get<double>(), 0.0) << p["name"];
    }
  }
  // The frame's passes in the seed's order.
  std::vector<std::string> order = {"shadow_map", "gbuffer", "directional_light", "light_mask",
                                    "point_lights", "skybox", "fairy_lights", "tonemap"};
  size_t at = 0;
  for (const std::string& n : names)
    if (at < order.size() && n == order[at]) ++at;
  EXPECT_EQ(at, order.size()) << "passes out of order or missing";
  // The shadow map ran in frame 1 and is reused in frames 2 and 3.
  for (const auto& p : j["passes"])
    if (p["name"] == "shadow_map") {
      EXPECT_TRUE(p["skipped"].get<bool>());
      EXPECT_EQ(p["runs"].get<int>(), 1);
    }
  const auto& c = j["culling"];
  EXPECT_GT(c["ideal_pairs"].get<uint64_t>(), 0u);
  EXPECT_GE(c["invocations"].get<uint64_t>(), c["ideal_pairs"].get<uint64_t>());
  EXPECT_NEAR(c["work_over_ideal"].get<double>(),
              double(c["invocations"].get<uint64_t>()) / double(c["ideal_pairs"].get<uint64_t>()), 1e-9);
  std::filesystem::remove(png);
}

// The default G-buffer is --gbuffer auto; on lavapipe (a CPU device) it rasterizes, and the stats
// say so with the auto reason, as they do for --method auto. The capture records the kind that ran
// (what its targets' absences follow), the --stats options the one asked for.
TEST(Cli, TheDefaultGBufferIsAutoAndRasterOnACpuDevice) {
  const std::filesystem::path dir = std::filesystem::temp_directory_path() / "gblens_cli_gbuffer_auto";
  std::filesystem::remove_all(dir);
  CliRun r = runGblens("capture --validate --size 96x54 --lights 8 --stats -o " + dir.string());
  ASSERT_EQ(r.status, 0);
  const nlohmann::json j = nlohmann::json::parse(r.out);
  EXPECT_EQ(j["format"], "gblens-frame-stats");
  EXPECT_EQ(j["version"], 3);  // docs/json.md: 2 added gbuffer, 3 overlap
  EXPECT_EQ(j["overlap"]["ran"], false);  // one queue, a CPU device
  EXPECT_EQ(j["overlap"]["why"], "auto: a CPU device runs one part at a time");
  EXPECT_EQ(j["options"]["gbuffer"], "auto");
  EXPECT_EQ(j["gbuffer"]["ran"], "raster");
  const std::string why = j["gbuffer"]["why"];
  EXPECT_EQ(why.rfind("auto: raster on a CPU device (lavapipe", 0), 0u) << why;
  for (const auto& p : j["passes"])
    if (p["name"] == "visibility" || p["name"] == "gbuffer_resolve") EXPECT_EQ(p["reason"], why) << p["name"];
  std::ifstream mf(dir / "manifest.json");
  const nlohmann::json m = nlohmann::json::parse(mf);
  EXPECT_EQ(m["options"]["gbuffer"], "raster");
  EXPECT_EQ(m["stats"]["gbuffer"]["ran"], "raster");
  EXPECT_EQ(m["stats"]["gbuffer"]["why"], why);
  std::filesystem::remove_all(dir);
}

}  // namespace gb
