// Built-in scenes (no files needed) and the one entry point that loads any SCENE argument.
#pragma once
#include <string>
#include <vector>

#include "renderer/scene/scene.h"

namespace gb {

Scene builtinTemple(int lightCount);
// builtin:depth-range: camera-facing cards at depths spaced in log from 1.5 near to far / 1.5
// (default 0.1 .. 1e5: a far/near ratio of 1e6), for depth-precision measurements.
// With `gap` > 0 every card has a twin behind it at depth x (1 + gap), drawn before it (so a depth
// test that cannot separate them keeps the twin: z-fighting, counted by its triangles).
Scene depthRangeScene(double znear = 0.1, double zfar = 1e5, double gap = 0.0);
// builtin:normal-sphere: a camera-filling card whose normals cover the sphere of directions
// uniformly (normal-encoding measurements over uniformly distributed unit vectors).
Scene normalSphereScene(int lightCount);
// Its map from the card's (u, v) in [0,1]^2 (u right, v down the screen) to unit normals: equal-area.
glm::dvec3 normalSphereDirection(double u, double v);

// A user mistake while loading (bad file, bad element): the message names the file and element.
struct SceneError {
  std::string message;
};

// What loading took and what the file holds beyond the Scene (gblens info).
struct SceneLoadStats {
  double parseMs = 0.0;   // reading files and the JSON/GLB structure (tinygltf), validation
  double decodeMs = 0.0;  // image decoding (OpenImageIO), wall time of the parallel decode
  double buildMs = 0.0;   // geometry, materials, nodes, cameras, lights into the Scene
  uint32_t fileMeshes = 0, filePrimitives = 0, fileNodes = 0, fileImages = 0;
  uint32_t pointLights = 0, spotLights = 0, directionalLights = 0;  // KHR_lights_punctual in the scene
  std::vector<std::string> ignored;  // present in the file, not drawn by gblens (one line each)
};

// SCENE as given on the command line: "builtin:temple" or a .gltf/.glb path. Throws SceneError.
// `lightCount` is used by the built-in scene and by files without lights of their own.
Scene loadScene(const std::string& spec, int lightCount, SceneLoadStats* stats = nullptr);

}  // namespace gb
