// Motion vectors checked by reprojection (`gblens motion`, docs/temporal.md): every surface pixel of
// frame N carried into frame N-1 by its depth and both cameras says what a static point's vector must
// be; the convention that explains the stored vectors best (units, direction, y axis, scale, jitter,
// lag) is detected and set against the layout's, moving objects are checked by warping N-1's G-buffer.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "renderer/core/image.h"
#include "renderer/core/layout.h"
#include "renderer/core/snapshot.h"

namespace gb {

// One frame of a sequence as analysis sees it: the snapshot and what the sequence says of it.
struct TemporalFrame {
  const FrameSnapshot* frame = nullptr;
  int64_t number = 0;
  std::optional<double> time;
  std::optional<glm::dvec2> jitter;  // pixels, x right, y down
};

// Where the surface at pixel centre (x + 0.5, y + 0.5) of `from` is in `to`, in `to`'s pixel
// coordinates (continuous: texel (i, j)'s centre is (i + 0.5, j + 0.5)), for a point that did not
// move: its position from `from`'s depth (or stored position) and camera, projected by `to`'s camera.
// Null where `from` holds no surface or the point is behind `to`'s camera.
std::optional<glm::dvec2> reprojectPixel(const FrameSnapshot& from, uint32_t x, uint32_t y, const FrameSnapshot& to);

// The world-space point pixel (x, y) of `f` shows (from its depth, or a stored position), its centre
// moved back by the frame's jitter; and a world point in a camera's unjittered pixel coordinates.
std::optional<glm::dvec3> surfacePoint(const FrameSnapshot& f, uint32_t x, uint32_t y, glm::dvec2 jitter);
std::optional<glm::dvec2> projectToPixel(const Camera& camera, const glm::dvec3& world);
// A world point's depth along the camera's view axis (null behind it).
std::optional<double> viewDepthOf(const Camera& camera, const glm::dvec3& world);

// How a layout's stored vector relates to the screen motion. The layout's motion quantity declares
// one (layout-format.md: units, direction, y, jitter); `gblens motion` detects one.
struct MotionConvention {
  MotionUnits units = MotionUnits::Pixels;
  bool toPrevious = true;       // the vector points from this frame's position to the previous one's
  bool yUp = false;             // +y is up the image
  double scale = 1.0;           // stored = scale x the true vector (0.5: made for a half-size target)
  bool jitterIncluded = false;  // the difference of the jittered positions, not the unjittered ones
  int lag = 0;                  // 1: the vectors are the previous frame's ("one frame late")
};
// Which of a detected convention's fields the frames decide (a field no alternative explains worse,
// e.g. the units when the camera did not move, or the lag when the motion did not change, is not).
struct MotionDecided {
  bool units = false, direction = false, y = false, scale = false, jitter = false, lag = false;
};
MotionConvention declaredConvention(const Quantity& motion);
// The convention's fields; with `decided`, an undecided field is null.
nlohmann::json conventionJson(const MotionConvention& c, const MotionDecided* decided = nullptr);
// What differs between the declared and a detected convention over its decided fields, each as
// people say it ("y is flipped", "vectors are half length", "one frame late"); empty when they agree.
std::vector<std::string> conventionDifferences(const MotionConvention& declared, const MotionConvention& detected,
                                               const MotionDecided& decided);
// The stored vector a convention gives for the true screen motion `m` (pixels, toward the previous
// frame, +y down, jitter excluded) with `jitterDelta` = previous jitter - current jitter, in the
// stored units; and back: the true motion a stored vector means under the convention.
glm::dvec2 storedFromMotion(const MotionConvention& c, glm::dvec2 m, glm::dvec2 jitterDelta, uint32_t width, uint32_t height);
glm::dvec2 motionFromStored(const MotionConvention& c, glm::dvec2 s, glm::dvec2 jitterDelta, uint32_t width, uint32_t height);

struct MotionPairOptions {
  const Quantity* motion = nullptr;  // the layout's motion quantity (null: the first)
  double inlierPixels = 0.0;         // 0: derived from the frames' precision (docs/accuracy.md)
};

// One pair of consecutive frames, N-1 -> N.
struct MotionPair {
  int64_t previous = 0, current = 0;
  bool detected = false;             // enough static surface to decide a convention
  MotionConvention declared, found;  // found: the detected one (when detected)
  MotionDecided decided;
  std::vector<std::string> differences;  // declared vs found, as people say it
  std::string undecided;             // why not detected ("" when detected)
  double staticFraction = 0.0;       // surface pixels the camera's motion explains under `found`
  double bound = 0.0;                // the inlier bound in pixels used
  // Under the declared convention: |stored - expected| in pixels over the static pixels.
  double medianError = 0.0, p95Error = 0.0, maxError = 0.0;
  uint64_t surfacePixels = 0, staticPixels = 0, movingPixels = 0, disoccluded = 0, wrongMoving = 0;
  CpuImage errorMap;                 // f32 1 channel: |stored - expected| pixels (NaN: no surface)
  CpuImage classMap;                 // u32 1 channel: 0 none, 1 static, 2 moving (warp agrees), 3 disoccluded, 4 wrong
};

MotionPair checkMotionPair(const TemporalFrame& previous, const TemporalFrame& current,
                           const TemporalFrame* beforePrevious, const MotionPairOptions& options);
nlohmann::json motionPairJson(const MotionPair& p);

}  // namespace gb
