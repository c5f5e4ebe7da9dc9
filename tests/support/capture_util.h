// Helpers for capture/compare/probe tests: fresh temporary directories, running the gblens
// binary (exit status + output), and small renders of the built-in scene to capture.
#pragma once
#include <string>
#include <vector>

#include "renderer/core/options.h"
#include "renderer/core/snapshot.h"

namespace gb {

// A fresh, empty directory for one test (removed first if a previous run left it).
std::string freshDir(const std::string& name);

struct RunResult {
  int exitCode = -1;
  std::string output;  // stdout and stderr
};
// Runs `gblens ARGS` (the binary this build made) through the shell.
RunResult runGblens(const std::string& args);
// Runs any shell command.
RunResult runShell(const std::string& command);

// Small options for captures in tests: 96x54, a few lights, a small shadow map, coverage on.
RenderOptions smallCaptureOptions();

// A frame made up on the CPU (no GPU): albedo_specular, normal_shadow, depth, depth_stencil,
// hdr, final and coverage_masked, w x h, with smooth made-up contents; the rest absent.
FrameSnapshot syntheticFrame(uint32_t width, uint32_t height);
// A frame of a camera at (cameraX, 0, 5) looking down -Z at the plane z = 0 (eye depth 5 everywhere,
// hardware depth to match, normals facing the camera), w x h: a checkerboard of 0.25-unit squares in
// the plane's x, y, scaled by `brightness`, in albedo, hdr and final. Consecutive frames of cameras
// moved along x are a sequence whose points move by a known number of pixels (kPlaneDepth).
constexpr double kPlaneDepth = 5.0;
FrameSnapshot planeFrame(uint32_t width, uint32_t height, double cameraX, double brightness = 1.0);
// Stores `value` at a texel in the image's own format (F16/F32 as floats, U8/U32 as integers).
void setTexel(CpuImage& image, uint32_t x, uint32_t y, uint32_t c, double value);

// Reads a whole file (empty when missing).
std::string readText(const std::string& path);

}  // namespace gb
