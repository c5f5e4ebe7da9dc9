// What import.cpp and import_camera.cpp share (not for other callers: import.h is the interface).
#pragma once
#include <string>

#include "views/import/import.h"

namespace gb {

// Where a target's source file is (import.cpp).
std::string sourcePath(const ImportInput& in, const LayoutTarget& t);

// The layout's camera with its matrices filled from the sidecar (looked for beside the imported
// files only) or the uniform buffer, for images of w x h; `from` says where they were read
// (import_camera.cpp).
bool resolveCamera(const ImportInput& in, LayoutCamera& c, uint32_t w, uint32_t h, std::string& error);

}  // namespace gb
