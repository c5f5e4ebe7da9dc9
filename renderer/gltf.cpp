// glTF loading: placeholder until the glTF issue lands (the loader replaces this file).
#include "renderer/gltf.h"

#include "renderer/builtin.h"

namespace gb {

Scene loadGltf(const std::string& path, int) {
  throw SceneError{path + ": glTF loading is not available in this build"};
}

}  // namespace gb
