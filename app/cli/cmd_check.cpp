// gblens check CAPTURE [--json] [--policy RULE]...: every target and quantity of a capture (gblens's own
// or imported) scanned for NaN, ±Inf, denormals and out-of-range decoded values, and positions rebuilt
// from depth checked against a stored position (views/analysis/check.h). What is a fault comes from the
// policy (default, the layout's "check" fields, --policy). Exit 0 no fault, 1 faults, 2 unreadable.
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
  std::vector<std::string> policy;
};
}  // namespace

Command addCheckCommand(CLI::App& root) {
  auto o = std::make_shared<CheckArgs>();
  CLI::App* cmd = root.add_subcommand(
      "check", "scan every target of a capture for NaN, Inf, denormals and out-of-range values (exit 1 when found)");
  cmd->add_option("CAPTURE", o->capture, "capture directory (gblens capture or gblens import)")->required();
  cmd->add_flag("--json", o->json, "print the report as JSON");
  cmd->add_option("--policy", o->policy,
                  "[QUANTITY.]CLASS=LEVEL: what a finding means (CLASS nan, inf, denormal, out_of_range, position; LEVEL "
                  "fault, warn, ignore); default: denormal=warn, the rest fault; the layout's \"check\" fields apply first")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  return {cmd, [o]() -> int {
            Capture c;
            std::string error;
            if (!loadCapture(o->capture, c, error)) {
              std::fprintf(stderr, "gblens check: %s\n", error.c_str());
              return 2;
            }
            CheckPolicy policy;
            if (!checkPolicy(c.frame.layout, o->policy, policy, error)) {
              std::fprintf(stderr, "gblens check: %s\n", error.c_str());
              return 2;
            }
            const CheckReport report = checkFrame(c.frame, policy);
            if (o->json)
              std::printf("%s\n", checkJson(report).dump(2).c_str());
            else
              std::printf("capture %s\n%s", o->capture.c_str(), checkText(report).c_str());
            return report.clean() ? 0 : 1;
          }};
}

}  // namespace gb
