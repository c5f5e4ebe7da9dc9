// gblens stats CAPTURE --rect X,Y,W,H [--target T] [--json]: statistics of a rectangle of a capture
// (gblens's own or imported), per stored channel and per decoded quantity (views/analysis/region_stats.h).
// Exit 0, or 2 when the capture cannot be read or a flag does not fit it.
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "views/analysis/region_stats.h"
#include "views/capture/capture.h"

namespace gb {

namespace {
struct StatsArgs {
  std::string capture, rect, target;
  int bins = 32;
  bool json = false;
};
}  // namespace

Command addStatsCommand(CLI::App& root) {
  auto o = std::make_shared<StatsArgs>();
  CLI::App* cmd = root.add_subcommand(
      "stats", "statistics of a rectangle of a capture: per channel and per decoded quantity, with histograms");
  cmd->add_option("CAPTURE", o->capture, "capture directory (gblens capture or gblens import)")->required();
  cmd->add_option("--rect", o->rect, "X,Y,W,H in frame pixels (top-left origin)")->required();
  cmd->add_option("--target", o->target, "only this target (the layout's name; default every one)");
  cmd->add_option("--bins", o->bins, "histogram bins")->check(CLI::Range(1, 1024));
  cmd->add_flag("--json", o->json, "print the statistics as JSON");
  return {cmd, [o]() -> int {
            Capture c;
            std::string error;
            if (!loadCapture(o->capture, c, error)) {
              std::fprintf(stderr, "gblens stats: %s\n", error.c_str());
              return 2;
            }
            RegionRect rect;
            if (!parseRegionRect(o->rect, c.frame.camera.width, c.frame.camera.height, rect, error)) {
              std::fprintf(stderr, "gblens stats: --rect %s\n", error.c_str());
              return 2;
            }
            if (!o->target.empty() && c.frame.layout.findTarget(o->target) < 0) {
              std::string names;
              for (const LayoutTarget& t : c.frame.layout.targets) names += (names.empty() ? "" : ", ") + t.name;
              std::fprintf(stderr, "gblens stats: --target %s: not a target of this capture (targets: %s)\n",
                           o->target.c_str(), names.c_str());
              return 2;
            }
            const RegionStats s = regionStats(c.frame, rect, o->target, o->bins);
            if (o->json)
              std::printf("%s\n", regionStatsJson(s).dump(2).c_str());
            else
              std::printf("capture %s\n%s", o->capture.c_str(), regionStatsText(s).c_str());
            return 0;
          }};
}

}  // namespace gb
