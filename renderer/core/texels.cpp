// Packing and unpacking texels (see texels.h).
#include "renderer/core/texels.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "renderer/core/assert.h"
#include "renderer/core/parallel_rows.h"

namespace gb {

uint32_t packedTexelBytes(TexelFormat f) {
  switch (f) {
    case TexelFormat::Rgba8Srgb:
    case TexelFormat::Rgba8Unorm:
    case TexelFormat::Rgba8Snorm:
    case TexelFormat::Rgb10a2Unorm:
    case TexelFormat::R32f:
    case TexelFormat::R32Uint:
    case TexelFormat::Rg16f:
    case TexelFormat::D32fS8:
    case TexelFormat::D24S8:
    case TexelFormat::D32f: return 4;
    case TexelFormat::D16: return 2;
    case TexelFormat::Rgba16Snorm:
    case TexelFormat::Rgba16f: return 8;
    case TexelFormat::Rgba32f: return 16;
  }
  GB_ASSERT(!"packedTexelBytes");
  return 0;
}

size_t packedImageBytes(TexelFormat f, uint32_t w, uint32_t h) {
  const size_t texels = size_t(w) * h;
  return texels * packedTexelBytes(f) + (texelFormatInfo(f).stencil ? texels : 0);
}

static CpuImage emptyImage(TexelFormat f, uint32_t w, uint32_t h) {
  const TexelFormatInfo& info = texelFormatInfo(f);
  CpuImage img;
  img.width = w;
  img.height = h;
  img.type = info.type;
  img.encoding = info.encoding;
  return img;
}

void unpackTexelsInto(TexelFormat f, const uint8_t* src, uint32_t w, uint32_t h, CpuImage& img) {
  std::vector<uint8_t> buffer = std::move(img.data);
  img = emptyImage(f, w, h);
  img.data = std::move(buffer);
  const size_t texels = size_t(w) * h;
  const TexelFormatInfo& info = texelFormatInfo(f);
  if (info.depth && info.stencil) {  // F32 Depth, F32 Stencil
    img.data.resize(texels * 8);
    float* out = reinterpret_cast<float*>(img.data.data());
    const uint8_t* stencil = src + texels * 4;
    parallelRows(h, texels, [&](uint32_t y0, uint32_t y1) {
      for (size_t i = size_t(y0) * w; i < size_t(y1) * w; ++i) {
        uint32_t bits;
        std::memcpy(&bits, src + i * 4, 4);
        float depth;
        if (f == TexelFormat::D24S8)
          depth = float(double(bits & 0xFFFFFF) / 16777215.0);
        else
          std::memcpy(&depth, &bits, 4);
        out[2 * i] = depth;
        out[2 * i + 1] = float(stencil[i]);
      }
    });
  } else if (f == TexelFormat::Rgb10a2Unorm) {
    img.data.resize(texels * 8);
    uint16_t* out = reinterpret_cast<uint16_t*>(img.data.data());
    parallelRows(h, texels, [&](uint32_t y0, uint32_t y1) {
      for (size_t i = size_t(y0) * w; i < size_t(y1) * w; ++i) {
        uint32_t v;
        std::memcpy(&v, src + i * 4, 4);
        out[4 * i + 0] = uint16_t(v & 0x3FF);
        out[4 * i + 1] = uint16_t((v >> 10) & 0x3FF);
        out[4 * i + 2] = uint16_t((v >> 20) & 0x3FF);
        out[4 * i + 3] = uint16_t(v >> 30);
      }
    });
  } else {
    const size_t row = size_t(w) * packedTexelBytes(f);
    img.data.resize(row * h);  // no fill where the buffer already held as many
    parallelRows(h, texels, [&](uint32_t y0, uint32_t y1) {
      std::memcpy(img.data.data() + y0 * row, src + y0 * row, (y1 - y0) * row);
    });
  }
}

void swapRedBlue(CpuImage& img) {
  GB_ASSERT(img.data.size() == size_t(img.width) * img.height * 4);
  uint8_t* d = img.data.data();
  const uint32_t w = img.width;
  parallelRows(img.height, size_t(w) * img.height, [d, w](uint32_t y0, uint32_t y1) {
    for (size_t i = size_t(y0) * w; i < size_t(y1) * w; ++i) std::swap(d[4 * i], d[4 * i + 2]);
  });
}

CpuImage unpackTexels(TexelFormat f, const uint8_t* src, uint32_t w, uint32_t h) {
  CpuImage img;
  unpackTexelsInto(f, src, w, h, img);
  return img;
}

std::vector<uint8_t> packTexels(const CpuImage& img, TexelFormat f) {
  const size_t texels = size_t(img.width) * img.height;
  const TexelFormatInfo& info = texelFormatInfo(f);
  std::vector<uint8_t> out;
  if (info.depth && info.stencil) {  // F32 Depth, F32 Stencil
    out.resize(texels * 5);
    for (size_t i = 0; i < texels; ++i) {
      const uint32_t x = uint32_t(i % img.width), y = uint32_t(i / img.width);
      float depth = float(img.value(x, y, 0));
      uint32_t bits;
      if (f == TexelFormat::D24S8)
        bits = uint32_t(std::lround(double(depth) * 16777215.0)) & 0xFFFFFF;
      else
        std::memcpy(&bits, &depth, 4);
      std::memcpy(&out[i * 4], &bits, 4);
      out[texels * 4 + i] = uint8_t(img.value(x, y, 1));
    }
  } else if (f == TexelFormat::Rgb10a2Unorm) {
    out.resize(texels * 4);
    for (size_t i = 0; i < texels; ++i) {
      const uint32_t x = uint32_t(i % img.width), y = uint32_t(i / img.width);
      uint32_t v = (img.raw(x, y, 0) & 0x3FF) | ((img.raw(x, y, 1) & 0x3FF) << 10) | ((img.raw(x, y, 2) & 0x3FF) << 20) |
                   (img.raw(x, y, 3) << 30);
      std::memcpy(&out[i * 4], &v, 4);
    }
  } else {
    GB_ASSERT(img.data.size() == texels * packedTexelBytes(f));
    out = img.data;
  }
  return out;
}

}  // namespace gb
