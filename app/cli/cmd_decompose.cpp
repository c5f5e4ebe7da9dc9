// gblens decompose CAPTURE -o DIR: the capture's lighting split by term and light (views/analysis/
// decompose.h) as EXR images lighting, diffuse, specular, sun, point_lights, light_count, written
// into a temporary folder renamed to DIR at the end (nothing half-written), with progress lines on
// stderr. Exit 0, or 2.
#include <chrono>
#include <cstdio>
#include <future>
#include <filesystem>
#include <memory>

#include "app/cli/cli.h"
#include "renderer/core/progress.h"
#include "views/analysis/decompose.h"
#include "views/capture/capture.h"
#include "views/capture/exr.h"

namespace gb {

namespace fs = std::filesystem;

namespace {
struct DecomposeArgs {
  std::string capture, out;
};

bool writeAll(const Decomposition& d, const std::string& out, std::string& error) {
  const fs::path tmp = fs::path(out).string() + ".tmp-decompose";
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) {
    error = tmp.string() + ": " + ec.message();
    return false;
  }
  for (size_t t = 0; t < kLightingTermCount; ++t)
    if (!writeExr((tmp / (std::string(name(LightingTerm(t))) + ".exr")).string(), d.images[t], error)) return false;
  fs::remove_all(out, ec);
  fs::rename(tmp, out, ec);
  if (ec) error = out + ": " + ec.message();
  return !ec;
}

// The decomposition in a worker while this thread prints a progress line on stderr at every tenth
// of the rows (as bench and stress report theirs), the first as soon as it starts.
bool decomposeWithProgress(const FrameSnapshot& frame, Decomposition& d, std::string& error) {
  WorkProgress progress;
  progress.total = frame.camera.height;
  const auto start = std::chrono::steady_clock::now();
  std::fprintf(stderr, "gblens decompose: %ux%u, %zu point lights in view\n", frame.camera.width, frame.camera.height,
               frame.visibleLights.size());
  std::future<bool> job = std::async(std::launch::async, [&] {
    ProgressScope scope(&progress);
    return decomposeLighting(frame, d, error);
  });
  int printed = -1;
  auto report = [&](int tenth) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    std::fprintf(stderr, "gblens decompose: %3d%% (%llu of %llu rows, %.1f s)\n", tenth * 10,
                 (unsigned long long)progress.done.load(), (unsigned long long)progress.total.load(), seconds);
    printed = tenth;
  };
  for (;;) {
    const bool finished = job.wait_for(std::chrono::milliseconds(100)) == std::future_status::ready;
    const int tenth = int(progress.fraction() * 10.0);
    if (tenth > printed && (tenth < 10 || finished)) report(tenth);
    if (finished) break;
  }
  return job.get();
}

}  // namespace

Command addDecomposeCommand(CLI::App& root) {
  auto o = std::make_shared<DecomposeArgs>();
  CLI::App* cmd = root.add_subcommand(
      "decompose", "split a capture's lighting: lighting only (white albedo), diffuse, specular, sun, point lights, light count");
  cmd->add_option("CAPTURE", o->capture, "capture directory (gblens capture or gblens import)")->required();
  cmd->add_option("-o,--out", o->out, "folder for lighting.exr, diffuse.exr, specular.exr, sun.exr, point_lights.exr, light_count.exr")
      ->required();
  return {cmd, [o]() -> int {
            Capture c;
            std::string error;
            if (!loadCapture(o->capture, c, error)) {
              std::fprintf(stderr, "gblens decompose: %s\n", error.c_str());
              return 2;
            }
            Decomposition d;
            if (!decomposeWithProgress(c.frame, d, error)) {
              std::fprintf(stderr, "gblens decompose: %s: %s\n", o->capture.c_str(), error.c_str());
              return 2;
            }
            if (!writeAll(d, o->out, error)) {
              std::fprintf(stderr, "gblens decompose: %s\n", error.c_str());
              return 2;
            }
            std::printf("gblens decompose: wrote %s/{lighting,diffuse,specular,sun,point_lights,light_count}.exr\n",
                        o->out.c_str());
            return 0;
          }};
}

}  // namespace gb
