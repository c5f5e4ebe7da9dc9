// gblens attach's headless receiving and --capture-frames (see attach_sequence.h). The layer sends
// every frame of the range (each frame's submission waits until gblens has read the one before, at
// most 20 s): a frame that still does not come (its copies written again before they were read, a
// ring slot it could not have) is a gap, and a sequence with a gap is never written.
#include "app/cli/attach_sequence.h"

#include <chrono>
#include <cstdio>

#include "app/cli/cli.h"
#include "views/capture/sequence.h"

namespace gb {

namespace {

std::string helloText(const LiveSession& s, const char* key, const std::string& fallback) {
  const nlohmann::json& h = s.hello();
  return h.is_object() && h.contains(key) && h[key].is_string() ? h[key].get<std::string>() : fallback;
}

std::string frameList(int64_t first, int64_t last) {
  return first == last ? "frame " + std::to_string(first) : "frames " + std::to_string(first) + ".." + std::to_string(last);
}

}  // namespace

std::string attachAppText(const AttachOptions& o) {
  std::string text;
  for (const std::string& a : o.app) text += (text.empty() ? "" : " ") + a;
  return text;
}

CaptureMeta attachMeta(const AttachOptions& o, const LiveSession& s, uint64_t appFrame) {
  CaptureMeta meta;
  meta.device = helloText(s, "device", "");
  meta.scene = "attach: " + attachAppText(o) + " (application frame " + std::to_string(appFrame) + ")";
  meta.commandLine = commandLine();
  return meta;
}

std::string attachTargetsText(const FrameSnapshot& frame, const LiveFrameInfo& info) {
  std::string text;
  char line[512];
  for (uint32_t t = 0; t < frame.layout.targets.size(); ++t)
    if (frame.images[t].present()) {
      std::snprintf(line, sizeof line, "  %-20s %-14s %ux%u  %s\n", frame.layout.targets[t].name.c_str(),
                    frame.layout.targets[t].format.name.c_str(), frame.images[t].image.width, frame.images[t].image.height,
                    info.sources[t].c_str());
      text += line;
    }
  for (const std::string& a : info.absent) text += "  absent: " + a + "\n";
  return text;
}

bool nextAttachFrame(const AttachOptions& o, LiveSession& s, FrameSnapshot& frame, LiveFrameInfo& info, int64_t wanted,
                     std::string& why) {
  const auto start = std::chrono::steady_clock::now();
  for (;;) {
    const bool got = s.wait(frame, 0.2, &info);
    for (const std::string& r : s.takeReports()) std::fprintf(stderr, "gblens attach: %s\n", r.c_str());
    if (got) return true;
    if (s.noMatch()) {
      why = "nothing matched the layout in the application's first frames (the layer's reports above say why)";
      return false;
    }
    if (!s.running() && !s.attached()) {
      why = s.hello().is_null() ? "the application ended without creating a Vulkan device under the layer"
                                : "the application ended after " + std::to_string(s.counts().received) + " streamed frame(s)" +
                                      (wanted >= 0 ? ", before its frame " + std::to_string(wanted) : std::string());
      return false;
    }
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count() > o.timeout) {
      why = "--timeout " + std::to_string(int(o.timeout)) + " s: no frame came";
      return false;
    }
  }
}

int captureAttachSequence(const AttachOptions& o, const LiveOptions& lo, LiveSession& s, std::string& why) {
  const int64_t first = lo.captureFrame, last = lo.captureLast;
  const std::string range = "--capture-frames " + o.captureFrames;
  uint64_t firstEndNs = 0, firstStream = 0, lastStream = 0;
  std::string targets;  // the first frame's
  // Filled with the first frame (the layer's hello has come by then); writeSequence reads it last.
  nlohmann::json extra;
  auto record = [&] {
    extra = {
        {"command_line", commandLine()},
        {"source", "attach: " + attachAppText(o)},
        {"application", helloText(s, "application", "")},
        {"device", helloText(s, "device", "")},
        {"layout", o.layout},
        {"time_is", "seconds from the end of the first frame to each frame's end (its present, or the submission that ended "
                    "it), on the layer's clock; the application waited for gblens to read each frame"}};
  };
  auto produce = [&](size_t i, SequenceEntry& e, std::string& error) {
    const int64_t expected = first + int64_t(i);
    LiveFrameInfo info;
    if (!nextAttachFrame(o, s, e.frame, info, expected, error)) {
      error = range + ": " + error + "; nothing written";
      return false;
    }
    if (int64_t(info.appFrame) != expected) {  // never a sequence with a hole in it
      error = range + ": the stream skipped application " + frameList(expected, int64_t(info.appFrame) - 1) +
              " (its copies were not read whole: the layer's reports above say why); nothing written";
      if (int64_t(info.appFrame) < expected)
        error = range + ": application frame " + std::to_string(info.appFrame) + " came after frame " +
                std::to_string(expected - 1) + "; nothing written";
      return false;
    }
    if (i == 0) {
      firstEndNs = info.endNs, firstStream = info.stream, targets = attachTargetsText(e.frame, info);
      record();
    }
    lastStream = info.stream;
    e.number = expected;
    e.meta = attachMeta(o, s, info.appFrame);
    // The layer's own clock at the frame's end, from frame A's: measured, never made up. The
    // application's animation clock is not on the wire; the jitter neither (null).
    e.time = double(info.endNs - firstEndNs) * 1e-9;
    return true;
  };
  std::string error;
  if (!writeSequence(o.output, size_t(last - first + 1), produce, extra, error)) {
    why = error;
    return 2;
  }
  std::printf("attached to %s (%s): wrote application %s (%lld frames, streamed %llu..%llu) with layout %s into %s\n",
              helloText(s, "application", "?").c_str(), helloText(s, "device", "").c_str(), frameList(first, last).c_str(),
              (long long)(last - first + 1), (unsigned long long)firstStream, (unsigned long long)lastStream, o.layout.c_str(),
              o.output.c_str());
  std::fputs(targets.c_str(), stdout);
  return 0;
}

}  // namespace gb
