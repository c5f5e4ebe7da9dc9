// SCENE argument dispatch: built-in scenes by name, glTF files by extension.
#include <filesystem>

#include "renderer/scene/builtin.h"
#include "renderer/scene/gltf.h"

namespace gb {

Scene loadScene(const std::string& spec, int lightCount, SceneLoadStats* stats) {
  if (spec == "builtin:temple") return builtinTemple(lightCount);
  if (spec == "builtin:depth-range") return depthRangeScene();
  if (spec == "builtin:normal-sphere") return normalSphereScene(lightCount);
  if (spec.rfind("builtin:", 0) == 0)
    throw SceneError{"unknown built-in scene '" + spec +
                     "' (available: builtin:temple, builtin:depth-range, builtin:normal-sphere)"};
  std::filesystem::path path(spec);
  std::string ext = path.extension().string();
  for (auto& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".gltf" && ext != ".glb")
    throw SceneError{spec + ": not a scene (expected builtin:temple, a .gltf or a .glb file)"};
  std::error_code ec;
  if (!std::filesystem::exists(path, ec)) throw SceneError{spec + ": no such file"};
  if (!std::filesystem::is_regular_file(path, ec)) throw SceneError{spec + ": not a regular file"};
  return loadGltf(spec, lightCount, stats);
}

}  // namespace gb
