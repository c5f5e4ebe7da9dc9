// gblens probe CAPTURE X Y [--json]: the pixel dossier (views/probe.h) from a capture's files.
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "views/analysis/probe.h"
#include "views/capture/capture.h"

namespace gb {

namespace {
struct ProbeArgs {
  std::string capture;
  uint32_t x = 0, y = 0;
  bool json = false;
};
}  // namespace

Command addProbeCommand(CLI::App& root) {
  auto o = std::make_shared<ProbeArgs>();
  CLI::App* cmd = root.add_subcommand("probe", "print everything about one pixel of a capture");
  cmd->add_option("CAPTURE", o->capture, "capture directory")->required();
  cmd->add_option("X", o->x, "pixel column (0 = left)")->required();
  cmd->add_option("Y", o->y, "pixel row (0 = top)")->required();
  cmd->add_flag("--json", o->json, "print the dossier as JSON");
  return {cmd, [o]() -> int {
            Capture c;
            std::string error;
            if (!loadCapture(o->capture, c, error)) {
              std::fprintf(stderr, "gblens probe: %s\n", error.c_str());
              return 2;
            }
            PixelDossier d = probePixel(c.frame, o->x, o->y);
            if (!d.error.empty()) {
              std::fprintf(stderr, "gblens probe: %s\n", d.error.c_str());
              return 2;
            }
            if (o->json)
              std::printf("%s\n", dossierJson(d).dump(2).c_str());
            else
              std::fputs(dossierText(d).c_str(), stdout);
            return 0;
          }};
}

}  // namespace gb
