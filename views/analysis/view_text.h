// What hover and the status bar say about a view at a pixel: the stored channels exactly as the
// target holds them (integer codes, float bits' values) and the decoded value under the layout's names,
// units and spaces (visualize.h viewValue), for any layout.
#pragma once
#include <array>
#include <optional>
#include <string>
#include <vector>

#include "renderer/core/snapshot.h"
#include "views/analysis/view_table.h"

namespace gb {

// "Albedo (330, 540)  stored albedo_specular (rgba8_srgb) Albedo.R 29 Albedo.G 40 Albedo.B 12  ->
// linear R 0.01161 G 0.02122 B 0.003677"; "" when the frame does not hold the texel.
std::string viewValueText(const FrameSnapshot& f, const ViewDef& view, uint32_t x, uint32_t y);

// What the viewer prints inside a texel at high zoom (tev's values in texels): one line per component
// the view shows (`shown`: bit c = component c), "R 0.9216", each with the significant digits its
// storage holds (float 7, half 4, 8-bit 3 + 1, 10-bit 4, 16-bit 5 + 1; integers whole); no lines where
// the view has no value at the texel.
// `value` is viewValue's at the texel (the caller decodes it once; nothing: no lines).
std::vector<std::string> texelValueLines(const FrameSnapshot& f, const ViewDef& view,
                                         const std::optional<std::array<double, 4>>& value, uint32_t shown);
// The significant digits `texelValueLines` prints for a channel of this storage.
int storageDigits(PixelType t, Encoding e);

// One stored channel as the target holds it: the integer code of integer and normalised formats,
// the value of half and float channels (every digit a float needs).
std::string storedText(const CpuImage& image, uint32_t x, uint32_t y, uint32_t channel);

}  // namespace gb
