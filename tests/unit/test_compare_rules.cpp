// Compare's rules in process: per-target thresholds, idiff's decision rule, the angular normal
// metric against a hand-computed case. The captures are written from synthetic frames.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "tests/support/capture_util.h"
#include "views/analysis/compare.h"

namespace gb {

namespace fs = std::filesystem;

static std::string write(const FrameSnapshot& f, const std::string& dir) {
  std::string error;
  EXPECT_TRUE(writeCapture(dir, f, CaptureMeta{}, error)) << error;
  return dir;
}

// The verdict of compareCaptures() (in process: fast) for thresholds given as CLI text.
static int verdict(const Capture& a, const Capture& b, const std::vector<std::pair<std::string, std::string>>& flags) {
  ThresholdSettings t;
  std::string error;
  for (auto& [param, value] : flags)
    if (!t.add(param, value, error)) return kCompareFileError;
  CompareReport report;
  if (!compareCaptures(a, b, t, report, error)) return kCompareFileError;
  return report.exitCode;
}

TEST(Compare, ThresholdsFollowIdiffGloballyAndPerTarget) {
  std::string root = freshDir("compare_thresholds");
  FrameSnapshot base = syntheticFrame(20, 10);
  // hdr changes by 0.01 at 3 of 200 pixels (1.5%).
  FrameSnapshot changed = base;
  for (uint32_t x : {2u, 7u, 11u}) setTexel(changed.target(Target::Hdr).image, x, 4, 0, 0.25 + (x + 0.5) / 20 + 0.01);
  Capture a, b;
  std::string message;
  ASSERT_TRUE(loadCapture(write(base, root + "/a"), a, message)) << message;
  ASSERT_TRUE(loadCapture(write(changed, root + "/b"), b, message)) << message;
  EXPECT_EQ(verdict(a, a, {}), kComparePass);
  EXPECT_EQ(verdict(a, b, {}), kCompareFail);  // idiff's defaults: 1e-6
  EXPECT_EQ(verdict(a, b, {{"fail", "0.02"}, {"warn", "0.005"}}), kCompareWarn);
  EXPECT_EQ(verdict(a, b, {{"fail", "0.02"}, {"warn", "0.005"}, {"warnpercent", "2"}}), kComparePass);
  EXPECT_EQ(verdict(a, b, {{"fail", "0.005"}}), kCompareFail);
  EXPECT_EQ(verdict(a, b, {{"fail", "0.005"}, {"failpercent", "2"}, {"warn", "1"}}), kComparePass);
  EXPECT_EQ(verdict(a, b, {{"fail", "0.005"}, {"failpercent", "2"}, {"hardfail", "0.008"}}), kCompareFail);
  // Per target: hdr may differ, every other target must stay exact; the most specific key wins.
  EXPECT_EQ(verdict(a, b, {{"fail", "hdr=0.02"}, {"warn", "hdr=0.02"}}), kComparePass);
  EXPECT_EQ(verdict(a, b, {{"fail", "final=0.02"}, {"warn", "final=0.02"}}), kCompareFail);
  EXPECT_EQ(verdict(a, b, {{"fail", "0"}, {"fail", "hdr=0.02"}, {"warn", "hdr=0.02"}}), kComparePass);
  EXPECT_EQ(verdict(a, b, {{"fail", "normal_shadow.Q=1"}}), kCompareFileError);  // no such group
  EXPECT_EQ(verdict(a, b, {{"fail", "nothing=1"}}), kCompareFileError);         // no such target
  EXPECT_EQ(verdict(a, b, {{"fail", "abc"}}), kCompareFileError);
}

}  // namespace gb
