// gblens capture [SCENE] -o DIR [--targets a,b,c] [--coverage on|off]: renders one frame and
// writes a capture (views/capture.h). Only the targets asked for are read back.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <sstream>

#include "app/cli.h"
#include "renderer/frame_memory.h"
#include "views/capture.h"
#include "views/report.h"

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
  return {cmd, [o, targets, coverage]() -> int {
            std::string error;
            if (!finishCommonOptions(*o, error)) {
              std::fprintf(stderr, "gblens capture: %s\n", error.c_str());
              return 2;
            }
            RenderOptions ro = o->render;
            ro.coverage = *coverage == "on";
            Scene scene;
            if (!loadSceneOrReport(*o, scene)) return 2;
            std::vector<Target> wanted;
            if (!targets->empty()) {
              if (!parseTargetList(*targets, wanted, error)) {
                std::fprintf(stderr, "gblens capture: %s\n", error.c_str());
                return 2;
              }
              for (Target t : wanted) {
                std::string why = targetUnavailable(t, ro, &scene);
                if (!why.empty()) {
                  std::fprintf(stderr, "gblens capture: --targets %s: %s\n", targetName(t), why.c_str());
                  return 2;
                }
              }
            } else {
              wanted = availableTargets(ro, &scene);
            }

            ContextOptions co;
            co.validation = o->validate;
            co.device = o->device;
            GpuContext ctx = createContext(co);
            // An output the device cannot hold is refused here, before any target is allocated.
            if (std::string why = frameTooLarge(ctx, scene, ro); !why.empty()) {
              std::fprintf(stderr, "gblens capture: %s\n", why.c_str());
              destroyContext(ctx);
              return 2;
            }
            int status = 0;
            {
              Renderer r;
              initRenderer(r, ctx, scene);
              FrameRequest request = captureRequest(wanted, ro);
              auto has = [&](Target t) { return std::find(wanted.begin(), wanted.end(), t) != wanted.end(); };
              std::vector<FrameStats> frames;
              for (int i = 0; i < o->frames; ++i) frames.push_back(renderFrame(r, ro, request));
              auto start = std::chrono::steady_clock::now();
              FrameSnapshot snap = snapshotFromRenderer(r, wanted);
              for (size_t i = 0; i < kTargetCount; ++i)
                if (!has(Target(i)) && snap.absent[i] == "not read back") snap.absent[i] = "not requested (--targets)";
              CaptureMeta meta;
              meta.device = ctx.deviceName;
              meta.driver = ctx.driverName;
              meta.scene = o->scene;
              meta.sceneSha256 = sceneContentSha256(scene);
              meta.sceneData = &scene;
              meta.stats = frames.back();
              meta.commandLine = commandLine();
              if (!writeCapture(o->output, snap, meta, error)) {
                std::fprintf(stderr, "gblens capture: %s\n", error.c_str());
                status = 2;
              } else {
                double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
                std::fprintf(stderr, "gblens: wrote %s (%zu targets, %.2f MB, frame %.1f ms, write %.1f ms)\n",
                             o->output.c_str(), wanted.size(), double(directoryBytes(o->output)) / 1e6,
                             frames.back().frameMs, ms);
              }
              if (o->stats) std::printf("%s\n", statsJson(frames, ctx, ro, scene).dump(2).c_str());
              destroyRenderer(r);
            }
            if (reportValidation(ctx) && status == 0) status = 1;
            destroyContext(ctx);
            return status;
          }};
}

}  // namespace gb
