// The report's texel coding (texel_chunks.h); views/report/page.js's decodeTexels is its inverse.
#include "views/report/texel_chunks.h"

#include <zlib.h>

#include "renderer/core/assert.h"

namespace gb {

void encodeTexels(const TexelArray& a, const TexelArray* ref, uint32_t width, uint32_t height, const TexelPass& pass,
                  uint32_t row0, uint32_t row1, std::vector<uint8_t>& out) {
  GB_ASSERT(a.values.size() == size_t(a.planes) * width * height);
  GB_ASSERT(!ref || (ref->planes == a.planes && ref->bytes == a.bytes && ref->values.size() == a.values.size()));
  const uint32_t cols = width > pass.x0 ? (width - pass.x0 + pass.dx - 1) / pass.dx : 0;
  std::vector<uint32_t> rows;  // the image rows of the pass inside [row0, row1)
  for (uint32_t y = pass.y0; y < height; y += pass.dy)
    if (y >= row0 && y < row1) rows.push_back(y);
  const size_t count = size_t(cols) * rows.size(), start = out.size();
  const uint32_t bits = 8 * a.bytes, mask = bits == 32 ? ~0u : (1u << bits) - 1;
  out.resize(start + count * a.planes * a.bytes);
  std::vector<uint32_t> prev(cols), cur(cols);  // the rows' values less the reference
  for (uint32_t p = 0; p < a.planes; ++p) {
    const size_t plane = size_t(p) * width * height;
    std::fill(prev.begin(), prev.end(), 0u);
    for (size_t j = 0; j < rows.size(); ++j) {
      for (uint32_t i = 0; i < cols; ++i) {
        const size_t at = plane + size_t(rows[j]) * width + pass.x0 + size_t(i) * pass.dx;
        cur[i] = (a.values[at] - (ref ? ref->values[at] : 0u)) & mask;
        const uint32_t left = i ? cur[i - 1] : 0u, up = prev[i], upLeft = i ? prev[i - 1] : 0u;
        const uint32_t r = (cur[i] - (left + up - upLeft)) & mask;
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
