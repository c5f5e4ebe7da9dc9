// Loading captures: the manifest read through the one manifest check (manifest_check.cpp), every
// listed file checked (a regular file inside the folder, the recorded size, the recorded SHA-256)
// before it is parsed; then the EXRs the images.
#include <filesystem>

#include "renderer/core/json_read.h"
#include "renderer/core/sha256.h"
#include "views/capture/capture.h"
#include "views/capture/sequence.h"
#include "views/capture/exr.h"
#include "views/capture/manifest_check.h"

namespace gb {

namespace fs = std::filesystem;

nlohmann::json matrixJson(const glm::dmat4& m) {
  nlohmann::json j = nlohmann::json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) j.push_back(m[c][r]);
  return j;
}

nlohmann::json cameraJson(const Camera& v) {
  return {{"width", v.width},   {"height", v.height}, {"yfov", v.yfov},
          {"aspect", v.aspect}, {"znear", v.znear},   {"zfar", v.zfar},
          {"reversed_z", v.reversedZ},
          {"clipFromEye", matrixJson(v.clipFromEye)},     {"eyeFromClip", matrixJson(v.eyeFromClip)},
          {"eyeFromWorld", matrixJson(v.eyeFromWorld)},   {"worldFromEye", matrixJson(v.worldFromEye)},
          {"clipFromWorld", matrixJson(v.clipFromWorld)}};
}

// Captures are self-contained folders: a listed file (or the manifest) that is a symbolic link to
// somewhere outside the folder is refused, as a ".." path would be.
static bool insideFolder(const fs::path& dir, const fs::path& p, std::string& error) {
  std::error_code ec;
  if (!fs::is_symlink(p, ec)) return true;
  const fs::path target = fs::canonical(p, ec), folder = fs::canonical(dir, ec);
  const std::string prefix = folder.string() + "/";
  if (!ec && target.string().compare(0, prefix.size(), prefix) == 0) return true;
  error = p.string() + ": a symbolic link leaving the capture folder (captures are self-contained)";
  return false;
}

// Every listed file: a regular file inside the folder, the recorded size, the recorded digest.
static bool checkFiles(const fs::path& dir, const std::vector<ManifestFile>& files, std::string& error,
                       CaptureProblem& problem) {
  for (const ManifestFile& file : files) {
    const fs::path p = dir / file.name;
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(p, ec))) {
      problem = CaptureProblem::Missing;
      error = p.string() + ": missing (listed in manifest.json)";
      return false;
    }
    std::string why;
    if (!insideFolder(dir, p, error) || !isRegularFile(p.string(), why)) {
      problem = CaptureProblem::Corrupt;
      if (!why.empty()) error = why + " (listed in manifest.json)";
      return false;
    }
    const uint64_t bytes = fs::file_size(p, ec), expected = file.bytes;
    if (bytes != expected) {
      problem = bytes < expected ? CaptureProblem::Truncated : CaptureProblem::Corrupt;
      error = p.string() + ": " + (bytes < expected ? "truncated: " : "wrong size: ") + std::to_string(bytes) +
              " bytes, manifest.json says " + std::to_string(expected);
      return false;
    }
    std::string hex;
    if (!sha256File(p.string(), hex, error)) {
      problem = CaptureProblem::Missing;
      return false;
    }
    if (hex != file.sha256) {
      problem = CaptureProblem::Checksum;
      error = p.string() + ": checksum mismatch: SHA-256 " + hex + ", manifest.json says " + file.sha256;
      return false;
    }
  }
  return true;
}

bool loadCapture(const std::string& dirText, Capture& out, std::string& error, CaptureProblem* problemOut) {
  CaptureProblem problem = CaptureProblem::None;
  auto fail = [&](CaptureProblem p, const std::string& message) {
    if (problem == CaptureProblem::None) problem = p;
    if (problemOut) *problemOut = problem;
    error = message;
    return false;
  };
  // SEQ@N: frame N of a sequence (views/capture/sequence.h).
  std::string frameDir;
  if (resolveSequenceFrame(dirText, frameDir, error)) return loadCapture(frameDir, out, error, problemOut);
  if (!error.empty()) return fail(CaptureProblem::Missing, error);
  const fs::path dir(dirText);
  std::error_code ec;
  if (!fs::is_directory(dir, ec)) return fail(CaptureProblem::Missing, dirText + ": no such capture directory");
  if (isSequence(dirText) && !fs::exists(dir / "manifest.json", ec))
    return fail(CaptureProblem::Missing, dirText + ": a sequence, not one capture (name a frame of it: " + dirText + "@N)");
  const fs::path manifestPath = dir / "manifest.json", lightsPath = dir / "lights.json";
  if (!fs::exists(fs::symlink_status(manifestPath, ec)))
    return fail(CaptureProblem::Missing, dirText + ": no manifest.json (not a capture, or an interrupted one)");
  // The manifest: inside the folder, a regular file of a sane size (not a link to /dev/zero), JSON
  // nested no deeper than a manifest is.
  std::string text;
  nlohmann::json m, lights;
  std::vector<ManifestFile> files;
  if (!insideFolder(dir, manifestPath, error) || !readRegularFile(manifestPath.string(), text, error, kMaxJsonBytes) ||
      !parseJson(text, manifestPath.string(), m, error) || !checkManifestFormat(m, manifestPath.string(), error) ||
      !manifestFiles(m, manifestPath.string(), files, error))
    return fail(CaptureProblem::Corrupt, error);
  if (!checkFiles(dir, files, error, problem)) return fail(problem, dirText + ": " + error);

  Capture c;
  c.dir = dirText;
  FrameSnapshot& f = c.frame;
  std::vector<ManifestTarget> targets;
  if (!readRegularFile(lightsPath.string(), text, error, kMaxJsonBytes) || !parseJson(text, lightsPath.string(), lights, error) ||
      !frameFromManifest(m, lights, manifestPath.string(), lightsPath.string(), f, targets, error))
    return fail(CaptureProblem::Corrupt, error);
  for (ManifestTarget& t : targets) {
    if (!readExr((dir / t.file).string(), t.image, error)) return fail(CaptureProblem::Corrupt, dirText + ": " + error);
    TargetImage& ti = f.images[size_t(t.index)];
    for (size_t k = 0; k < t.sampleFiles.size(); ++k) {  // a multisampled target: every sample, each as sample 0 is
      CpuImage sample = t.image;
      if (k > 0 && !readExr((dir / t.sampleFiles[k]).string(), sample, error))
        return fail(CaptureProblem::Corrupt, dirText + ": " + error);
      ti.samples.push_back(std::move(sample));
    }
    ti.image = std::move(t.image);
    ti.targetWidth = ti.image.width;
    ti.targetHeight = ti.image.height;
    f.absences[size_t(t.index)] = Absent::No;
  }
  c.manifest = std::move(m);
  out = std::move(c);
  if (problemOut) *problemOut = CaptureProblem::None;
  return true;
}

}  // namespace gb
