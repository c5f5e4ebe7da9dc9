// gblens decompose reports its progress on stderr as bench and stress do: lines "gblens decompose:
// N% (K of H rows, S s)" whose percentages rise in tenths and whose last line counts every row of the
// capture (its height, known from the capture command), stdout keeping the one line it had.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cstdio>
#include <sstream>

#include "tests/support/capture_util.h"

namespace gb {
namespace {

TEST(DecomposeProgress, StderrLinesRiseInTenthsToEveryRowOfTheCapture) {
  const std::string dir = freshDir("decompose-progress");
  RunResult c = runGblens("capture builtin:temple --size 96x54 --time 1.5 -o '" + dir + "/capture'");
  ASSERT_EQ(c.exitCode, 0) << c.output;
  // stderr into a file of its own (runShell adds 2>&1 outside the parentheses).
  RunResult r = runShell("('" + std::string(GBLENS_BINARY) + "' decompose '" + dir + "/capture' -o '" + dir + "/out' 2>'" +
                         dir + "/stderr.txt')");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_NE(r.output.find("wrote"), std::string::npos) << r.output;
  EXPECT_EQ(r.output.find('%'), std::string::npos) << "progress belongs on stderr: " << r.output;
  std::istringstream err(readText(dir + "/stderr.txt"));
  std::string line;
  int last = -1, lines = 0;
  unsigned long long done = 0, rows = 0;
  while (std::getline(err, line)) {
    int percent = -1;
    double seconds = 0.0;
    if (std::sscanf(line.c_str(), "gblens decompose: %d%% (%llu of %llu rows, %lf s)", &percent, &done, &rows, &seconds) != 4)
      continue;
    ++lines;
    EXPECT_GT(percent, last) << line;
    EXPECT_EQ(percent % 10, 0) << line;
    EXPECT_LE(percent, int(100 * done / rows)) << "the percentage overstates the rows done: " << line;
    last = percent;
  }
  EXPECT_GE(lines, 1);
  EXPECT_EQ(last, 100);
  EXPECT_EQ(rows, 54u);  // the capture's height
  EXPECT_EQ(done, 54u);
}

}  // namespace
}  // namespace gb
