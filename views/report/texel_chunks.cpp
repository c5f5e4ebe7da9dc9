// The report's texel coding (texel_chunks.h); views/report/page.js's decodeTexels is its inverse.
#include "views/report/texel_chunks.h"

#include <zlib.h>

#include "renderer/core/assert.h"

namespace gb {

namespace {

int64_t signExtend(uint32_t v, uint32_t bits) {
  const int64_t top = int64_t(1) << (bits - 1);
  return int64_t(v) >= top ? int64_t(v) - 2 * top : int64_t(v);
}

}  // namespace

void encodeTexels(const TexelArray& a, const TexelArray* ref, uint32_t width, uint32_t height, uint32_t passIndex,
                  uint32_t row0, uint32_t row1, std::vector<uint8_t>& out) {
  GB_ASSERT(passIndex < 5 && row1 <= height);
  GB_ASSERT(a.values.size() == size_t(a.planes) * width * height);
  GB_ASSERT(!ref || (ref->planes == a.planes && ref->bytes == a.bytes && ref->values.size() == a.values.size()));
  const TexelPass& pass = kTexelPasses[passIndex];
  const uint32_t cols = width > pass.x0 ? (width - pass.x0 + pass.dx - 1) / pass.dx : 0;
  std::vector<uint32_t> rows;  // the image rows of the pass inside [row0, row1)
  for (uint32_t y = pass.y0; y < height; y += pass.dy)
    if (y >= row0 && y < row1) rows.push_back(y);
  const size_t count = size_t(cols) * rows.size(), start = out.size();
  const uint32_t bits = 8 * a.bytes, mask = bits == 32 ? ~0u : (1u << bits) - 1;
  out.resize(start + count * a.planes * a.bytes);
  std::vector<uint32_t> prev(cols), cur(cols);  // pass 0: the rows' values less the reference
  for (uint32_t p = 0; p < a.planes; ++p) {
    const size_t plane = size_t(p) * width * height;
    const auto delta = [&](size_t at) { return (a.values[plane + at] - (ref ? ref->values[plane + at] : 0u)) & mask; };
    std::fill(prev.begin(), prev.end(), 0u);
    for (size_t j = 0; j < rows.size(); ++j) {
      const uint32_t y = rows[j];
      uint32_t before = 0;  // the residual of the texel before, in this row of the pass
      for (uint32_t i = 0; i < cols; ++i) {
        const uint32_t x = pass.x0 + i * pass.dx;
        const size_t at = size_t(y) * width + x;
        uint32_t r;
        if (passIndex == 0) {
          cur[i] = delta(at);
          const uint32_t left = i ? cur[i - 1] : 0u, up = prev[i], upLeft = i ? prev[i - 1] : 0u;
          r = (cur[i] - (left + up - upLeft)) & mask;
        } else {
          const int64_t first = signExtend(delta(at - size_t(pass.oy) * width - pass.ox), bits);
          const bool second = x + pass.ox < width && y + pass.oy < row1;
          const int64_t mean = second ? (first + signExtend(delta(at + size_t(pass.oy) * width + pass.ox), bits)) >> 1 : first;
          const uint32_t residual = (delta(at) - uint32_t(mean)) & mask;
          r = (residual - before) & mask;
          before = residual;
        }
        const uint32_t z = ((r << 1) ^ (0u - (r >> (bits - 1)))) & mask;  // zig-zag: small magnitudes small
        const size_t k = (size_t(p) * rows.size() + j) * cols + i;      // the value's place in its byte plane
        for (uint32_t b = 0; b < a.bytes; ++b) out[start + (size_t(b) * a.planes * count) + k] = uint8_t(z >> (8 * b));
      }
      std::swap(prev, cur);
    }
  }
}

std::string deflatedLiteral(const std::vector<uint8_t>& bytes) {
  uLongf size = compressBound(uLong(bytes.size()));
  std::vector<unsigned char> deflated(size);
  const int z = compress2(deflated.data(), &size, bytes.data(), uLong(bytes.size()), 6);
  GB_ASSERT(z == Z_OK);
  std::string out;
  out.reserve(size + size / 64 + 2);
  out += '"';
  for (uLongf i = 0; i < size; ++i) {
    const unsigned char c = deflated[i];
    if (c == '"') out += "\\\"";
    else if (c == '\\') out += "\\\\";
    else if (c == '\n') out += "\\n";
    else if (c == '\r') out += "\\r";
    else out += char(c);
  }
  out += '"';
  return out;
}

}  // namespace gb
