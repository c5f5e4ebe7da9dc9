// gblens compare A B [-o DIFFDIR] [--json REPORT] [--fail ...]: compares two captures target by
// target (views/compare.h) with idiff's thresholds and exit codes, and FLIP of final and hdr.
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <memory>

#include "app/cli/cli.h"
#include "views/analysis/compare.h"

namespace gb {

namespace {

// Two imports replayed on different drivers (or RenderDoc versions) may differ in texels the
// application never changed: said before the figures, not after a user has chased them.
std::string replayDriverWarning(const Capture& a, const Capture& b) {
  auto replay = [](const Capture& c) -> nlohmann::json {
    if (!c.manifest.contains("source") || !c.manifest["source"].is_object()) return nullptr;
    const nlohmann::json& r = c.manifest["source"].value("replay", nlohmann::json());
    return r.is_object() ? r : nlohmann::json();
  };
  const nlohmann::json ra = replay(a), rb = replay(b);
  if (ra.is_null() || rb.is_null()) return "";
  auto text = [](const nlohmann::json& r) {
    return r.value("device", std::string("?")) + " (RenderDoc " + r.value("renderdoc", std::string("?")) + ")";
  };
  if (ra.value("device", "") == rb.value("device", "") && ra.value("renderdoc", "") == rb.value("renderdoc", "")) return "";
  return a.dir + " was replayed on " + text(ra) + ", " + b.dir + " on " + text(rb) +
         ": differences may come from the replay drivers, not the application";
}

}  // namespace

namespace {
struct CompareArgs {
  std::string a, b, diffDir, json, mask;
  std::vector<std::string> fail, failPercent, hardFail, warn, warnPercent, failFlip, warnFlip;
  std::string flipPpd;
  bool quiet = false;
};
}  // namespace

Command addCompareCommand(CLI::App& root) {
  auto o = std::make_shared<CompareArgs>();
  CLI::App* cmd = root.add_subcommand(
      "compare",
      "compare two captures; exit 0 pass, 1 warn, 2 fail, 3 size/target mismatch, 4 file or usage error (as idiff)");
  cmd->add_option("A", o->a, "capture directory (reference)")->required();
  cmd->add_option("B", o->b, "capture directory (test)")->required();
  cmd->add_option("-o,--output", o->diffDir, "directory for difference heat maps (one PNG per differing group)");
  cmd->add_option("--json", o->json, "write the report as JSON to this file ('-' for stdout)");
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
  cmd->add_flag("-q,--quiet", o->quiet, "print only the verdict line");
  cmd->add_option("--mask", o->mask,
                  "pixels reported apart, not deciding pass/fail: silhouettes (primitive_id edges), penumbra (the "
                  "shadow band), or a mask image FILE (non-zero = masked); comma-separated");
  Command c{cmd, [o]() -> int {
              std::string error;
              ThresholdSettings settings;
              for (auto& [param, values] : {std::pair{"fail", &o->fail}, {"failpercent", &o->failPercent},
                                            {"hardfail", &o->hardFail}, {"warn", &o->warn},
                                            {"warnpercent", &o->warnPercent}})
                for (const std::string& v : *values)
                  if (!settings.add(param, v, error)) {
                    std::fprintf(stderr, "gblens compare: %s\n", error.c_str());
                    return kCompareFileError;
                  }
              FlipSettings flip;
              for (auto& [flag, values] : {std::pair{"--fail-flip", &o->failFlip}, {"--warn-flip", &o->warnFlip}})
                for (const std::string& v : *values)
                  if (!flip.add(flag, v, error)) {
                    std::fprintf(stderr, "gblens compare: %s\n", error.c_str());
                    return kCompareFileError;
                  }
              if (!o->flipPpd.empty()) {
                char* end = nullptr;
                flip.ppd = std::strtod(o->flipPpd.c_str(), &end);
                if (*end != '\0' || !(flip.ppd > 0.0) || !std::isfinite(flip.ppd)) {
                  std::fprintf(stderr, "gblens compare: --flip-ppd %s: expected a positive number\n", o->flipPpd.c_str());
                  return kCompareFileError;
                }
              }
              Capture a, b;
              for (auto [cap, dir] : {std::pair{&a, &o->a}, {&b, &o->b}}) {
                CaptureProblem problem;
                if (!loadCapture(*dir, *cap, error, &problem)) {
                  std::fprintf(stderr, "gblens compare: %s\n", error.c_str());
                  return kCompareFileError;
                }
              }
              const std::string drivers = replayDriverWarning(a, b);
              if (!drivers.empty()) std::fprintf(stderr, "gblens compare: warning: %s\n", drivers.c_str());
              CompareReport report;
              if (!compareCaptures(a, b, settings, report, error)) {
                std::fprintf(stderr, "gblens compare: %s\n", error.c_str());
                return kCompareFileError;
              }
              compareFlip(a, b, flip, report);
              if (!o->mask.empty()) {
                CompareMask mask;
                if (!buildCompareMask(a, b, o->mask, mask, error)) {
                  std::fprintf(stderr, "gblens compare: %s\n", error.c_str());
                  return kCompareFileError;
                }
                applyCompareMask(report, mask);
              }
              if (!o->diffDir.empty() && !writeHeatmaps(report, o->diffDir, error)) {
                std::fprintf(stderr, "gblens compare: %s\n", error.c_str());
                return kCompareFileError;
              }
              std::string text = report.text();
              if (o->quiet) text = text.substr(text.rfind('\n', text.size() - 2) + 1);
              std::fputs(text.c_str(), o->json == "-" ? stderr : stdout);
              if (o->json == "-") {
                std::printf("%s\n", report.json().dump(2).c_str());
              } else if (!o->json.empty()) {
                std::ofstream out(o->json);
                out << report.json().dump(2) << "\n";
                if (!out) {
                  std::fprintf(stderr, "gblens compare: %s: cannot write\n", o->json.c_str());
                  return kCompareFileError;
                }
              }
              return report.exitCode;
            }};
  c.usageExit = kCompareFileError;
  return c;
}

}  // namespace gb
