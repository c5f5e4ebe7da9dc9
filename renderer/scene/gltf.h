// glTF 2.0 loading (.gltf, .glb) into a Scene, stricter than tinygltf about bad data.
// What is supported, ignored and rejected, and how materials and lights are mapped: docs/gltf.md.
#pragma once
#include <cstddef>
#include <cstdint>
#include <string>

#include "renderer/scene/scene.h"

namespace gb {

struct SceneLoadStats;  // renderer/builtin.h

// Throws SceneError (renderer/builtin.h) naming the file and the offending element.
// `stats`, when given, receives the load timing and what the file holds that gblens ignores.
Scene loadGltf(const std::string& path, int lightCount, SceneLoadStats* stats = nullptr);

// The same from bytes in memory (the fuzzer, tests). `name` is used in messages; external URIs
// are resolved in `baseDir`, and refused when it is empty.
Scene loadGltfMemory(const uint8_t* data, size_t size, const std::string& name, const std::string& baseDir,
                     int lightCount, SceneLoadStats* stats = nullptr);

}  // namespace gb
