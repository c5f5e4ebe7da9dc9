// Built-in scenes (no files needed) and the one entry point that loads any SCENE argument.
#pragma once
#include <string>

#include "renderer/scene.h"

namespace gb {

Scene builtinTemple(int lightCount);
// builtin:depth-range: camera-facing cards at depths spaced in log from 1.5 near to far / 1.5
// (default 0.1 .. 1e5: a far/near ratio of 1e6), for depth-precision measurements.
Scene depthRangeScene(double znear = 0.1, double zfar = 1e5);

// A user mistake while loading (bad file, bad element): the message names the file and element.
struct SceneError {
  std::string message;
};

// SCENE as given on the command line: "builtin:temple" or a .gltf/.glb path. Throws SceneError.
// `lightCount` is used by the built-in scene and by files without lights of their own.
Scene loadScene(const std::string& spec, int lightCount);

}  // namespace gb
