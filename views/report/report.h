// The compare report a reviewer opens: a static, self-contained HTML page (no server, no network;
// its script and style inside index.html, images and data files beside it) with the summary table,
// per quantity A, B, |A-B|, the heat map and FLIP map side by side, as a swipe or flipped on a key,
// a hover readout of both sides' stored and decoded values, and the manifests' differing fields;
// JUnit XML for CI; many pairs at once under one index page (docs/report.md).
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "views/analysis/compare.h"
#include "views/capture/capture.h"

namespace gb {

// Writes the report of `report` (compare() of a and b) into `dir`, atomically: a folder beside it,
// renamed into place; an existing report there is replaced, any other non-empty folder refused.
bool writeReport(const Capture& a, const Capture& b, const CompareReport& report, const std::string& dir,
                 std::string& error);

// JUnit XML: one <testsuite> per report (named by its string, "" : "gblens compare"), one <testcase>
// per compared group and FLIP entry (a failing one carries <failure>), a mismatched target a failing
// test case, a skipped one <skipped/>. Written atomically.
using NamedReport = std::pair<std::string, const CompareReport*>;
std::string junitXml(const std::vector<NamedReport>& reports);
bool writeJunit(const std::vector<NamedReport>& reports, const std::string& file, std::string& error);

// `gblens compare --pairs LIST`: each line "A B [NAME]" (paths relative to LIST's folder; '#' starts a
// comment), compared with the same settings. `report`: one page per pair under DIR/NAME and an index
// page DIR/index.html; `junit`, `json`: one file for all pairs. A pair whose captures cannot be
// loaded is listed with its error (exit 4 at the end); the exit code is the worst pair's.
struct PairsOutputs {
  std::string report, junit, json;
};
struct PairsRun {
  int exitCode = 0;
  std::string text;  // one line per pair
  std::string json;  // the JSON when `json` is "-" (for stdout)
};
bool comparePairs(const std::string& list, const CompareSettings& settings, const PairsOutputs& outputs, PairsRun& run,
                  std::string& error);

}  // namespace gb
