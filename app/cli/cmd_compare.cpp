// gblens compare A B [-o DIFFDIR] [--json REPORT] [--report DIR] [--junit FILE] [--fail ...]: compares
// two captures target by target (views/analysis/compare.h) with idiff's thresholds and exit codes, and
// FLIP of final and hdr; --pairs LIST compares many pairs into one report (views/report/report.h).
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>

#include "app/cli/cli.h"
#include "views/analysis/compare.h"
#include "views/capture/image_io.h"
#include "views/report/report.h"

namespace gb {

namespace {

// Two imports replayed on different drivers (or RenderDoc versions) may differ in texels the
// application never changed: said apart, not left for a user to find among the manifest fields.
void warnOfReplays(const CompareReport& report) {
  std::string fields;
  for (const nlohmann::json& d : report.differences)
    if (d["name"].get<std::string>().rfind("source.replay.", 0) == 0)
      fields += (fields.empty() ? "" : ", ") + d["name"].get<std::string>() + " " + d["a"].dump() + " in A, " + d["b"].dump() + " in B";
  if (!fields.empty())
    std::fprintf(stderr, "gblens compare: warning: the captures were replayed differently (%s): differences may come from "
                 "the replay drivers, not the application\n", fields.c_str());
}

struct CompareArgs {
  std::string a, b, diffDir, json, mask, report, junit, pairs, flip = "on";
  std::vector<std::string> fail, failPercent, hardFail, warn, warnPercent, failFlip, warnFlip, exclude;
  std::string flipPpd;
  bool quiet = false;
};

int usage(const std::string& error) {
  std::fprintf(stderr, "gblens compare: %s\n", error.c_str());
  return kCompareFileError;
}

// The flags as CompareSettings; false with one line naming the flag.
bool settingsFrom(const CompareArgs& o, CompareSettings& s, std::string& error) {
  for (auto& [param, values] : {std::pair{"fail", &o.fail}, {"failpercent", &o.failPercent}, {"hardfail", &o.hardFail},
                                {"warn", &o.warn}, {"warnpercent", &o.warnPercent}})
    for (const std::string& v : *values)
      if (!s.thresholds.add(param, v, error)) return false;
  for (auto& [flag, values] : {std::pair{"--fail-flip", &o.failFlip}, {"--warn-flip", &o.warnFlip}})
    for (const std::string& v : *values)
      if (!s.flip.add(flag, v, error)) return false;
  if (!o.flipPpd.empty()) {
    char* end = nullptr;
    s.flip.ppd = std::strtod(o.flipPpd.c_str(), &end);
    if (*end != '\0' || !(s.flip.ppd > 0.0) || !std::isfinite(s.flip.ppd)) {
      error = "--flip-ppd " + o.flipPpd + ": expected a positive number";
      return false;
    }
  }
  s.flipOn = o.flip == "on";
  s.mask = o.mask;
  s.exclude = o.exclude;
  if (!o.quiet)  // progress lines, as bench and stress print theirs
    s.progress = [](double done, const std::string& what) {
      std::fprintf(stderr, "gblens compare: %3.0f%% %s\n", 100.0 * done, what.c_str());
    };
  return true;
}

// Writes the summary (stdout, or stderr when the JSON goes to stdout) and the outputs asked for.
int finish(const CompareArgs& o, CompareReport& report) {
  std::string error;
  if (!o.diffDir.empty() && !writeCompareImages(report, o.diffDir, error)) return usage(error);
  std::string text = report.text();
  if (o.quiet) text = text.substr(text.rfind('\n', text.size() - 2) + 1);
  std::fputs(text.c_str(), o.json == "-" ? stderr : stdout);
  if (o.json == "-") {
    std::printf("%s\n", report.json().dump(2).c_str());
  } else if (!o.json.empty()) {
    if (!writeTextAtomically(o.json, report.json().dump(2) + "\n", error)) return usage("--json " + error);
  }
  return report.exitCode;
}

// Every destination, before any capture is loaded: a bad one is said at once, and nothing is written.
bool checkDestinations(const CompareArgs& o, std::string& error) {
  return (o.diffDir.empty() || checkFolderDestination("-o", o.diffDir, "", "", error)) &&
         (o.json.empty() || o.json == "-" || checkFileDestination("--json", o.json, error)) &&
         (o.report.empty() || checkFolderDestination("--report", o.report, "report.js", "compare report", error)) &&
         (o.junit.empty() || checkFileDestination("--junit", o.junit, error));
}

int runCompare(const CompareArgs& o) {
  std::string error;
  CompareSettings settings;
  if (!settingsFrom(o, settings, error) || !checkDestinations(o, error)) return usage(error);
  if (!o.report.empty()) removeDebrisOf("compare", o.report);
  if (!o.pairs.empty()) {
    if (!o.a.empty()) return usage("--pairs " + o.pairs + ": give either A B or --pairs, not both");
    if (o.report.empty() && o.junit.empty() && o.json.empty())
      return usage("--pairs " + o.pairs + ": needs --report DIR, --junit FILE or --json FILE to write the results to");
    PairsRun run;
    if (!comparePairs(o.pairs, settings, {o.report, o.junit, o.json}, run, error)) return usage(error);
    std::fputs(run.text.c_str(), run.json.empty() ? stdout : stderr);
    std::fputs(run.json.c_str(), stdout);
    return run.exitCode;
  }
  if (o.a.empty() || o.b.empty()) return usage("A B: two capture folders to compare (or --pairs LIST)");
  Capture a, b;
  for (auto [cap, dir] : {std::pair{&a, &o.a}, {&b, &o.b}})
    if (!loadCapture(*dir, *cap, error)) return usage(error);
  CompareReport report;
  if (!compare(a, b, settings, report, error)) return usage(error);
  warnOfReplays(report);
  const int status = finish(o, report);
  if (status == kCompareFileError) return status;
  if (!o.report.empty() && !writeReport(a, b, report, o.report, error)) return usage(error);
  if (!o.junit.empty() && !writeJunit({{"", &report}}, o.junit, error)) return usage(error);
  return status;
}
}  // namespace

Command addCompareCommand(CLI::App& root) {
  auto o = std::make_shared<CompareArgs>();
  CLI::App* cmd = root.add_subcommand(
      "compare",
      "compare two captures; exit 0 pass, 1 warn, 2 fail, 3 size/target mismatch, 4 file or usage error (as idiff)");
  cmd->add_option("A", o->a, "capture directory (reference)");
  cmd->add_option("B", o->b, "capture directory (test)");
  cmd->add_option("-o,--output", o->diffDir,
                  "directory for images: a heat map with legend per compared group, the FLIP maps, mask.png");
  cmd->add_option("--json", o->json, "write the report as JSON to this file ('-' for stdout)");
  cmd->add_option("--report", o->report,
                  "write a static HTML report to this directory (index.html; open it in a browser, no server)");
  cmd->add_option("--junit", o->junit, "write JUnit XML to this file (one test case per compared quantity)");
  cmd->add_option("--pairs", o->pairs,
                  "a file of pairs to compare, one 'A B [NAME]' a line (paths relative to the file; # comments): "
                  "one report for all");
  const char* keyHelp = " (VALUE for every target, or TARGET=VALUE / TARGET.GROUP=VALUE; repeatable)";
  cmd->add_option("--fail", o->fail, std::string("failure threshold, default 1e-6") + keyHelp);
  cmd->add_option("--failpercent", o->failPercent, std::string("allow this % of pixels over --fail, default 0") + keyHelp);
  cmd->add_option("--hardfail", o->hardFail, std::string("fail if any pixel is over this, default inf") + keyHelp);
  cmd->add_option("--warn", o->warn, std::string("warning threshold, default 1e-6") + keyHelp);
  cmd->add_option("--warnpercent", o->warnPercent, std::string("allow this % of pixels over --warn, default 0") + keyHelp);
  cmd->add_option("--fail-flip", o->failFlip,
                  "fail if the mean FLIP (LDR-FLIP of final, HDR-FLIP of hdr; 0 to 1) is over this (VALUE, or "
                  "final=VALUE / hdr=VALUE; repeatable); without it FLIP is reported only");
  cmd->add_option("--warn-flip", o->warnFlip, "warn if the mean FLIP is over this (as --fail-flip)");
  cmd->add_option("--flip-ppd", o->flipPpd,
                  "FLIP's observer: pixels per degree of visual angle (default 67: 0.7 m from a 0.7 m wide 3840-pixel "
                  "monitor)");
  cmd->add_option("--flip", o->flip, "FLIP of final and hdr: on | off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_flag("-q,--quiet", o->quiet, "print only the verdict line (no progress)");
  cmd->add_option("--mask", o->mask,
                  "pixels reported apart, not deciding pass/fail: silhouettes (primitive_id edges), penumbra (the "
                  "shadow band), or a mask image FILE (non-zero = masked); comma-separated");
  cmd->add_option("--exclude", o->exclude, "leave this target out (listed as skipped); repeatable");
  Command c{cmd, [o]() -> int { return runCompare(*o); }};
  c.usageExit = kCompareFileError;
  return c;
}

}  // namespace gb
