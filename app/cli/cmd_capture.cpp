// gblens capture [SCENE] -o DIR [--targets a,b,c] [--coverage on|off] [--sequence N]: renders one
// frame and writes a capture (views/capture.h), or N frames at --time T, T + S, ... (S: --time-step)
// as a sequence (views/capture/sequence.h). Only the targets asked for are read back.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "app/cli/cli.h"
#include "renderer/frame/session.h"
#include "renderer/gpu/render_targets.h"
#include "views/capture/capture.h"
#include "renderer/core/camera_motion.h"
#include "views/capture/report.h"
#include "views/capture/sequence.h"

namespace gb {

static bool parseTargetList(const std::string& text, std::vector<Target>& out, std::string& error) {
  std::stringstream s(text);
  std::string item;
  while (std::getline(s, item, ',')) {
    Target t;
    if (!parseTarget(item, t)) {
      error = "--targets: unknown target \"" + item + "\" (targets:";
      for (size_t i = 0; i < kTargetCount; ++i) error += std::string(" ") + targetName(Target(i));
      error += ")";
      return false;
    }
    if (std::find(out.begin(), out.end(), t) == out.end()) out.push_back(t);
  }
  if (out.empty()) error = "--targets: empty list";
  return !out.empty();
}

static uint64_t directoryBytes(const std::string& dir) {
  uint64_t n = 0;
  std::error_code ec;
  for (const auto& e : std::filesystem::directory_iterator(dir, ec))
    if (e.is_regular_file(ec)) n += e.file_size(ec);
  return n;
}

// Which targets to capture: --targets (parsed before the device starts; each must be computed
// under the options as this device runs them, `ran`) or every available one.
static bool chooseTargets(const std::vector<Target>& listed, const RenderOptions& ran, const Scene& scene,
                          std::vector<Target>& wanted) {
  if (listed.empty()) {
    wanted = availableTargets(ran, scene.sun.enabled);
    return true;
  }
  wanted = listed;
  for (Target t : wanted)
    if (Absent why = targetAbsence(t, ran, scene.sun.enabled); why != Absent::No) {
      std::fprintf(stderr, "gblens capture: --targets %s: %s\n", targetName(t), absentText(why));
      return false;
    }
  return true;
}

static CaptureMeta captureMeta(const HeadlessSession& session, const CommonOptions& o, const Scene& scene,
                               const FrameStats& stats) {
  CaptureMeta meta;
  meta.device = session.deviceName();
  meta.driver = session.driverName();
  meta.scene = o.scene;
  meta.sceneSha256 = sceneContentSha256(scene);
  meta.stats = stats;
  meta.commandLine = commandLine();
  return meta;
}

// The frames of a sequence: frame i at time T + i S with time_step S, so that each frame's motion
// target points at the frame before it; its jitter recorded in sequence.json.
static int captureSequence(const CommonOptions& o, HeadlessSession& session, const Scene& scene,
                           const RenderOptions& ro, const std::vector<Target>& wanted, int count) {
  std::vector<FrameStats> last;
  auto produce = [&](size_t i, SequenceEntry& entry, std::string&) {
    RenderOptions frame = ro;
    frame.time = ro.time + double(i) * ro.timeStep;
    const FrameRequest request = captureRequest(wanted, frame);
    std::vector<FrameStats> frames;
    for (int k = 0; k < o.frames; ++k) frames.push_back(session.render(frame, request));
    entry.frame = session.snapshot(wanted);
    for (Absent& a : entry.frame.absences)
      if (a == Absent::NotReadBack) a = Absent::NotRequested;
    entry.meta = captureMeta(session, o, scene, frames.back());
    entry.time = frame.time;
    entry.jitter = frameJitter(frame);  // pixels, +x right, +y down (zero with jitter off)
    last = frames;
    return true;
  };
  const nlohmann::json extra = {{"command_line", commandLine()}, {"scene", o.scene}, {"time_step", ro.timeStep}};
  std::string error;
  int status = 0;
  if (!writeSequence(o.output, size_t(count), produce, extra, error)) {
    std::fprintf(stderr, "gblens capture: %s\n", error.c_str());
    status = 2;
  } else {
    std::fprintf(stderr, "gblens: wrote %s (%d frames from time %g, step %g s, %zu targets each)\n", o.output.c_str(),
                 count, ro.time, ro.timeStep, wanted.size());
  }
  if (o.stats && !last.empty()) {
    const nlohmann::json stats = statsJson(last, {session.deviceName(), session.driverName(), scene.source}, ro);
    std::printf("%s\n", stats.dump(2).c_str());
  }
  if (session.reportValidation() && status == 0) status = 1;
  return status;
}

static int capture(const CommonOptions& o, const std::string& targets, bool coverage, int sequence) {
  RenderOptions ro = o.render;
  ro.coverage = coverage;
  Scene scene;
  if (!loadSceneOrReport(o, scene)) return 2;
  std::vector<Target> listed;
  if (std::string error; !targets.empty() && !parseTargetList(targets, listed, error)) {
    std::fprintf(stderr, "gblens capture: %s\n", error.c_str());
    return 2;
  }
  HeadlessSession session(scene, {o.device, o.validate});
  // Which targets the frame computes depends on the G-buffer kind this device runs (--gbuffer auto).
  std::vector<Target> wanted;
  if (!chooseTargets(listed, session.frameOptions(ro), scene, wanted)) return 2;
  removeDebrisOf("capture", o.output);
  // An output the device cannot hold is refused here, before any target is allocated.
  if (std::string why = session.tooLarge(ro); !why.empty()) {
    std::fprintf(stderr, "gblens capture: %s\n", why.c_str());
    return 2;
  }
  if (std::string why = session.refused(ro); !why.empty()) {  // --gbuffer visibility out of reach
    std::fprintf(stderr, "gblens capture: %s\n", why.c_str());
    return 2;
  }
  if (sequence > 0) return captureSequence(o, session, scene, ro, wanted, sequence);
  FrameRequest request = captureRequest(wanted, ro);
  std::vector<FrameStats> frames;
  for (int i = 0; i < o.frames; ++i) {
    RenderDocCapture rdc(session.context(), i + 1 == o.frames);  // under RenderDoc: the frame captured
    frames.push_back(session.render(ro, request));
    reportRenderDocCapture("gblens capture", rdc);
  }
  auto start = std::chrono::steady_clock::now();
  FrameSnapshot snap = session.snapshot(wanted);
  for (Absent& a : snap.absences)
    if (a == Absent::NotReadBack) a = Absent::NotRequested;
  const CaptureMeta meta = captureMeta(session, o, scene, frames.back());
  int status = 0;
  std::string error;
  if (!writeCapture(o.output, snap, meta, error)) {
    std::fprintf(stderr, "gblens capture: %s\n", error.c_str());
    status = 2;
  } else {
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "gblens: wrote %s (%zu targets, %.2f MB, frame %.1f ms, write %.1f ms)\n", o.output.c_str(),
                 wanted.size(), double(directoryBytes(o.output)) / 1e6, frames.back().frameMs, ms);
  }
  if (o.stats) std::printf("%s\n", statsJson(frames, {meta.device, meta.driver, scene.source}, ro).dump(2).c_str());
  if (session.reportValidation() && status == 0) status = 1;
  return status;
}

Command addCaptureCommand(CLI::App& root) {
  auto o = std::make_shared<CommonOptions>();
  auto targets = std::make_shared<std::string>();
  auto coverage = std::make_shared<std::string>("on");
  CLI::App* cmd = root.add_subcommand("capture", "render one frame and write a capture: EXR per target + manifest");
  addCommonOptions(cmd, *o);
  cmd->add_option("-o,--output", o->output, "capture directory to write (replaced if it holds a capture)")->required();
  cmd->add_option("--targets", *targets, "comma-separated targets to capture (default: every available one)");
  cmd->add_option("--coverage", *coverage, "compute the coverage_masked/coverage_full targets: on | off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  auto sequence = std::make_shared<std::string>();
  cmd->add_option("--sequence", *sequence,
                  "write N frames at --time T, T + S, ... (S: --time-step, which is also each frame's motion "
                  "target's step) as a sequence: DIR/frame_NNNN captures + sequence.json (time, jitter)");
  return {cmd, [o, targets, coverage, sequence]() -> int {
            std::string error;
            if (!finishCommonOptions(*o, error)) {
              std::fprintf(stderr, "gblens capture: %s\n", error.c_str());
              return 2;
            }
            int frames = 0;  // no sequence: one capture
            if (!sequence->empty()) {
              char* end = nullptr;
              const long n = std::strtol(sequence->c_str(), &end, 10);
              if (*end != 0 || n < 1 || n > 100000) {
                std::fprintf(stderr, "gblens capture: --sequence %s: expected a frame count 1..100000\n",
                             sequence->c_str());
                return 2;
              }
              frames = int(n);
            }
            return capture(*o, *targets, *coverage == "on", frames);
          }};
}

}  // namespace gb
