// Guessing what a target's channels hold, for a draft layout (import --suggest-layout): from its
// name (Blender's passes, Unreal's buffers, OIIO's channel names, common engine words), its storage
// format, and its texels (a unit-length xyz is a normal). Every quantity carries a "guess" note.
#pragma once
#include <set>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/image.h"
#include "renderer/core/layout.h"

namespace gb {

// The pixels that hold a surface (by the depth target), or none known (empty: every pixel).
struct SurfaceMask {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> at;  // width * height, 1: a surface
  bool surface(uint32_t x, uint32_t y) const { return at.empty() || at[size_t(y) * width + x]; }
};

// The layout's storage format name for a RenderDoc format name ("R16G16B16A16_FLOAT" -> "rgba16f",
// "D32S8" -> "d32s8"); "" when a layout cannot name it (BGRA, block-compressed, ...).
std::string storageFormatName(const std::string& renderDocFormat);

// The quantities of one target (a JSON list for the draft). `name` is the texture's or the EXR
// layer's name; `image` its texels (may be null); `used` the quantity names taken so far;
// `afterGBuffer`: a later pass writes it (a colour there is the lit or displayed picture, not albedo).
nlohmann::json guessQuantities(const std::string& name, const StorageFormat& format, const CpuImage* image,
                               const SurfaceMask& surface, std::set<std::string>& used, bool afterGBuffer = false);

// A layout target name from any text: lower case, a-z 0-9 _, unique among `used`.
std::string targetName(const std::string& text, std::set<std::string>& used);

}  // namespace gb
