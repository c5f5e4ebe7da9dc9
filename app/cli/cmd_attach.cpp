// gblens attach: another running Vulkan application's G-buffer, streamed by the gblens layer.
//   gblens attach --layout L.json --capture-frame N -o DIR [--stats] -- APP ARGS...
//   gblens attach --layout L.json --capture-frames A..B -o DIR [--stats] -- APP ARGS...   (a sequence)
//   gblens attach --layout L.json --frames K [--every E] [--history K] [--stats] -- APP ARGS...
//   gblens attach --suggest [-o DRAFT.json] -- APP ARGS...   (the viewer on a drafted layout, or the draft)
//   gblens attach --layout L.json [--suggest] [--every E] [--history K] -- APP ARGS...   (the viewer)
// Headless, the application is started with the layer, runs to its own end (the layer detaches), and
// the command exits 0 when it got what it was asked for, 2 when nothing matched the layout (with why).
// With a layout and none of --capture-frame(s), --frames: the viewer opens on the stream's first frame;
// closing it detaches and the application runs on. --suggest without a layout drafts one from what
// the application draws (views/infer/live_suggest.cpp) and streams under it. docs/attach.md.
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <memory>
#include <type_traits>

#include "app/cli/attach_args.h"
#include "app/cli/attach_sequence.h"
#include "app/cli/cli.h"
#include "app/cli/messages.h"
#include "app/viewer/viewer.h"
#include "views/capture/capture.h"
#include "views/capture/image_io.h"
#include "views/live/live.h"
#include "views/infer/suggest_live.h"

namespace gb {

namespace {

int attachFail(const std::string& message) {
  std::fprintf(stderr, "gblens attach: %s\n", oneLine(message).c_str());
  return 2;
}

void printReports(LiveSession& s) {
  for (const std::string& r : s.takeReports()) std::fprintf(stderr, "gblens attach: %s\n", r.c_str());
}

// A field of what the layer sent, or `fallback`: the hello is null when the application never made a
// device under the layer (/bin/true), the layer's figures null before its first frame (killed early).
template <class T>
T field(const nlohmann::json& j, const char* key, T fallback) {
  if (!j.is_object() || !j.contains(key)) return fallback;
  const nlohmann::json& v = j[key];
  if constexpr (std::is_same_v<T, std::string>) return v.is_string() ? v.get<std::string>() : fallback;
  else return v.is_number() ? v.get<T>() : fallback;
}

// --history K: the frames kept (the application's numbers, oldest first) and their bytes; null without it.
nlohmann::json historyJson(const FrameHistory& h) {
  if (h.limit() == 0) return nullptr;
  nlohmann::json frames = nlohmann::json::array(), bytes = nlohmann::json::array();
  for (const HistoryFrame& f : h.frames()) frames.push_back(f.appFrame), bytes.push_back(f.bytes);
  return {{"limit", h.limit()}, {"app_frames", frames}, {"frame_bytes", bytes}, {"bytes", h.bytes()}};
}

nlohmann::json statsJson(const LiveSession& s) {
  const LiveCounts& c = s.counts();
  const double frameMs = field(c.layer, "frame_ms", 0.0);
  return {{"application", s.hello().is_object() ? nlohmann::json(field(s.hello(), "application", std::string())) : nullptr},
          {"device", s.hello().is_object() ? nlohmann::json(field(s.hello(), "device", std::string())) : nullptr},
          {"received", c.received},
          {"undecodable", c.undecodable},
          {"dropped", c.dropped},
          {"not_asked", c.notAsked},
          {"application_frames", c.appFrames},
          {"latency_ms", {{"mean", c.meanLatencyMs}, {"max", c.maxLatencyMs}}},
          {"decode_ms", c.meanDecodeMs},
          {"copies_done_ms", c.meanReadyMs},
          {"overwritten", c.overwritten},
          {"latency_frames", frameMs > 0.0 ? c.meanLatencyMs / frameMs : 0.0},
          {"layer", c.layer},
          {"history", historyJson(s.history())}};
}

int writeFrame(const AttachOptions& o, const LiveSession& s, const FrameSnapshot& frame, const LiveFrameInfo& info) {
  const CaptureMeta meta = attachMeta(o, s, info.appFrame);
  std::string error;
  if (!writeCapture(o.output, frame, meta, error)) return attachFail(error);
  std::printf("attached to %s (%s): wrote application frame %llu (streamed frame %llu) with layout %s into %s\n",
              field(s.hello(), "application", std::string("?")).c_str(), meta.device.c_str(), (unsigned long long)info.appFrame,
              (unsigned long long)info.stream, o.layout.c_str(), o.output.c_str());
  std::fputs(attachTargetsText(frame, info).c_str(), stdout);
  return 0;
}

// The viewer on the stream: the window opens on the first frame (nothing to show before it; with
// `suggested`, its first frame came already); closing it detaches, and the application runs on.
int runViewerOnStream(const AttachOptions& o, LiveSession& s, const LiveSuggestion* suggested = nullptr) {
  FrameSnapshot first;
  LiveFrameInfo info;
  if (suggested) first = suggested->frame, info = suggested->info;
  else std::fprintf(stderr, "gblens attach: waiting for the first frame of %s\n", o.app[0].c_str());
  const auto start = std::chrono::steady_clock::now();
  std::string why;
  while (!suggested && !s.wait(first, 0.2, &info)) {
    printReports(s);
    if (s.noMatch())
      why = "nothing matched the layout in the application's first frames (the layer's reports above say why)";
    else if (!s.running() && !s.attached())
      why = s.hello().is_null() ? "the application ended without creating a Vulkan device under the layer"
                                : "the application ended before a frame matched the layout";
    else if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > o.timeout)
      why = "--timeout " + std::to_string(int(o.timeout)) + " s: no frame came";
    if (!why.empty()) {
      s.detach();
      return attachFail(why);
    }
  }
  printReports(s);
  ViewerArgs a;
  a.scene = "attach: " + std::filesystem::path(o.app[0]).filename().string();  // titles and the status bar
  for (size_t i = 1; i < o.app.size(); ++i) a.scene += " " + o.app[i];
  a.commandLine = commandLine();
  a.window = o.window;
  a.windowGiven = true;
  a.paused = o.paused;
  a.eventLog = o.eventLog;
  a.probeLog = o.probeLog;
  a.render = first.options;
  a.attach = &s;
  a.attachFirst = &first;
  a.attachFirstInfo = info;
  if (suggested) {
    a.attachPasses = suggested->passes;
    a.attachSummary = suggested->summary;
    a.attachDraft = suggested->draft;
  }
  const int status = runViewer(a, Scene{});
  s.detach();
  printReports(s);
  if (s.running())
    std::fprintf(stderr, "gblens attach: detached; %s (pid %d) runs on\n", o.app[0].c_str(), int(s.pid()));
  else
    std::fprintf(stderr, "gblens attach: %s exited with status %d\n", o.app[0].c_str(), s.exitStatus());
  return status;
}

// Where a window can open (GLFW's X11 and Wayland back ends look for these).
bool haveDisplay() {
  const char* x = std::getenv("DISPLAY");
  const char* wayland = std::getenv("WAYLAND_DISPLAY");
  return (x && *x) || (wayland && *wayland);
}

// --suggest without --layout: the draft refined with a streamed frame, then the viewer on the stream
// under it, or (-o, or no display) the draft written to -o or stdout and the passes on stderr.
int runSuggestLive(const AttachOptions& o, const LiveOptions& lo) {
  const bool viewer = o.output.empty() && haveDisplay();
  LiveSession s;
  LiveSuggestion suggested;
  std::string error;
  const bool ok = suggestLive(lo, o.timeout, s, suggested,
                              [](const std::string& line) { std::fprintf(stderr, "%s\n", line.c_str()); }, error);
  for (const std::string& r : suggested.reports) std::fprintf(stderr, "gblens attach: %s\n", r.c_str());
  if (!suggested.passes.empty()) std::fputs(suggested.passes.c_str(), stderr);
  if (!ok) return attachFail(error);
  for (const std::string& line : suggested.summary) std::fprintf(stderr, "  %s\n", line.c_str());
  if (viewer) return runViewerOnStream(o, s, &suggested);
  const std::string text = suggested.draft.dump(2) + "\n";
  s.detach();
  if (o.output.empty()) {
    std::fputs(text.c_str(), stdout);
  } else if (!writeTextAtomically(o.output, text, error)) {
    return attachFail(o.output + ": cannot write the draft");
  }
  std::fprintf(stderr, "gblens attach: draft%s%s; check every \"guess\", then: gblens attach --layout %s -- %s\n",
               o.output.empty() ? " on stdout" : " written to ", o.output.c_str(),
               o.output.empty() ? "DRAFT.json" : o.output.c_str(), attachAppText(o).c_str());
  // The draft is what was asked for: the application is ended (scripts wait for gblens, not for it).
  if (!o.output.empty() && !o.keepRunning) {
    s.stop();
    std::fprintf(stderr, "gblens attach: ended %s (pid %d) once the draft was written (--keep-running lets it run on)\n",
                 o.app[0].c_str(), int(s.pid()));
    return 0;
  }
  if (!o.output.empty()) {
    std::fprintf(stderr, "gblens attach: detached; %s (pid %d) runs on\n", o.app[0].c_str(), int(s.pid()));
    return 0;
  }
  const int app = s.waitApplication();
  if (app != 0) std::fprintf(stderr, "gblens attach: %s exited with status %d\n", o.app[0].c_str(), app);
  return 0;
}

int runAttach(const AttachOptions& o) {
  const bool draft = o.suggest && o.layout.empty();  // --suggest drafting the layout (runSuggestLive)
  const bool viewer = !o.capturing() && !o.frames && !draft;
  LiveOptions lo;
  std::string error;
  if (!checkAttachOptions(o, lo, error)) return attachFail(error);
  if (draft) return runSuggestLive(o, lo);
  lo.ringOffThread = !o.capturing();  // a stream (the viewer, --frames): the application never waits for the ring
  if (o.capturing()) removeDebrisOf("attach", o.output);
  LiveSession s;
  if (!s.start(lo, error)) return attachFail(error);
  if (viewer) return runViewerOnStream(o, s);

  std::string why;
  int status = 2;
  if (o.sequence()) {
    status = captureAttachSequence(o, lo, s, why);
  } else {
    for (uint64_t received = 0;;) {  // --capture-frame N: the frame written; --frames K: K frames received
      FrameSnapshot frame;
      LiveFrameInfo info;
      if (!nextAttachFrame(o, s, frame, info, o.captureFrame, why)) break;
      if (o.capturing()) {
        status = writeFrame(o, s, frame, info);
        break;
      }
      if (++received == o.frames) {
        status = 0;
        break;
      }
      s.recycle(std::move(frame));  // its buffers take the next frame's texels (no fresh pages each frame)
      s.ready();                    // --pace on: the next frame may be copied now
    }
  }
  s.detach();
  printReports(s);
  if (o.stats) std::printf("%s\n", statsJson(s).dump(2).c_str());
  if (status != 0 && !why.empty()) attachFail(why);
  const int app = s.waitApplication();
  if (app != 0) std::fprintf(stderr, "gblens attach: %s exited with status %d\n", o.app[0].c_str(), app);
  return status;
}

}  // namespace

Command addAttachCommand(CLI::App& root) {
  auto o = std::make_shared<AttachOptions>();
  CLI::App* cmd = root.add_subcommand("attach", "start a Vulkan application with the gblens layer and stream its G-buffer "
                                                "(docs/attach.md)");
  addAttachOptions(cmd, *o);
  return {cmd, [o]() -> int { return runAttach(*o); }};
}

}  // namespace gb
