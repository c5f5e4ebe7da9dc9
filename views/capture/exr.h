// One target <-> one OpenEXR file, losslessly (docs/capture-format.md):
//   float32 targets -> FLOAT channels, half -> HALF, uint -> UINT (bit-exact, ZIP compressed);
//   8/16-bit integer-stored targets (UNORM, SNORM, sRGB, 10-bit) -> a UINT channel with the
//   stored integer ("<target>.raw.<channel>") plus a FLOAT channel with the decoded value
//   ("<target>.<channel>") for people and other tools; a channel named "Stencil" (read back
//   as float) is stored as UINT.
// Channel names are "<target>.<channel>" with the UI's names (e.g. "normal_shadow.N.X").
#pragma once
#include <string>
#include <vector>

#include "renderer/core/image.h"

namespace gb {

struct ExrChannel {
  std::string name;   // full EXR channel name
  std::string type;   // "uint", "half", "float"
  int source = 0;     // CpuImage channel index
  bool raw = false;   // holds CpuImage::raw() (else the value as stored, or decoded)
};

// The EXR channels a target image is written as, in CpuImage channel order.
std::vector<ExrChannel> exrChannels(const CpuImage& image);

// Writes `image` (its name is the target's) to `path`. False with `error` naming the file.
bool writeExr(const std::string& path, const CpuImage& image, std::string& error);

// Reads `path` into `image`, which arrives described (name, channels, type, encoding, size)
// from the manifest; the file must have exactly those channels, types and size.
bool readExr(const std::string& path, CpuImage& image, std::string& error);

}  // namespace gb
