// What import.cpp and import_camera.cpp share (not for other callers: import.h is the interface).
#pragma once
#include <string>

#include "renderer/core/texels.h"
#include "views/import/import.h"

namespace gb {

// Where a target's source file is (import.cpp).
std::string sourcePath(const ImportInput& in, const LayoutTarget& t);

// Whether a file the layout names (not one given on the command line) may be read: inside the
// layout's folder or a given file's folder, after symlinks, unless allowOutsideSources; else false
// with why in `error` ("WHERE: FIELD \"PATH\": outside ...") (import_source.cpp).
bool sourceAllowed(const ImportInput& in, const std::string& path, const std::string& where, const std::string& field,
                   std::string& error);

// Raw dumps (import_raw.cpp): the GPU format a layout format names, when it is one (its dumps are
// packed as texels.h says); the bytes a packed dump of w x h texels takes; a packed dump's texels
// (RenderDoc's, a live attachment's, a raw file's), at least its bytes; and a raw file's target,
// its size checked against what the layout explains (offset, rows, row_stride, the file's other dumps).
bool gpuFormatOf(const LayoutTarget& t, TexelFormat& gpu);
size_t dumpBytes(const LayoutTarget& t, uint32_t w, uint32_t h);
bool unpackDump(const uint8_t* data, size_t bytes, const LayoutTarget& t, uint32_t w, uint32_t h, const std::string& at,
                CpuImage& img, std::string& error);
bool readRawDump(const ImportInput& in, const LayoutTarget& lt, const std::string& path, uint32_t w, uint32_t h,
                 const std::string& where, CpuImage& img, std::string& error);

// The layout's camera with its matrices filled from the sidecar (looked for beside the imported
// files only) or the uniform buffer, for images of w x h; `from` says where they were read
// (import_camera.cpp).
bool resolveCamera(const ImportInput& in, LayoutCamera& c, uint32_t w, uint32_t h, std::string& error);

}  // namespace gb
