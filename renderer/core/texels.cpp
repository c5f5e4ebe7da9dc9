// Packing and unpacking texels (see texels.h).
#include "renderer/core/texels.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <thread>

#include "renderer/core/assert.h"

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

// f(begin, end) over [0, n) in contiguous runs, on up to 8 threads for n of a million or more.
template <class F>
static void splitRuns(size_t n, const F& f) {
  const unsigned threads = n < (1u << 20) ? 1u : std::clamp(std::thread::hardware_concurrency(), 1u, 8u);
  std::vector<std::thread> pool;
  for (unsigned i = 1; i < threads; ++i) pool.emplace_back(f, n * i / threads, n * (i + 1) / threads);
  f(size_t(0), n / threads);
  for (std::thread& t : pool) t.join();
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
    splitRuns(texels, [&](size_t i0, size_t i1) {
      for (size_t i = i0; i < i1; ++i) {
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
    splitRuns(texels, [&](size_t i0, size_t i1) {
      for (size_t i = i0; i < i1; ++i) {
        uint32_t v;
        std::memcpy(&v, src + i * 4, 4);
        out[4 * i + 0] = uint16_t(v & 0x3FF);
        out[4 * i + 1] = uint16_t((v >> 10) & 0x3FF);
        out[4 * i + 2] = uint16_t((v >> 20) & 0x3FF);
        out[4 * i + 3] = uint16_t(v >> 30);
      }
    });
  } else {
    const size_t bytes = texels * packedTexelBytes(f);
    img.data.resize(bytes);  // no fill where the buffer already held as many
    splitRuns(bytes, [&](size_t b0, size_t b1) { std::memcpy(img.data.data() + b0, src + b0, b1 - b0); });
  }
}

void swapRedBlue(CpuImage& img) {
  GB_ASSERT(img.data.size() % 4 == 0);
  uint8_t* d = img.data.data();
  splitRuns(img.data.size() / 4, [d](size_t i0, size_t i1) {
    for (size_t i = i0; i < i1; ++i) std::swap(d[4 * i], d[4 * i + 2]);
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
