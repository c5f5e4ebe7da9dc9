// CpuImage decoding: the one place that knows how each stored format maps to values.
#include "renderer/core/image.h"

#include <algorithm>
#include <cmath>

namespace gb {

size_t pixelTypeSize(PixelType t) {
  switch (t) {
    case PixelType::U8:
    case PixelType::I8: return 1;
    case PixelType::U16:
    case PixelType::I16:
    case PixelType::F16: return 2;
    case PixelType::U32:
    case PixelType::F32: return 4;
  }
  return 0;
}

const char* name(PixelType t) {
  static const char* n[] = {"u8", "i8", "u16", "i16", "u32", "f16", "f32"};
  return n[int(t)];
}
const char* name(Encoding e) {
  static const char* n[] = {"unorm", "snorm", "srgb", "float", "uint", "unorm10", "unorm24"};
  return n[int(e)];
}

size_t CpuImage::texelBytes() const { return pixelTypeSize(type) * channels.size(); }

float halfToFloat(uint16_t h) {
  uint32_t sign = uint32_t(h >> 15) << 31, exp = (h >> 10) & 0x1F, mant = h & 0x3FF, bits;
  if (exp == 0) {
    if (mant == 0) {
      bits = sign;
    } else {  // subnormal: renormalize
      exp = 127 - 15 + 1;
      while (!(mant & 0x400)) {
        mant <<= 1;
        --exp;
      }
      bits = sign | (exp << 23) | ((mant & 0x3FF) << 13);
    }
  } else if (exp == 31) {
    bits = sign | 0x7F800000u | (mant << 13);
  } else {
    bits = sign | ((exp + 127 - 15) << 23) | (mant << 13);
  }
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

uint16_t floatToHalf(float f) {  // round to nearest even
  uint32_t x;
  std::memcpy(&x, &f, 4);
  uint32_t sign = (x >> 16) & 0x8000, absx = x & 0x7FFFFFFF;
  if (absx >= 0x7F800000) return uint16_t(sign | 0x7C00 | (absx > 0x7F800000 ? 0x200 : 0));
  if (absx >= 0x477FF000) return uint16_t(sign | 0x7C00);  // rounds to >= 65520: Inf
  if (absx < 0x38800000) {                                 // subnormal or zero
    float a;
    std::memcpy(&a, &absx, 4);
    return uint16_t(sign | uint32_t(std::nearbyint(a * 16777216.0f)));
  }
  uint32_t mant = absx & 0x7FFFFF, exp = (absx >> 23) - 127 + 15;
  uint32_t h = (exp << 10) | (mant >> 13);
  uint32_t rest = mant & 0x1FFF;
  if (rest > 0x1000 || (rest == 0x1000 && (h & 1))) ++h;
  return uint16_t(sign | h);
}

double srgbToLinear(double v) { return v <= 0.04045 ? v / 12.92 : std::pow((v + 0.055) / 1.055, 2.4); }

uint32_t CpuImage::raw(uint32_t x, uint32_t y, uint32_t c) const {
  const uint8_t* p = data.data() + (size_t(y) * width + x) * texelBytes() + c * pixelTypeSize(type);
  switch (type) {
    case PixelType::U8:
    case PixelType::I8: return p[0];
    case PixelType::U16:
    case PixelType::I16:
    case PixelType::F16: {
      uint16_t v;
      std::memcpy(&v, p, 2);
      return v;
    }
    case PixelType::U32:
    case PixelType::F32: {
      uint32_t v;
      std::memcpy(&v, p, 4);
      return v;
    }
  }
  return 0;
}

double CpuImage::value(uint32_t x, uint32_t y, uint32_t c) const { return decodeRaw(type, encoding, c, raw(x, y, c)); }

double decodeRaw(PixelType type, Encoding encoding, uint32_t c, uint32_t r) {
  switch (type) {
    case PixelType::F32: {
      float f;
      std::memcpy(&f, &r, 4);
      return f;
    }
    case PixelType::F16: return halfToFloat(uint16_t(r));
    case PixelType::I8: return std::fmax(double(int8_t(uint8_t(r))) / 127.0, -1.0);
    case PixelType::I16: return std::fmax(double(int16_t(uint16_t(r))) / 32767.0, -1.0);
    default: break;
  }
  double unormMax = type == PixelType::U16 ? 65535.0 : 255.0;
  switch (encoding) {
    case Encoding::Unorm: return double(r) / unormMax;
    case Encoding::Srgb: return c == 3 ? double(r) / 255.0 : srgbToLinear(double(r) / 255.0);
    case Encoding::Unorm10: return c == 3 ? double(r) / 3.0 : double(r) / 1023.0;
    case Encoding::Unorm24: return double(r) / 16777215.0;
    default: return double(r);
  }
}

int CpuImage::channel(const std::string& n) const {
  for (size_t i = 0; i < channels.size(); ++i)
    if (channels[i] == n) return int(i);
  return -1;
}

double storageUlp(PixelType t, Encoding e, double v) {
  const double a = std::abs(v);
  switch (t) {
    case PixelType::F16: {
      const int exponent = a > 0.0 ? int(std::floor(std::log2(a))) : -14;
      return std::ldexp(1.0, std::max(exponent, -14) - 10);
    }
    case PixelType::F32: {
      const float f = float(a);
      return double(std::nextafter(f, INFINITY)) - double(f);
    }
    case PixelType::U8: return 1.0 / 255.0;
    case PixelType::I8: return 1.0 / 127.0;
    case PixelType::U16: return e == Encoding::Unorm10 ? 1.0 / 1023.0 : 1.0 / 65535.0;
    case PixelType::I16: return 1.0 / 32767.0;
    case PixelType::U32: return e == Encoding::Unorm24 ? 1.0 / 16777215.0 : 1.0;
  }
  return 0.0;
}

}  // namespace gb
