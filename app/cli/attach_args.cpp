// gblens attach's flags and their checks (see attach_args.h).
#include "app/cli/attach_args.h"

#include <cmath>

#include "app/cli/params.h"
#include "views/capture/sequence.h"

namespace gb {

void addAttachOptions(CLI::App* cmd, AttachOptions& o) {
  cmd->add_option("--layout", o.layout, "what the G-buffer holds and where (a layout file with live sources, or builtin:NAME)");
  cmd->add_option("--param", o.params, "NAME=VALUE: an option value for a parameterised layout (e.g. normal_format=oct-rg16)")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--capture-frame", o.captureFrame, "write the application's frame N (0: its first) as a capture, then detach")
      ->check(CLI::Range(int64_t(0), int64_t(1) << 40));
  cmd->add_option("--capture-frames", o.captureFrames,
                  "A..B: write the application's frames A to B, every one, as a sequence (docs/temporal.md), then detach");
  cmd->add_option("-o,--output", o.output,
                  "the capture folder --capture-frame writes, the sequence folder --capture-frames writes (atomically); "
                  "--suggest: the draft layout's file");
  cmd->add_option("--frames", o.frames, "receive and decode K streamed frames, write nothing (with --stats: the costs)")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
  cmd->add_option("--history", o.history,
                  "keep the stream's last K decoded frames (the viewer, --frames; at most K frames' bytes; 0: none)")
      ->check(CLI::Range(size_t(0), size_t(10000)))
      ->capture_default_str();
  cmd->add_option("--every", o.every, "stream every Nth frame of the application")->check(CLI::Range(1u, 100000u))->capture_default_str();
  cmd->add_flag("--suggest", o.suggest,
                "without --layout: draft a layout from the render passes and texels the layer sees and stream under it "
                "(the viewer; -o or no display: write the draft); with --layout: show the passes beside the stream");
  cmd->add_flag("--keep-running", o.keepRunning,
                "--suggest -o: let the application run on once the draft is written (default: it is ended)");
  cmd->add_flag("--stats", o.stats, "print the layer's costs (frame time, memory, drops, latency) as JSON");
  cmd->add_option("--timeout", o.timeout, "give up when no frame came within this many seconds")->capture_default_str();
  cmd->add_option("--window", o.window, "the viewer's window size WxH")->capture_default_str();
  cmd->add_option("--event-log", o.eventLog, "the viewer: append its events (frames received, layout, hover, capture) as JSON lines");
  cmd->add_option("--probe-log", o.probeLog, "the viewer: append each pixel dossier (a click) as one JSON line to FILE");
  cmd->add_flag("--paused", o.paused, "the viewer: start paused on the first frame (Space resumes)");
  cmd->add_option("--pace", o.pace,
                  "on: the application copies a frame only when gblens asks for it (the viewer: timed to come when it "
                  "will show it; --frames: once the one before is decoded); off: every frame gblens can take (default: on "
                  "for the viewer without --history, off for --frames)")
      ->check(CLI::IsMember({"on", "off"}));
  cmd->add_option("APP", o.app, "the application and its arguments (after --)")->required();
}

bool checkAttachOptions(const AttachOptions& o, LiveOptions& lo, std::string& error) {
  const bool draft = o.suggest && o.layout.empty();  // --suggest drafting the layout
  const bool viewer = !o.capturing() && !o.frames && !draft;
  auto refuse = [&](const std::string& why) {
    error = why;
    return false;
  };
  if (viewer && o.layout.empty())
    return refuse("--layout: required for the viewer (a layout file, docs/layout-format.md, or builtin:NAME), or --suggest "
                  "to draft one");
  if (!viewer && !(draft && o.output.empty()) && (!o.eventLog.empty() || !o.probeLog.empty() || o.paused))
    return refuse("--event-log, --probe-log and --paused are the viewer's");
  const std::string captureFlag = o.sequence() ? "--capture-frames" : "--capture-frame";
  if (draft && (o.capturing() || o.frames))
    return refuse("--suggest: drafts a layout; " + captureFlag + " and --frames need --layout");
  if (o.sequence() && o.captureFrame >= 0)
    return refuse("--capture-frames: one frame is --capture-frames N, not with --capture-frame");
  if (o.sequence() && o.frames) return refuse("--frames: receives frames and writes nothing; --capture-frames writes them");
  int64_t first = o.captureFrame, last = -1;
  if (o.sequence() && !parseFrameRange(o.captureFrames, "--capture-frames", first, last, error)) return false;
  if (o.sequence() && first < 0)
    return refuse("--capture-frames " + o.captureFrames + ": the application's frames count from 0");
  if (o.capturing() && o.output.empty())
    return refuse("-o: required with " + captureFlag + " (the " + (o.sequence() ? "sequence" : "capture") + " folder to write)");
  if (!o.capturing() && !draft && !o.output.empty())
    return refuse("-o: writes the frame --capture-frame names, the frames --capture-frames names, or the layout --suggest "
                  "drafts");
  if (o.history && (o.capturing() || draft))
    return refuse("--history: keeps the last frames of the viewer's stream or of --frames; " +
                  (draft ? std::string("--suggest drafts a layout") : captureFlag + " writes its frames"));
  if ((o.capturing() || o.frames) && o.layout.empty())
    return refuse("--layout: required (a layout file, docs/layout-format.md, or builtin:NAME)");
  if (o.keepRunning && !(draft && !o.output.empty())) return refuse("--keep-running: goes with --suggest -o");
  if (o.capturing() && o.every != 1)
    return refuse("--every: " + captureFlag + (o.sequence() ? " names consecutive frames" : " names one frame") +
                  " of the application");
  if (!(o.timeout > 0.0) || !std::isfinite(o.timeout)) return refuse("--timeout: expected a positive number of seconds");
  if (!o.pace.empty() && (o.capturing() || (draft && !o.output.empty())))
    return refuse("--pace: paces the viewer's stream or --frames; " +
                  (o.capturing() ? captureFlag + " takes the frames it names" : std::string("--suggest -o drafts from one frame")));
  lo = LiveOptions{};
  lo.paced = o.pace.empty() ? (viewer || (draft && o.output.empty())) && !o.history : o.pace == "on";
  lo.layout = o.layout;
  lo.argv = o.app;
  lo.every = o.every;
  lo.captureFrame = first;
  lo.captureLast = o.sequence() ? last : -1;
  lo.history = o.history;
  lo.suggest = o.suggest;
  return parseLayoutParameters(o.params, lo.options, error, &lo.given);
}

}  // namespace gb
