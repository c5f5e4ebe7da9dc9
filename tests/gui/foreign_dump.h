// The application's own read-back of a frame (tests/subjects/foreign_deferred --dump DIR), decoded
// here from the application's README and the Vulkan formats, without gblens's decoder: the
// independent values the GUI tests hold the viewer's probe and region statistics to.
#pragma once
#include <array>
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace gb::gui {

struct ForeignDump {
  uint32_t width = 0, height = 0;
  std::map<std::string, std::string> bytes;  // target name -> its texels, rows top to bottom, packed
  std::map<std::string, uint32_t> texelBytes;

  // Reads DIR/camera.json and every file its "targets" list; false with `error` when a file's size
  // is not width x height x bytes_per_texel.
  bool load(const std::filesystem::path& dir, std::string& error);

  // Stored texels: byte `c` of an 8-bit target's texel, float `c` of an fp32 target's texel.
  uint8_t code(const std::string& target, uint32_t x, uint32_t y, uint32_t c = 0) const;
  float f32(const std::string& target, uint32_t x, uint32_t y, uint32_t c = 0) const;
  uint32_t f32Bits(const std::string& target, uint32_t x, uint32_t y, uint32_t c = 0) const;

  // Decoded as the application wrote them (its README: "The frame").
  bool surface(uint32_t x, uint32_t y) const;  // position.w, eye depth / far, is not the clear value 1
  double occlusion(uint32_t x, uint32_t y) const;                 // R8_UNORM: code / 255
  double albedo(uint32_t x, uint32_t y, uint32_t c) const;        // R8G8B8A8_SRGB: the sRGB EOTF of code / 255
  std::array<double, 3> normal(uint32_t x, uint32_t y) const;     // rgb * 2 - 1, made unit length
};

// Count, min, max and mean of plain values: what a region's series reports, computed here.
struct Summary {
  uint64_t count = 0;
  double min = 0.0, max = 0.0, mean = 0.0;
};
Summary summarize(const std::vector<double>& values);

}  // namespace gb::gui
