// A probed surface point followed across the frames of a sequence (the viewer's timeline,
// docs/temporal.md): its position in every other frame found by chaining reprojectPixel (motion.h)
// frame to frame, N -> N+1 -> ... and N -> N-1 -> ..., stopping where a step finds no surface or
// leaves the image; and a view's decoded value there in each frame reached (the plot over time).
#pragma once
#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "renderer/core/snapshot.h"
#include "views/analysis/view_table.h"

namespace gb {

// Frame i of the sequence (0-based, in frame order); null when it cannot be loaded (the track stops
// there). Shared: a caller's cache may drop a frame while the track still reads it.
using TrackFrames = std::function<std::shared_ptr<const FrameSnapshot>(size_t i)>;
// Frame i's jitter (pixels, as sequence.json gives it; null: not known, taken as none).
using TrackJitters = std::function<std::optional<glm::dvec2>(size_t i)>;

struct ProbeTrack {
  size_t frameCount = 0;
  size_t start = 0;                // the frame probed
  glm::ivec2 pixel{0};             // the pixel probed there
  size_t first = 0, last = 0;      // the frames the track reaches: [first, last], start among them
  // Per frame (frameCount entries; empty outside [first, last]): the point's continuous position
  // (texel (i, j)'s centre is (i + 0.5, j + 0.5)) and the texel holding it.
  std::vector<std::optional<glm::dvec2>> positions;
  std::vector<std::optional<glm::ivec2>> texels;
  std::string stopBefore, stopAfter;  // why it stops before `first` / after `last` ("" at the ends)
  // The view plotted: its name, the names of its components, and per component one value per frame
  // (NaN outside the track or where the frame holds no value there), as viewValue decodes it.
  std::string view;
  std::vector<std::string> components;
  std::vector<std::vector<double>> values;
};

// Follows pixel `pixel` of frame `start` through the `frameCount` frames and decodes `view` (a view
// of the start frame's layout; other frames: their view of the same name) along it. Each step starts
// from the texel holding the point and keeps its offset inside the texel, so a uniform motion (a
// camera translation over a plane) carries sub-texel positions exactly.
// With `jitters`, each frame's jitter is taken out of the point it shows and put into where the next
// frame shows it (a jittered sequence's points stay on their surface to a hundredth of a pixel).
ProbeTrack trackProbe(size_t frameCount, const TrackFrames& frames, size_t start, glm::ivec2 pixel, const ViewDef& view,
                      const TrackJitters& jitters = {});

// The track as JSON (the viewer's event log): the followed texels by frame index, the stops, the values.
nlohmann::json trackJson(const ProbeTrack& t);

}  // namespace gb
