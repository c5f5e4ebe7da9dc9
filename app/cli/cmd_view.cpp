// gblens view: the interactive viewer (app/viewer/*). Options beyond the common ones control
// the window and make runs reproducible for tests (--paused, --size, --probe-log, --event-log).
// SCENE may name a sequence (SEQ, SEQ@N: opened at frame N), shown as --capture SEQ is: with a timeline.
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "app/viewer/viewer.h"
#include "views/capture/sequence.h"
#include "views/ui/keys.h"

namespace gb {

Command addViewCommand(CLI::App& root) {
  auto a = std::make_shared<ViewerArgs>();
  auto common = std::make_shared<CommonOptions>();
  CLI::App* cmd = root.add_subcommand("view", "open the interactive viewer (needs a display)");
  addCommonOptions(cmd, *common);
  auto keys = std::make_shared<bool>(false);
  cmd->add_flag("--keys", *keys, "print the viewer's keys and mouse as a Markdown table (the README's) and exit");
  cmd->add_option("--window", a->window, "initial window size WxH (default: 85% of the monitor, at most 1920x1080)");
  cmd->add_flag("--paused", a->paused, "start with the animation paused (at --time)");
  addViewOption(cmd, "--view", a->initialView, "initial view");
  cmd->add_option("--probe-log", a->probeLog, "append each pixel dossier as one JSON line to FILE");
  cmd->add_option("--reference-error", a->referenceErrorDir,
                  "open the Reference error window, compute it for the first frame and write its maps into DIR "
                  "(the PNGs gblens error -o writes)");
  cmd->add_flag("--probe-reference", a->probeReference,
                "start with the Pixel panel's reference on: each probe of a live frame adds the ray-traced reference");
  cmd->add_option("--event-log", a->eventLog, "append viewer events (layout, probe latency, exit) as JSON lines to FILE");
  auto reduce = std::make_shared<std::string>("auto");
  cmd->add_option("--reduce-while-moving", *reduce,
                  "while input changes the frame render at 1/N of the size, full when it stops: auto (only where a full "
                  "frame is slower than the input budget), off, or N (2..8)")
      ->check(CLI::IsMember({"auto", "off", "2", "3", "4", "5", "6", "7", "8"}))
      ->capture_default_str();
  cmd->add_option("--capture", a->capture,
                  "open a capture directory instead of rendering (gblens capture -o DIR); a sequence SEQ or SEQ@N opens "
                  "with a timeline over its frames (as `gblens view SEQ` does)");
  cmd->add_option("--compare", a->compare, "with --capture A: compare with capture B (A, B, |A-B|, split, both dossiers)");
  return {cmd, [a, common, cmd, reduce, keys]() -> int {
            if (*keys) {
              std::fputs(keysMarkdown().c_str(), stdout);
              return 0;
            }
            std::string error;
            if (!finishCommonOptions(*common, error)) {
              std::fprintf(stderr, "gblens view: %s\n", error.c_str());
              return 2;
            }
            a->scene = common->scene;
            a->render = common->render;
            a->device = common->device;
            a->validate = common->validate;
            a->commandLine = commandLine();
            a->sizeGiven = cmd->get_option("--size")->count() > 0;
            a->windowGiven = cmd->get_option("--window")->count() > 0;
            a->reduceWhileMoving = *reduce == "auto" ? ViewerModel::kReduceAuto
                                   : *reduce == "off" ? ViewerModel::kReduceOff
                                                      : std::stoi(*reduce);
            // gblens view SEQ / SEQ@N: a sequence in place of the scene, opened as --capture opens one.
            if (a->capture.empty() && sequenceArgument(common->scene)) a->capture = a->scene;
            if (a->compare.empty() && sequenceArgument(a->capture)) {  // refused before a window opens
              Sequence s;
              std::string dir;
              if (isSequence(a->capture) ? !loadSequence(a->capture, s, error) : !resolveSequenceFrame(a->capture, dir, error)) {
                std::fprintf(stderr, "gblens view: %s\n", error.c_str());
                return 2;
              }
            }
            Scene scene;
            if (a->capture.empty() && !loadSceneOrReport(*common, scene)) return 2;
            return runViewer(*a, std::move(scene));
          }};
}

}  // namespace gb
