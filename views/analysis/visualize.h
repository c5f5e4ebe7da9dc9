// Turns a target into an image a person can read, as the view table says (views/analysis/view_table.h):
// colour sRGB-encoded, normals decoded as colour, depth near-bright over its automatic range,
// grey channels, coverage as a heat map. Used by `gblens render --target` and captures' previews;
// the viewer maps the same table on the GPU (views/ui/view_map).
#pragma once
#include "renderer/core/snapshot.h"
#include "views/analysis/view_table.h"
#include "views/capture/image_io.h"

namespace gb {

// The view of a frame; an empty image when the frame does not hold the view's target.
Rgba8Image visualize(ViewKind view, const FrameSnapshot& frame);

// Heat-map colour for a count (0 = black, then blue -> green -> yellow -> red at `max`).
void heatColor(double count, double max, uint8_t out[3]);

}  // namespace gb
