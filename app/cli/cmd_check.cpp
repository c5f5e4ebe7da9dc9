// gblens check CAPTURE [--json]: every target and quantity of a capture (gblens's own or imported)
// scanned for NaN, ±Inf, denormals and out-of-range decoded values (views/analysis/check.h).
// Exit 0 clean, 1 when anything was found, 2 when the capture cannot be read.
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "views/analysis/check.h"
#include "views/capture/capture.h"

namespace gb {

namespace {
struct CheckArgs {
  std::string capture;
  bool json = false;
};
}  // namespace

Command addCheckCommand(CLI::App& root) {
  auto o = std::make_shared<CheckArgs>();
  CLI::App* cmd = root.add_subcommand(
      "check", "scan every target of a capture for NaN, Inf, denormals and out-of-range values (exit 1 when found)");
  cmd->add_option("CAPTURE", o->capture, "capture directory (gblens capture or gblens import)")->required();
  cmd->add_flag("--json", o->json, "print the report as JSON");
  return {cmd, [o]() -> int {
            Capture c;
            std::string error;
            if (!loadCapture(o->capture, c, error)) {
              std::fprintf(stderr, "gblens check: %s\n", error.c_str());
              return 2;
            }
            const CheckReport report = checkFrame(c.frame);
            if (o->json)
              std::printf("%s\n", checkJson(report).dump(2).c_str());
            else
              std::printf("capture %s\n%s", o->capture.c_str(), checkText(report).c_str());
            return report.clean() ? 0 : 1;
          }};
}

}  // namespace gb
