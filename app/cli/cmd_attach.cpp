// gblens attach: another running Vulkan application's G-buffer, streamed by the gblens layer.
//   gblens attach --layout L.json --capture-frame N -o DIR [--every E] [--stats] -- APP ARGS...
//   gblens attach --layout L.json --frames K [--every E] [--stats] -- APP ARGS...
//   gblens attach --suggest -- APP ARGS...
// The application is started with the layer, runs to its own end (the layer detaches), and the
// command exits 0 when it got what it was asked for, 2 when nothing matched the layout (with why).
// Without --capture-frame, --frames or --suggest it would open the live viewer, which is not wired
// yet. docs/attach.md.
#include <chrono>
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "views/capture/capture.h"
#include "views/capture/live.h"

namespace gb {

namespace {

struct AttachOptions {
  std::string layout, output;
  std::vector<std::string> params, app;
  uint32_t every = 1;
  uint64_t captureFrame = 0, frames = 0;
  bool suggest = false, stats = false;
  double timeout = 300.0;
};

int fail(const std::string& message) {
  std::fprintf(stderr, "gblens attach: %s\n", message.c_str());
  return 2;
}

void printReports(LiveSession& s) {
  for (const std::string& r : s.takeReports()) std::fprintf(stderr, "gblens attach: %s\n", r.c_str());
}

// The layer's --suggest report, printed as import --list prints a capture, with the source that
// names each attachment in a layout.
void printSuggestion(const nlohmann::json& hello, const nlohmann::json& s) {
  std::printf("application  %s (%s)\n", hello.value("application", "").c_str(), hello.value("device", "").c_str());
  std::printf("frame        %llu\n", (unsigned long long)s.value("frame", 0ull));
  const nlohmann::json& passes = s["passes"];
  std::printf("passes       %zu (ordinal in its command buffer, labels or render pass name; attachments)\n", passes.size());
  for (const nlohmann::json& p : passes) {
    std::string names;
    for (const nlohmann::json& l : p["labels"]) names += (names.empty() ? "" : " > ") + l.get<std::string>();
    if (!p.value("render_pass", "").empty()) names += (names.empty() ? "" : "  ") + ("render pass \"" + p.value("render_pass", "") + "\"");
    std::printf("  #%-3d %s%s\n", p.value("ordinal", 0), p.value("dynamic", false) ? "(dynamic rendering) " : "", names.c_str());
    for (const nlohmann::json& a : p["attachments"]) {
      const std::string role = a.value("role", ""), image = a.value("image", "");
      nlohmann::json source = {{"pass", p.value("ordinal", 0)}};
      if (!image.empty())
        source = {{"name", image}};
      else if (role == "depth")
        source["depth"] = true;
      else if (role.rfind("color ", 0) == 0)
        source["color"] = std::stoi(role.substr(6));
      const std::string format = a.value("format", "");
      std::printf("       %-8s %-20s %-32s %-14s %ux%u%s%s\n", role.c_str(), image.empty() ? "(unnamed)" : image.c_str(),
                  a.value("vk_format", "").c_str(), format.empty() ? "-" : format.c_str(), a.value("width", 0u),
                  a.value("height", 0u), a.value("store_patched", false) ? "  (not stored by the application: gblens stores it)" : "",
                  a.value("why", "").empty() ? "" : ("  * " + a.value("why", "")).c_str());
      if (format.size() && a.value("why", "").empty() && role != "other")
        std::printf("                source: {\"live\": %s}\n", source.dump().c_str());
    }
  }
}

nlohmann::json statsJson(const LiveSession& s) {
  const LiveCounts& c = s.counts();
  const double frameMs = c.layer.value("frame_ms", 0.0);
  return {{"application", s.hello().value("application", "")},
          {"device", s.hello().value("device", "")},
          {"received", c.received},
          {"undecodable", c.undecodable},
          {"dropped", c.dropped},
          {"application_frames", c.appFrames},
          {"latency_ms", {{"mean", c.meanLatencyMs}, {"max", c.maxLatencyMs}}},
          {"decode_ms", c.meanDecodeMs},
          {"copies_done_ms", c.meanReadyMs},
          {"overwritten", c.overwritten},
          {"latency_frames", frameMs > 0.0 ? c.meanLatencyMs / frameMs : 0.0},
          {"layer", c.layer}};
}

int writeFrame(const AttachOptions& o, const LiveSession& s, const FrameSnapshot& frame, const LiveFrameInfo& info) {
  CaptureMeta meta;
  meta.device = s.hello().value("device", "");
  meta.scene = "attach:";
  for (const std::string& a : o.app) meta.scene += " " + a;
  meta.scene += " (application frame " + std::to_string(info.appFrame) + ")";
  meta.commandLine = commandLine();
  std::string error;
  if (!writeCapture(o.output, frame, meta, error)) return fail(error);
  std::printf("attached to %s (%s): wrote application frame %llu (streamed frame %llu) with layout %s into %s\n",
              s.hello().value("application", "?").c_str(), meta.device.c_str(), (unsigned long long)info.appFrame,
              (unsigned long long)info.stream, o.layout.c_str(), o.output.c_str());
  for (uint32_t t = 0; t < frame.layout.targets.size(); ++t)
    if (frame.images[t].present())
      std::printf("  %-20s %-14s %ux%u  %s\n", frame.layout.targets[t].name.c_str(), frame.layout.targets[t].format.name.c_str(),
                  frame.images[t].image.width, frame.images[t].image.height, info.sources[t].c_str());
  for (const std::string& a : info.absent) std::printf("  absent: %s\n", a.c_str());
  return 0;
}

int runAttach(const AttachOptions& o) {
  if (!o.captureFrame && !o.frames && !o.suggest)
    return fail("the live viewer is not wired yet: give --capture-frame N -o DIR (write a frame), --frames K (stream K "
                "frames) or --suggest (list the render passes)");
  if (o.captureFrame && o.output.empty()) return fail("-o: required with --capture-frame (the capture folder to write)");
  if (!o.captureFrame && !o.output.empty()) return fail("-o: writes the frame --capture-frame names");
  if ((o.captureFrame || o.frames) && o.layout.empty())
    return fail("--layout: required (a layout file, docs/layout-format.md, or builtin:NAME)");
  LiveOptions lo;
  lo.layout = o.layout;
  lo.argv = o.app;
  lo.every = o.every;
  lo.onlyFrame = o.captureFrame;
  lo.suggest = o.suggest;
  std::string error;
  if (!parseLayoutParameters(o.params, lo.options, error)) return fail(error);
  LiveSession s;
  if (!s.start(lo, error)) return fail(error);

  int status = 2;
  std::string why;
  uint64_t received = 0;
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    FrameSnapshot frame;
    LiveFrameInfo info;
    const bool got = s.wait(frame, 0.2, &info);
    printReports(s);
    if (got && o.captureFrame) {
      status = writeFrame(o, s, frame, info);
      break;
    }
    if (got && ++received == o.frames) {
      status = 0;
      break;
    }
    if (o.suggest && s.suggestion()) {
      printSuggestion(s.hello(), *s.suggestion());
      status = 0;
      break;
    }
    if (s.noMatch()) {
      why = "nothing matched the layout in the application's first frames (the layer's reports above say why)";
      break;
    }
    if (!s.running() && !s.attached()) {
      why = s.hello().is_null() ? "the application ended without creating a Vulkan device under the layer"
            : o.suggest         ? "the application ended before submitting a render pass"
                                : "the application ended after " + std::to_string(s.counts().received) +
                                      " streamed frame(s), before the one asked for";
      break;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > o.timeout) {
      why = "--timeout " + std::to_string(int(o.timeout)) + " s: no frame came";
      break;
    }
  }
  s.detach();
  printReports(s);
  if (o.stats) std::printf("%s\n", statsJson(s).dump(2).c_str());
  if (status != 0 && !why.empty()) fail(why);
  const int app = s.waitApplication();
  if (app != 0) std::fprintf(stderr, "gblens attach: %s exited with status %d\n", o.app[0].c_str(), app);
  return status;
}

}  // namespace

Command addAttachCommand(CLI::App& root) {
  auto o = std::make_shared<AttachOptions>();
  CLI::App* cmd = root.add_subcommand("attach", "start a Vulkan application with the gblens layer and stream its G-buffer "
                                                "(docs/attach.md)");
  cmd->add_option("--layout", o->layout, "what the G-buffer holds and where (a layout file with live sources, or builtin:NAME)");
  cmd->add_option("--param", o->params, "NAME=VALUE: an option value for a parameterised layout (e.g. normal_format=oct-rg16)")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--capture-frame", o->captureFrame, "write the Nth streamed frame (1: the first) as a capture, then detach")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
  cmd->add_option("-o,--output", o->output, "the capture folder --capture-frame writes (atomically)");
  cmd->add_option("--frames", o->frames, "receive and decode K streamed frames, write nothing (with --stats: the costs)")
      ->check(CLI::Range(uint64_t(1), uint64_t(1) << 40));
  cmd->add_option("--every", o->every, "stream every Nth frame of the application")->check(CLI::Range(1u, 100000u))->capture_default_str();
  cmd->add_flag("--suggest", o->suggest, "print the render passes and attachments the layer sees in one frame");
  cmd->add_flag("--stats", o->stats, "print the layer's costs (frame time, memory, drops, latency) as JSON");
  cmd->add_option("--timeout", o->timeout, "give up when no frame came within this many seconds")->capture_default_str();
  cmd->add_option("APP", o->app, "the application and its arguments (after --)")->required();
  return {cmd, [o]() -> int { return runAttach(*o); }};
}

}  // namespace gb
