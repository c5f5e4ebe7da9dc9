// gblens stress as CI meets it (the suite itself runs as the CTest entry stress.quick): mistakes
// exit 2, one case runs alone and writes its table as JSON; and the frame-fit check that keeps an
// output the device cannot hold from reaching an allocation.
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "renderer/frame_memory.h"
#include "tests/gpu_test.h"

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

class FrameFit : public GpuTest {};

TEST_F(FrameFit, RefusesWhatTheDeviceCannotHoldAndNamesSize) {
  Scene s = floorScene();
  RenderOptions o;
  o.width = 640;
  o.height = 480;
  EXPECT_EQ(frameTooLarge(ctx(), s, o), "");
  // The estimate: at least colour + depth targets of the size (a lower bound computed by hand:
  // albedo 4 + normal 4 + eye depth 4 + depth/stencil 5 + hdr 16 + final 4 bytes per pixel).
  EXPECT_GE(frameMemory(ctx(), s, o).targets, uint64_t(640) * 480 * 37);
  GpuContext small = ctx();  // a copy with a small heap and a small dimension limit
  small.isCpu = false;       // (a CPU device is bounded by system memory instead)
  small.memory.memoryHeapCount = 1;
  small.memory.memoryHeaps[0].size = 4ull << 20;  // the frame needs ~11 MiB
  std::string why = frameTooLarge(small, s, o);
  EXPECT_NE(why.find("--size 640x480"), std::string::npos) << why;
  EXPECT_NE(why.find("GiB"), std::string::npos) << why;
  small.properties.limits.maxImageDimension2D = 512;
  why = frameTooLarge(small, s, o);
  EXPECT_NE(why.find("at most 512"), std::string::npos) << why;
}

}  // namespace gb
