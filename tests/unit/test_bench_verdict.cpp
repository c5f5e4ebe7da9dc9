// The bench's defaults decision: the A/B's confidence interval of the median ratio (order
// statistics, coverage from the binomial distribution, checked against hand-computed values), and
// dominance decided from that interval, never from single medians.
#include <gtest/gtest.h>

#include <cmath>

#include "app/bench/bench_report.h"

namespace gb {

TEST(BenchVerdict, MedianIntervalFromOrderStatistics) {
  // 12 pairs: P(B(12, 1/2) <= 2) = (1 + 12 + 66) / 4096, so [r(3), r(10)] covers 1 - 2 * 79/4096.
  std::vector<double> r = {1.12, 0.91, 1.03, 0.97, 1.30, 0.88, 1.01, 0.99, 1.05, 0.95, 1.08, 0.93};
  AbResult ab = abStatistics(r);
  EXPECT_EQ(ab.pairs(), 12);
  EXPECT_DOUBLE_EQ(ab.ciLow, 0.93);   // sorted: .88 .91 .93 .95 .97 .99 1.01 1.03 1.05 1.08 1.12 1.30
  EXPECT_DOUBLE_EQ(ab.ciHigh, 1.08);
  EXPECT_NEAR(ab.confidence, 1.0 - 2.0 * 79.0 / 4096.0, 1e-12);
  EXPECT_DOUBLE_EQ(ab.median, 1.0);
  // 20 pairs: P(B <= 5) = 21700 / 2^20 = 0.0207, P(B <= 6) = 0.0577: [r(6), r(15)].
  std::vector<double> s;
  for (int i = 1; i <= 20; ++i) s.push_back(i);
  AbResult ab20 = abStatistics(s);
  EXPECT_DOUBLE_EQ(ab20.ciLow, 6.0);
  EXPECT_DOUBLE_EQ(ab20.ciHigh, 15.0);
  EXPECT_NEAR(ab20.confidence, 1.0 - 2.0 * 21700.0 / 1048576.0, 1e-12);
  // 6 pairs: only the whole range, 1 - 2/64.
  AbResult ab6 = abStatistics({1, 2, 3, 4, 5, 6});
  EXPECT_DOUBLE_EQ(ab6.ciLow, 1.0);
  EXPECT_DOUBLE_EQ(ab6.ciHigh, 6.0);
  EXPECT_NEAR(ab6.confidence, 1.0 - 2.0 / 64.0, 1e-12);
}

TEST(BenchVerdict, TimeVerdictFollowsTheInterval) {
  AbResult ab;
  ab.ratios = {1.0};
  ab.ciLow = 0.90, ab.ciHigh = 0.98;
  EXPECT_EQ(abVerdict(ab, 0.05), "faster");
  ab.ciLow = 1.01, ab.ciHigh = 1.2;
  EXPECT_EQ(abVerdict(ab, 0.05), "slower");
  ab.ciLow = 0.97, ab.ciHigh = 1.04;
  EXPECT_EQ(abVerdict(ab, 0.05), "same within 5%");
  ab.ciLow = 0.9, ab.ciHigh = 1.1;
  EXPECT_EQ(abVerdict(ab, 0.05), "undecided");
}

namespace {
BenchRow row(const std::string& name, const std::string& group, double normal, std::vector<double> ratios) {
  BenchRow r;
  r.scene = "s";
  r.name = name;
  r.group = group;
  r.measured = true;
  r.error = {{"normal_deg_mean", normal}, {"position_rel_mean", 1e-7}, {"hdr_rel_mean", 0.02}};
  if (!ratios.empty()) r.ab = abStatistics(ratios);
  return r;
}
}  // namespace

// Lower error with a time that is not shown slower dominates; a faster median whose interval
// reaches above 1 does not (noise); lower error with an interval reaching past 1.05 is undecided.
TEST(BenchVerdict, DominanceNeedsTheIntervalNotTheMedian) {
  const std::vector<double> same = {0.97, 0.99, 1.0, 1.01, 1.02, 0.98, 1.0, 1.01, 0.99, 1.0, 1.02, 0.98};
  const std::vector<double> noisyFast = {0.70, 0.8, 0.85, 0.9, 0.92, 0.95, 1.1, 1.2, 1.25, 1.3, 0.75, 0.88};
  const std::vector<double> wide = {0.8, 0.9, 0.95, 1.0, 1.05, 1.1, 1.15, 1.2, 0.85, 1.0, 1.1, 0.9};
  std::vector<BenchRow> rows = {row("default", "default", 0.01, {}), row("better_same_time", "normal", 0.001, same),
                                row("same_error_noisy_fast", "normal", 0.01, noisyFast),
                                row("better_wide_time", "normal", 0.001, wide)};
  std::vector<DefaultsCheck> c = checkDefaults(rows, BenchTolerances{});
  ASSERT_EQ(c.size(), 1u);
  EXPECT_FALSE(c[0].onFrontier);
  EXPECT_EQ(c[0].dominatedBy, std::vector<std::string>{"better_same_time"});
  EXPECT_EQ(c[0].undecided, std::vector<std::string>{"better_wide_time"});
}

}  // namespace gb
