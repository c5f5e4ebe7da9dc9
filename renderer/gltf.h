// glTF 2.0 loading (.gltf, .glb) into a Scene, stricter than tinygltf about bad data.
#pragma once
#include <string>

#include "renderer/scene.h"

namespace gb {

// Throws SceneError (renderer/builtin.h) naming the file and the offending element.
Scene loadGltf(const std::string& path, int lightCount);

}  // namespace gb
