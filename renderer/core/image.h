// A CPU copy of one target: raw texels exactly as the GPU stored them, plus how to decode them.
// Produced by read-back and by capture loading; consumed by views, probe, compare and tests.
#pragma once
#include <cstdint>
#include <cstring>
#include <string>
#include <vector>

namespace gb {

enum class PixelType : uint8_t { U8, I8, U16, I16, U32, F16, F32 };
// How stored integers map to values: UNORM (/255 or /65535), SNORM (/127 or /32767, clamped at
// -1), sRGB-encoded UNORM (decoded to linear), float, plain integer. RGB10A2 is unpacked to U16
// channels (Unorm10: /1023, alpha /3); D24 depth is a U32 holding 24 bits (Unorm24).
enum class Encoding : uint8_t { Unorm, Snorm, Srgb, Float, Uint, Unorm10, Unorm24 };

struct CpuImage {
  std::string name;                   // the target's name, e.g. "normal_shadow"
  std::vector<std::string> channels;  // e.g. {"N.X", "N.Y", "N.Z", "Shadow"}
  uint32_t width = 0, height = 0;
  PixelType type = PixelType::F32;
  Encoding encoding = Encoding::Float;
  std::vector<uint8_t> data;  // width * height * channels * size(type), rows top to bottom

  uint32_t channelCount() const { return uint32_t(channels.size()); }
  size_t texelBytes() const;
  bool empty() const { return data.empty(); }
  // The stored value's bits (for 8/16-bit types: the integer; for F32 the float's bits).
  uint32_t raw(uint32_t x, uint32_t y, uint32_t c) const;
  // The decoded value (UNORM/SNORM/sRGB -> float in their range, half -> float).
  double value(uint32_t x, uint32_t y, uint32_t c) const;
  // Index of a channel by name, or -1.
  int channel(const std::string& channelName) const;
};

size_t pixelTypeSize(PixelType t);
// What CpuImage::value gives for stored bits `raw` of channel `c` (channel 3 is alpha: sRGB and
// RGB10A2 store it linearly).
double decodeRaw(PixelType type, Encoding encoding, uint32_t c, uint32_t raw);
// One unit in the last place of `v` stored in a channel of this type and encoding: half and float
// ulps at |v| (half subnormals share the smallest exponent), one code step of normalised integers
// (their [0, 1] or [-1, 1] range), 1 for plain integers.
double storageUlp(PixelType t, Encoding e, double v);
float halfToFloat(uint16_t h);
uint16_t floatToHalf(float f);
double srgbToLinear(double v);
const char* name(PixelType t);
const char* name(Encoding e);

}  // namespace gb
