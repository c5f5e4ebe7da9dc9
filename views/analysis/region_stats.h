// Statistics of a rectangle of a frame (gblens's own or imported): per stored channel of each
// target, and per decoded quantity through the layout (normal angle to the view direction, eye
// depth, eye-space position, colours, scalars, ids). `gblens stats` prints them; the viewer's
// Region panel draws the same numbers and their histogram (RenderDoc #872, tev #228).
#pragma once
#include <cstdint>
#include <map>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/snapshot.h"

namespace gb {

struct RegionRect {
  uint32_t x = 0, y = 0, width = 0, height = 0;
};
// "X,Y,W,H" -> rect; false (with `error` saying why) when malformed or outside a WxH frame.
bool parseRegionRect(const std::string& text, uint32_t frameWidth, uint32_t frameHeight, RegionRect& out,
                     std::string& error);

// One series of values: a stored channel ("albedo_specular" / "Albedo.R") or a decoded quantity's
// component ("normal" / "angle_to_view_deg").
struct SeriesStats {
  std::string target, series, unit;
  bool surfacesOnly = false;  // decoded over the pixels that hold a surface only
  uint64_t count = 0;         // finite values (the moments and percentiles are over these)
  uint64_t nan = 0, posInf = 0, negInf = 0;
  double min = 0.0, max = 0.0, mean = 0.0, stddev = 0.0;  // population standard deviation
  double p1 = 0.0, p50 = 0.0, p99 = 0.0;                  // nearest rank: the ceil(p/100 n)-th smallest
  std::vector<uint64_t> histogram;                        // equal bins over [min, max]
  std::map<uint32_t, uint64_t> ids;                       // integer quantities: value -> pixels
};

struct RegionStats {
  RegionRect rect;
  uint64_t pixels = 0, surfacePixels = 0;  // in the rect; with a surface (all of them when unknown)
  bool surfaceKnown = false;               // the layout has a camera depth that says where surfaces are
  std::vector<SeriesStats> channels;       // stored channels, every pixel of the rect
  std::vector<SeriesStats> quantities;     // decoded quantities
  // The stored channel / decoded series of that name; null when absent.
  const SeriesStats* channel(const std::string& target, const std::string& series) const;
  const SeriesStats* quantity(const std::string& target, const std::string& series) const;
};

// Statistics of `rect` (frame pixels, must lie inside the frame), for every target the frame holds
// or only `target` (a layout target name; "" every one), with `bins` histogram bins.
RegionStats regionStats(const FrameSnapshot& f, const RegionRect& rect, const std::string& target = "",
                        int bins = 32);

// Statistics of plain values (non-finite ones counted apart): the one computation every series uses.
SeriesStats seriesStats(const std::vector<double>& values, int bins);

std::string regionStatsText(const RegionStats& s);
nlohmann::json regionStatsJson(const RegionStats& s);

}  // namespace gb
