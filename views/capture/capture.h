// Captures: a directory with one lossless OpenEXR per target, final.png, lights.json and
// manifest.json (docs/capture-format.md). Written atomically (temporary directory beside
// the destination, renamed into place); loading validates the manifest, every file's size and
// SHA-256 and every EXR's channels before anything is used.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "renderer/core/frame_stats.h"
#include "renderer/core/snapshot.h"

namespace gb {

// 2: a multisampled target's `sample_files`. A capture is written in the oldest version that holds
// it (1 without multisampled targets), so that a gblens of version 1 refuses, rather than shows as
// one sample, a capture whose targets it cannot read whole.
constexpr int kCaptureFormatVersion = 2;

// What a capture records beyond the frame snapshot.
struct CaptureMeta {
  std::string device, driver;
  std::string scene;             // SCENE as given ("builtin:temple" or a path)
  std::string sceneSha256;       // sceneContentSha256() of the loaded scene
  FrameStats stats;              // per-pass ms, light counts, culling statistics
  std::string commandLine;       // how it was made, for the record
  // Where an imported frame came from (manifest "source"): the recording API and machine, the replay
  // driver; null for gblens's own frames (device and driver say it).
  nlohmann::json source;
};

// Every target that can be read back under these options (targetAbsence() is Absent::No).
std::vector<Target> availableTargets(const RenderOptions& options, bool sceneHasSun = true);

// Writes a capture of `frame` to `dir`. The targets written are those present in the
// snapshot; absent ones are listed in the manifest with the snapshot's reason. An existing
// capture at `dir` is replaced; an existing non-capture directory is refused (never clobbered).
bool writeCapture(const std::string& dir, const FrameSnapshot& frame, const CaptureMeta& meta, std::string& error);

struct Capture {
  std::string dir;
  nlohmann::json manifest;
  FrameSnapshot frame;  // whole images of every captured target
};

// What went wrong while loading (compare exits 4 for all of them; the message says which).
enum class CaptureProblem { None, Missing, Corrupt, Truncated, Checksum };

// Loads and validates a capture. On failure returns false with a one-line message naming the
// file and, in `problem`, the kind of failure.
bool loadCapture(const std::string& dir, Capture& out, std::string& error, CaptureProblem* problem = nullptr);

// JSON forms used by the manifest (also by tests and the viewer's "copy as JSON").
nlohmann::json matrixJson(const glm::dmat4& m);  // 16 numbers, column-major (glm order)
bool matrixFromJson(const nlohmann::json& j, glm::dmat4& m);
nlohmann::json cameraJson(const Camera& v);
bool cameraFromJson(const nlohmann::json& j, Camera& v, std::string& error);

}  // namespace gb
