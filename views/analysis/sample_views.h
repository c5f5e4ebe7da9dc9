// Multisampled targets (a capture or a stream of an MSAA G-buffer, docs/attach.md "MSAA"): which
// sample the frame shows, and per target a view of the per-pixel spread of its samples.
#pragma once
#include <array>
#include <optional>
#include <vector>

#include "renderer/core/snapshot.h"
#include "views/analysis/view_table.h"

namespace gb {

// The most samples any target of the frame has (1: none is multisampled).
size_t frameSamples(const FrameSnapshot& f);
// Every multisampled target's image becomes its sample `k` (the last where it has fewer): views,
// hover, probe and region statistics then read that sample exactly. FrameSnapshot::sampleShown says which.
void showSample(FrameSnapshot& f, size_t k);
// A "NAME spread" view per multisampled target: at each pixel the largest, over the target's
// channels, of the difference between its samples' largest and smallest stored value (decoded
// channel values, CpuImage::value; integer channels such as ids: how many distinct values less one);
// empty where no sample holds a number.
std::vector<ViewDef> spreadViews(const FrameSnapshot& f);
std::optional<std::array<double, 4>> sampleSpread(const FrameSnapshot& f, uint32_t target, uint32_t x, uint32_t y);
// The spread of channel c of a multisampled target's samples at target texel (x, y), every plane
// of the image's size: for an integer channel (ids) how many distinct values less one, else the
// largest finite value less the smallest (NaN where no sample is finite). The probe shows it per
// channel; the spread view is the largest over the channels.
double channelSpread(const TargetImage& t, uint32_t x, uint32_t y, uint32_t c);

}  // namespace gb
