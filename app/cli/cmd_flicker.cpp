// gblens flicker SEQ --quantity Q [--reference N] [--no-reproject] [--json] [-o DIR]: per-pixel temporal
// statistics of a decoded quantity over a sequence, each frame carried to the reference frame's pixels
// by reprojection (views/analysis/temporal.h). Exit 0, or 2 on bad input.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/cli/cli.h"
#include "app/cli/messages.h"
#include "views/analysis/temporal.h"
#include "views/capture/exr.h"
#include "views/capture/image_io.h"

namespace gb {

namespace {
struct FlickerArgs {
  std::string sequence, quantity, output;
  int64_t reference = -1;
  bool noReproject = false, json = false;
};

int flickerFail(const std::string& message) {
  std::fprintf(stderr, "gblens flicker: %s\n", oneLine(message).c_str());
  return 2;
}
}  // namespace

Command addFlickerCommand(CLI::App& root) {
  auto o = std::make_shared<FlickerArgs>();
  CLI::App* cmd = root.add_subcommand(
      "flicker", "per-pixel temporal statistics of a quantity over a sequence (standard deviation, largest step), reprojected");
  cmd->add_option("SEQUENCE", o->sequence, "a sequence folder (capture --sequence, import --frames)")->required();
  cmd->add_option("--quantity", o->quantity, "the quantity (a view name of the layout: Normal, Roughness, ...)")->required();
  cmd->add_option("--reference", o->reference, "the frame every frame is carried to (default: the first)");
  cmd->add_flag("--no-reproject", o->noReproject, "compare the same pixel in every frame (a static camera)");
  cmd->add_option("-o,--output", o->output, "a folder for flicker.json and flicker.exr (standard deviation, largest step, frames seen)");
  cmd->add_flag("--json", o->json, "print the report as JSON");
  return {cmd, [o]() -> int {
            Sequence seq;
            std::string error;
            if (!loadSequence(o->sequence, seq, error)) return flickerFail(error);
            if (!o->output.empty() && !checkFolderDestination("-o", o->output, "flicker.json", "flicker report", error))
              return flickerFail(error);
            FlickerOptions fo;
            fo.quantity = o->quantity, fo.reference = o->reference, fo.reproject = !o->noReproject;
            fo.progress = terminalProgress();
            FlickerReport r;
            if (!flickerSequence(seq, fo, r, error)) return flickerFail(error);
            const nlohmann::json j = flickerReportJson(r);
            if (!o->output.empty()) {
              const bool ok = replaceDirectory(o->output, "flicker.json", "flicker report", [&](const std::string& tmp, std::string& e) {
                namespace fs = std::filesystem;
                return writeExr((fs::path(tmp) / "flicker_stddev.exr").string(), r.stddev, e) &&
                       writeExr((fs::path(tmp) / "flicker_max_step.exr").string(), r.maxStep, e) &&
                       writeExr((fs::path(tmp) / "flicker_seen.exr").string(), r.seen, e) &&
                       writeTextAtomically((fs::path(tmp) / "flicker.json").string(), j.dump(2) + "\n", e);
              }, error);
              if (!ok) return flickerFail(error);
            }
            if (o->json) {
              std::printf("%s\n", j.dump(2).c_str());
            } else {
              std::printf("sequence %s, %s over %zu frames (reference frame %lld)\n  standard deviation: mean %.6g, p99 %.6g\n"
                          "  largest step between consecutive frames: %.6g\n",
                          o->sequence.c_str(), r.quantity.c_str(), r.frames, (long long)r.reference, r.meanStddev, r.p99Stddev,
                          r.maxStepAll);
            }
            return 0;
          }};
}

}  // namespace gb
