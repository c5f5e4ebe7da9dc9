// The compare report's texel data, coded so a page shows a coarse image at once and the rest when
// asked: texels in five interleaved passes (coarse to fine, as PNG's Adam7 but in a 4x4 cell),
// fine passes in bands of rows; each value predicted from its neighbours, stored as bytes. page.js
// undoes it (texel_chunks.js); docs/report.md states the format.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

namespace gb {

struct TexelPass {
  uint32_t x0, y0, dx, dy;  // texels x0 + i dx, y0 + j dy
  uint32_t ox, oy;          // a finer pass's texel lies midway between the known ones at -+(ox, oy)
};
// Pass 0: one texel per 4x4 cell; 1 and 2 make it one per 2x2; 3 and 4 every texel. Each finer pass
// fills the midpoints of what the passes before it hold: pass 1 between pass 0's texels in a row,
// pass 2 between the rows so far, 3 between texels in a row, 4 between rows.
inline constexpr TexelPass kTexelPasses[5] = {
    {0, 0, 4, 4, 0, 0}, {2, 0, 4, 4, 2, 0}, {0, 2, 2, 4, 0, 2}, {1, 0, 2, 2, 1, 0}, {0, 1, 1, 2, 0, 1}};
// Rows per band of the fine chunks (passes 3 and 4): what one hover or a zoomed-in pane loads.
inline constexpr uint32_t kTexelBand = 128;

// One array over the whole image: `planes` planes (channels or components) of width x height values
// of `bytes` bytes each (the stored bits; floats as their bits), plane-major.
struct TexelArray {
  uint32_t bytes = 4, planes = 1;
  std::vector<uint32_t> values;
};

// Appends the texels of pass `pass` (kTexelPasses) whose rows lie in [row0, row1) of array `a` to
// `out`. Each value less the same texel of `ref` (when given: B coded against A, nothing left where
// they agree) is predicted, modulo 2^(8 bytes) with the values read as signed: in pass 0 by left + up -
// up-left within the pass; in a finer pass by the mean (rounded down) of the two known texels it lies
// between, or the first alone where the second is outside the image or [row0, row1), less the residual
// of the texel before it in the pass's row. What is left is zig-zag folded and written as the values'
// lowest bytes, then their next bytes, ... (slowly varying high bytes deflate together).
void encodeTexels(const TexelArray& a, const TexelArray* ref, uint32_t width, uint32_t height, uint32_t pass,
                  uint32_t row0, uint32_t row1, std::vector<uint8_t>& out);

// zlib-deflated `bytes` as a JavaScript string literal whose characters' low bytes are the bytes,
// for a script loaded with charset x-user-defined (the Encoding Standard: byte b >= 0x80 decodes to
// U+F700 + b): one byte per byte where base64 would take four per three. Quote, backslash, CR and LF
// are escaped.
std::string deflatedLiteral(const std::vector<uint8_t>& bytes);

}  // namespace gb
