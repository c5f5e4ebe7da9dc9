// `gblens error` and `gblens bench` as a user runs them (validation on through GBLENS_VALIDATE):
// the JSON has every quantity with sane values, the bench writes its files with one row per
// variant, and user mistakes exit 2 with a message while a glTF that fails to load is skipped.
#include "tests/support/test_paths.h"
#include <sys/wait.h>
#include <unistd.h>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>

namespace gb {

namespace {

struct CliRun {
  int status = -1;
  std::string out;  // stdout and stderr
};

CliRun run(const std::string& args) {
  CliRun r;
  std::string cmd = std::string(GBLENS_BINARY) + " " + args + " 2>&1";
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return r;
  char buf[4096];
  while (size_t n = fread(buf, 1, sizeof buf, p)) r.out.append(buf, n);
  int s = pclose(p);
  r.status = WIFEXITED(s) ? WEXITSTATUS(s) : -1;
  return r;
}

std::string tempDir(const char* name) {
  auto dir = std::filesystem::temp_directory_path() / (std::string("gblens_test_") + name + "_" + std::to_string(getpid()));
  std::filesystem::remove_all(dir);
  return dir.string();
}

}  // namespace

TEST(CliAccuracy, ErrorJsonReportsEveryQuantity) {
  CliRun r = run("error --size 96x54 --lights 8 --json");
  ASSERT_EQ(r.status, 0) << r.out;
  nlohmann::json j = nlohmann::json::parse(r.out.substr(r.out.find('{')));
  const nlohmann::json& e = j["error"];
  EXPECT_EQ(j["options"]["normal_format"], j["options"]["normal_format"].get<std::string>());
  EXPECT_GT(e["pixels"]["surface"].get<int>(), 96 * 54 / 3);
  EXPECT_EQ(e["pixels"]["silhouettes_from"], "primitive_id");
  EXPECT_LT(e["pixels"]["silhouette"].get<double>(), 0.05 * 96 * 54);
  EXPECT_LT(e["normal_deg"]["mean"].get<double>(), 0.03);
  EXPECT_LT(e["position"]["eye_depth"]["relative"]["max"].get<double>(), 1e-3);
  EXPECT_GT(e["position"]["hardware_depth"]["relative"]["mean"].get<double>(), 0.0);
  EXPECT_GT(e["shadow"]["compared"].get<int>(), 100);
  EXPECT_LT(e["shadow"]["fraction"].get<double>(), 0.02);
  EXPECT_GT(e["hdr"]["relative"]["count"].get<int>(), 1000);
  EXPECT_LT(e["lighting"]["per_contribution"]["max"].get<double>(), std::ldexp(1.0, -10) + 1e-5);
}

TEST(CliAccuracy, ErrorWritesImagesAndRejectsBadFlags) {
  std::string dir = tempDir("error");
  CliRun r = run("error --size 64x36 --lights 0 -o " + dir);
  ASSERT_EQ(r.status, 0) << r.out;
  for (const char* f : {"shadow.png", "silhouettes.png", "normal.png", "hdr.png", "position.png", "lighting.png"})
    EXPECT_GT(std::filesystem::file_size(std::filesystem::path(dir) / f), 100u) << f;
  std::filesystem::remove_all(dir);
  CliRun bad = run("error --normal-format rgb9 --size 64x36");
  EXPECT_EQ(bad.status, 2);
  EXPECT_NE(bad.out.find("--normal-format"), std::string::npos) << bad.out;
}

TEST(CliAccuracy, BenchWritesJsonCsvAndPlotsWithOneRowPerVariant) {
  std::string dir = tempDir("bench");
  CliRun r = run("bench builtin:temple /nonexistent/model.gltf --only default,normal_format=rgba16f,lights "
              "--lights-sweep 0,4 --size 96x54 --frames 3 --warmup 1 --depth-range off --out " + dir);
  ASSERT_EQ(r.status, 0) << r.out;
  EXPECT_NE(r.out.find("skipping /nonexistent/model.gltf"), std::string::npos) << r.out;
  std::ifstream jf(std::filesystem::path(dir) / "bench.json");
  nlohmann::json j = nlohmann::json::parse(jf);
  EXPECT_EQ(j["format"], "gblens-bench");
  EXPECT_EQ(j["format_version"], 6);  // docs/json.md: 2 added gbuffer and before_ms, 3 overlap, 4 steady_ms, 5 attach_application, 6 the viewer variants
  ASSERT_EQ(j["rows"].size(), 5u);  // default, rgba16f normals, lights=0, lights=4, default (repeat)
  for (const auto& row : j["rows"]) {
    EXPECT_TRUE(row["measured"].get<bool>()) << row["variant"];
    EXPECT_EQ(row["frames"].get<int>(), 3);
    EXPECT_GT(row["frame_ms"]["median"].get<double>(), 0.0);
    EXPECT_LE(row["frame_ms"]["min"].get<double>(), row["frame_ms"]["median"].get<double>());
    EXPECT_GT(row["error"]["normal_deg_mean"].get<double>(), 0.0);
    EXPECT_EQ(row["options"]["size"], "96x54");
  }
  EXPECT_EQ(j["rows"][1]["options"]["normal_format"], "rgba16f");
  EXPECT_EQ(j["rows"][2]["options"]["lights"], 0);
  ASSERT_EQ(j["defaults"].size(), 1u);
  EXPECT_EQ(j["skipped_scenes"].size(), 1u);
  std::ifstream cf(std::filesystem::path(dir) / "bench.csv");
  std::string line;
  int lines = 0;
  while (std::getline(cf, line)) ++lines;
  EXPECT_EQ(lines, 6);
  for (const char* f : {"time_vs_error.png", "time_vs_lights.png", "bench.md"}) {
    std::ifstream img(std::filesystem::path(dir) / f, std::ios::binary);
    std::string head(8, '\0');
    img.read(head.data(), 8);
    EXPECT_TRUE(img) << f;
    if (std::string(f).ends_with(".png")) {
      EXPECT_EQ(head.substr(1, 3), "PNG") << f;
    }
  }
  std::filesystem::remove_all(dir);
  EXPECT_EQ(run("bench --only nosuch --out " + dir).status, 2);
}

// The method comparison: the five methods at every light count, in bench.json, methods.csv and
// bench.md, with their ratios to the defaults (the method auto picks, marked) taken in the same
// rounds (the defaults' own is 1), the G-buffer kind each ran,
// culling work from the coverage counts (forward's: every visible light at every fragment it
// shaded, far above the ideal pairs), and forward left out above --methods-forward-max.
TEST(CliAccuracy, BenchComparesTheMethodsSideBySide) {
  std::string dir = tempDir("bench_methods");
  CliRun r = run("bench --only methods --methods-sizes 96x54 --methods-lights 0,24 --methods-forward-max 8 "
                 "--methods-rounds 2 --methods-min-rounds 2 --methods-burst 3 --size 96x54 --lights 8 --out " + dir);
  ASSERT_EQ(r.status, 0) << r.out;
  std::ifstream jf(std::filesystem::path(dir) / "bench.json");
  nlohmann::json j = nlohmann::json::parse(jf);
  EXPECT_EQ(j["rows"].size(), 0u);  // no sweep variant asked for
  // Frame ms is the throughput of bursts of frames in flight, and the report says so.
  EXPECT_EQ(j["methods_settings"]["burst"].get<int>(), 3);
  EXPECT_EQ(j["methods_settings"]["frames_in_flight"].get<int>(), 2);
  EXPECT_NE(j["methods_settings"]["frame_ms"].get<std::string>().find("throughput"), std::string::npos);
  EXPECT_NE(j["methods_settings"]["steady_ms"].get<std::string>().find("without the pipeline's fill"), std::string::npos);
  ASSERT_EQ(j["methods"].size(), 10u);  // 5 methods x 2 light counts
  std::map<std::string, int> seen;
  for (const auto& m : j["methods"]) {
    const std::string method = m["method"];
    ++seen[method];
    const int lights = m["lights"];
    EXPECT_EQ(m["size"], "96x54");
    if (method == "forward" && lights == 24) {
      EXPECT_FALSE(m["measured"].get<bool>());  // above --methods-forward-max
      continue;
    }
    ASSERT_TRUE(m["measured"].get<bool>()) << method << " " << lights;
    EXPECT_EQ(m["bursts"].get<int>(), 2);  // one per round
    EXPECT_EQ(m["frames"].get<int>(), 4);  // each burst's but its first
    EXPECT_EQ(m["frames_in_flight"].get<int>(), 2);
    EXPECT_EQ(m["gbuffer"], "raster") << method;  // --gbuffer auto on a CPU device
    EXPECT_GT(m["frame_ms"]["median"].get<double>(), 0.0);
    // The steady state (lavapipe has timestamps) never exceeds what the wall clock allows: a burst of 3
    // counts 2 frames, so steady x 1 <= frame ms x 2 in every round, and the medians keep that.
    ASSERT_TRUE(m.contains("steady_ms")) << method;
    EXPECT_GT(m["steady_ms"]["median"].get<double>(), 0.0) << method;
    EXPECT_LE(m["steady_ms"]["median"].get<double>(), 2.0 * m["frame_ms"]["max"].get<double>()) << method;
    if (m["auto_pick"].get<bool>()) {
      EXPECT_EQ(m["time_over_default"].get<double>(), 1.0);
      ++seen["auto"];
    }
    EXPECT_GT(m["time_over_default"].get<double>(), 0.0);
    ASSERT_TRUE(m.contains("culling")) << method;
    if (lights == 0) {
      EXPECT_EQ(m["culling"]["ideal_pairs"].get<uint64_t>(), 0u);
      continue;
    }
    const double work = m["culling"]["work_over_ideal"];
    EXPECT_GE(work, 1.0) << method;  // every method evaluates at least the pairs that light a pixel
    if (method == "deferred_unculled") {
      for (const auto& d : j["methods"])
        if (d["method"] == "deferred" && d["lights"] == lights) {
          EXPECT_GT(work, d["culling"]["work_over_ideal"].get<double>());  // culling removes work
        }
    }
  }
  for (const char* method : {"deferred", "deferred_unculled", "forward", "tiled", "clustered", "auto"})
    EXPECT_EQ(seen[method], 2) << method;  // auto: one picked row per light count
  ASSERT_EQ(j["skips"].size(), 3u);
  EXPECT_EQ(j["skips"][0]["pass"], "shadow_map");
  int lines = 0;
  std::ifstream cf(std::filesystem::path(dir) / "methods.csv");
  for (std::string line; std::getline(cf, line);) ++lines;
  EXPECT_EQ(lines, 11);
  std::ifstream md(std::filesystem::path(dir) / "bench.md");
  std::string text((std::istreambuf_iterator<char>(md)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("## Lighting methods"), std::string::npos);
  EXPECT_NE(text.find("| lights | method | gbuffer |"), std::string::npos);
  EXPECT_NE(text.find("Culling efficiency vs lights"), std::string::npos);
  std::ifstream img(std::filesystem::path(dir) / "methods_vs_lights.png", std::ios::binary);
  std::string head(4, '\0');
  img.read(head.data(), 4);
  EXPECT_EQ(head.substr(1, 3), "PNG");
  std::filesystem::remove_all(dir);
}

}  // namespace gb
