// The probe's track across a sequence (probe_track.h): the point reprojected frame to frame in both
// directions from the probed frame, then the view decoded at each texel reached.
#include "views/analysis/probe_track.h"

#include <algorithm>
#include <cmath>
#include <limits>

#include "views/analysis/motion.h"
#include "views/analysis/visualize.h"

namespace gb {

namespace {

// One step of the chain: where the point at `from`'s position is in `to` (the offset inside its
// texel kept), or why it is not followed there.
std::optional<glm::dvec2> step(const FrameSnapshot& from, glm::dvec2 position, const FrameSnapshot& to, glm::dvec2 jFrom,
                               glm::dvec2 jTo, std::string& why) {
  const glm::ivec2 texel(int(std::floor(position.x)), int(std::floor(position.y)));
  const std::optional<glm::dvec3> point = surfacePoint(from, uint32_t(texel.x), uint32_t(texel.y), jFrom);
  std::optional<glm::dvec2> centre = point ? projectToPixel(to.camera, *point) : std::nullopt;
  if (centre) *centre += jTo;  // where the jittered frame shows it
  if (!centre) {
    why = "no static surface to follow (no depth there, or behind the next frame's camera)";
    return std::nullopt;
  }
  const glm::dvec2 p = *centre + (position - (glm::dvec2(texel) + 0.5));
  if (!(p.x >= 0.0 && p.y >= 0.0 && p.x < double(to.options.width) && p.y < double(to.options.height))) {
    why = "the point leaves the image";
    return std::nullopt;
  }
  return p;
}

// The view of `frame` that shows what `view` shows in the probed frame (its layout's of that name).
std::optional<ViewDef> sameView(const FrameSnapshot& frame, const FrameSnapshot& probed, const ViewDef& view) {
  if (frame.layout.name == probed.layout.name) return view;
  const std::vector<ViewDef> views = layoutViews(frame.layout);
  const int k = findView(views, view.name);
  if (k < 0 || views[size_t(k)].visual != view.visual) return std::nullopt;
  return views[size_t(k)];
}

// The view's decoded components at frame i's texel of the track (left NaN where the frame has none).
void decodeAt(ProbeTrack& t, size_t i, const FrameSnapshot& f, const FrameSnapshot& probed, const ViewDef& view) {
  const std::optional<ViewDef> d = view.quantity >= 0 ? sameView(f, probed, view) : std::nullopt;
  if (!d || d->quantity < 0) return;  // not a layout quantity's view: nothing to decode
  const glm::ivec2 texel = *t.texels[i];
  const std::optional<std::array<double, 4>> value = viewValue(f, *d, uint32_t(texel.x), uint32_t(texel.y));
  if (!value) return;
  for (size_t c = 0; c < t.values.size(); ++c) t.values[c][i] = (*value)[c];
}

// Follows the track from `start` towards `direction` (+1, -1) until a step fails or the frames end,
// decoding the view in each frame reached (each frame is asked for once).
void follow(ProbeTrack& t, const TrackFrames& frames, const TrackJitters& jitters,
            const std::shared_ptr<const FrameSnapshot>& probed, const ViewDef& view, int direction) {
  auto jitter = [&](int64_t i) { return jitters ? jitters(size_t(i)).value_or(glm::dvec2(0.0)) : glm::dvec2(0.0); };
  std::shared_ptr<const FrameSnapshot> from = probed;
  std::string& stop = direction > 0 ? t.stopAfter : t.stopBefore;
  for (int64_t i = int64_t(t.start) + direction; i >= 0 && i < int64_t(t.frameCount); i += direction) {
    std::shared_ptr<const FrameSnapshot> to = frames(size_t(i));
    if (!to) {
      stop = "frame index " + std::to_string(i) + " could not be loaded";
      return;
    }
    const std::optional<glm::dvec2> p =
        step(*from, *t.positions[size_t(i - direction)], *to, jitter(i - direction), jitter(i), stop);
    if (!p) return;
    t.positions[size_t(i)] = p;
    t.texels[size_t(i)] = glm::ivec2(int(std::floor(p->x)), int(std::floor(p->y)));
    (direction > 0 ? t.last : t.first) = size_t(i);
    decodeAt(t, size_t(i), *to, *probed, view);
    from = std::move(to);
  }
}

}  // namespace

ProbeTrack trackProbe(size_t frameCount, const TrackFrames& frames, size_t start, glm::ivec2 pixel, const ViewDef& view,
                      const TrackJitters& jitters) {
  ProbeTrack t;
  t.frameCount = frameCount;
  t.start = t.first = t.last = start;
  t.pixel = pixel;
  t.positions.resize(frameCount);
  t.texels.resize(frameCount);
  t.view = view.name;
  const size_t n = std::min<size_t>(view.components, 4);
  for (size_t c = 0; c < n; ++c)
    t.components.push_back(c < view.componentNames.size() && !view.componentNames[c].empty() ? view.componentNames[c] : view.name);
  t.values.assign(n, std::vector<double>(frameCount, std::numeric_limits<double>::quiet_NaN()));
  const std::shared_ptr<const FrameSnapshot> probed = start < frameCount ? frames(start) : nullptr;
  if (!probed || pixel.x < 0 || pixel.y < 0 || uint32_t(pixel.x) >= probed->options.width ||
      uint32_t(pixel.y) >= probed->options.height) {
    t.stopBefore = t.stopAfter = probed ? "the pixel is outside the probed frame" : "the probed frame could not be loaded";
    return t;
  }
  t.positions[start] = glm::dvec2(pixel) + 0.5;
  t.texels[start] = pixel;
  decodeAt(t, start, *probed, *probed, view);
  follow(t, frames, jitters, probed, view, +1);
  follow(t, frames, jitters, probed, view, -1);
  return t;
}

nlohmann::json trackJson(const ProbeTrack& t) {
  nlohmann::json texels = nlohmann::json::array(), positions = nlohmann::json::array();
  for (size_t i = 0; i < t.frameCount; ++i) {
    texels.push_back(t.texels[i] ? nlohmann::json::array({t.texels[i]->x, t.texels[i]->y}) : nlohmann::json());
    positions.push_back(t.positions[i] ? nlohmann::json::array({t.positions[i]->x, t.positions[i]->y}) : nlohmann::json());
  }
  nlohmann::json values = nlohmann::json::array();  // per component: its name and a value per frame (null: none)
  for (size_t c = 0; c < t.values.size(); ++c) {
    nlohmann::json series = nlohmann::json::array();
    for (double v : t.values[c]) series.push_back(std::isfinite(v) ? nlohmann::json(v) : nlohmann::json());
    values.push_back({{"component", t.components[c]}, {"values", series}});
  }
  return {{"start", t.start},        {"pixel", {t.pixel.x, t.pixel.y}}, {"first", t.first},
          {"last", t.last},          {"texels", texels},                {"positions", positions},
          {"stop_before", t.stopBefore}, {"stop_after", t.stopAfter},   {"view", t.view},
          {"values", values}};
}

}  // namespace gb
