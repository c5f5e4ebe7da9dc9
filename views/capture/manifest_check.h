// The one reading of a capture's manifest.json and lights.json into a frame's description, shared
// by the writer and the readers: loadCapture runs it on what it loads; writeCapture (capture,
// import) runs it on the files it has just written, before the atomic rename, so that no capture is
// written that probe, check, stats, compare or view would refuse. Every field is read through the
// checked accessor (renderer/core/json_read.h): a wrong type, a non-finite number (JSON null), an
// out-of-range integer or a name that cannot be a file or EXR channel name is one line naming it.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/image.h"
#include "renderer/core/json_read.h"
#include "renderer/core/snapshot.h"

namespace gb {

// A target the manifest lists: its index in the layout, its file and its image, described
// (name, channels, type, encoding, size) but without texels.
struct ManifestTarget {
  int index = -1;
  std::string file;
  CpuImage image;
  std::vector<std::string> sampleFiles;  // a multisampled target: every sample's file (the first is `file`)
};

// The largest whole target a capture holds (texels): what readExr may allocate for one.
constexpr uint64_t kMaxCaptureTexels = 1ull << 28;

// The manifest's format and version ("manifest.json: not a gblens capture manifest", ...).
bool checkManifestFormat(const nlohmann::json& m, const std::string& file, std::string& error);

// The file list: {"NAME": {"bytes": N, "sha256": HEX}}, names plain file names of the folder.
struct ManifestFile {
  std::string name, sha256;
  uint64_t bytes = 0;
};
bool manifestFiles(const nlohmann::json& m, const std::string& file, std::vector<ManifestFile>& out, std::string& error);

// Options, camera, layout, sun, sky, lights (from lights.json), the method, and the targets; `f`
// gets everything but the images. `file`/`lightsFile` name the two in messages.
bool frameFromManifest(const nlohmann::json& m, const nlohmann::json& lights, const std::string& file,
                       const std::string& lightsFile, FrameSnapshot& f, std::vector<ManifestTarget>& targets,
                       std::string& error);

// The manifest against itself (manifest_sanity.cpp; frameFromManifest runs it last): the frame's
// size is every target's (its layout's size, gblens's shadow map options.shadow_map_size) and the
// size fields'; the camera's ranges (yfov, aspect, znear < zfar), its matrices each other's inverses
// and its projection a perspective or orthographic one; lights, sun and sky within a 32-bit float's
// range. Throws JsonError naming the field.
void checkManifestConsistency(const JsonIn& m, const JsonIn& lights, const FrameSnapshot& f,
                              const std::vector<ManifestTarget>& targets);

// What writeCapture runs on the folder it wrote (before renaming it into place): manifest.json and
// lights.json read back from disk and through frameFromManifest.
bool checkWrittenManifest(const std::string& dir, std::string& error);

}  // namespace gb
