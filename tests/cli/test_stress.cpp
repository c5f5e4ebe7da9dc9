// gblens stress as CI meets it (the suite itself runs as the CTest entry stress.quick): mistakes
// exit 2, one case runs alone and writes its table as JSON.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>


namespace gb {

static int runStatus(const std::string& args, std::string* out = nullptr) {
  std::string cmd = std::string(GBLENS_BINARY) + " " + args;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) return -1;
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0)
    if (out) out->append(buf.data(), n);
  int st = pclose(p);
  return WIFEXITED(st) ? WEXITSTATUS(st) : -1;
}

TEST(Stress, UnknownCaseExitsTwoAndListNamesNine) {
  EXPECT_EQ(runStatus("stress --case no-such-case 2>/dev/null"), 2);
  std::string list;
  EXPECT_EQ(runStatus("stress --list", &list), 0);
  for (const char* name : {"depth-range", "far-from-origin", "lights-at-camera", "tiny-huge-lights", "many-lights",
                           "grazing-sun", "degenerate-geometry", "sizes", "extreme-fov"})
    EXPECT_NE(list.find(name), std::string::npos) << name;
}

TEST(Stress, OneCaseWritesItsTableAsJson) {
  std::filesystem::path json = std::filesystem::path(GBLENS_BUILD_DIR) / "test-stress-sizes.json";
  std::filesystem::remove(json);
  EXPECT_EQ(runStatus("stress --quick --case sizes --json " + json.string() + " 2>/dev/null >/dev/null"), 0);
  std::ifstream in(json);
  ASSERT_TRUE(in.good());
  nlohmann::json j = nlohmann::json::parse(in);
  ASSERT_TRUE(j["rows"].is_array());
  bool nanRow = false;
  for (const auto& row : j["rows"]) {
    EXPECT_EQ(row["case"], "sizes");
    EXPECT_NE(row["result"], "FAIL") << row.dump();
    nanRow |= row["metric"] == "NaN/Inf texels, all targets" && row["measured"] == 0.0;
  }
  EXPECT_TRUE(nanRow);
}


}  // namespace gb
