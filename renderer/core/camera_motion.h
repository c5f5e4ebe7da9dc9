// The camera across frames: its motion over time (camera_motion orbit), the projection's sub-pixel
// jitter (jitter halton) and the frame number the jitter follows. Plain math, no scene: the caller
// passes the scene's centre and radius. The formulas are documented here and in docs/capture-format.md
// ("Across frames"); the tests recompute them on their own.
#pragma once
#include <glm/glm.hpp>

#include <cstdint>

#include "renderer/core/camera.h"
#include "renderer/core/options.h"

namespace gb {

// camera_motion orbit, at time t (seconds), for a camera description W0 (world_from_eye) and the
// scene's bounding box centre c and radius R:
//   angle(t)  = 10 degrees/s x t                 (about the world +Y axis through c, counter-clockwise
//                                                 seen from above)
//   rise(t)   = 0.02 R sin(2 pi t / 4 s)
//   W(t)      = Translate(0, rise(t), 0) Translate(c) RotateY(angle(t)) Translate(-c) W0
// The camera turns with its position, so what it looked at (the scene's centre) stays in view.
constexpr double kOrbitDegreesPerSecond = 10.0;
constexpr double kOrbitRiseFraction = 0.02;  // of the scene's radius
constexpr double kOrbitRisePeriod = 4.0;     // seconds
glm::dmat4 orbitWorldFromEye(const glm::dmat4& worldFromEye, const glm::dvec3& centre, double radius, double time);

// The camera description at `time` under options.cameraMotion (unchanged when off).
CameraDesc movedCamera(const CameraDesc& camera, const RenderOptions& options, const glm::dvec3& centre, double radius,
                       double time);

// The frame number the jitter follows: round(time / time_step) (the frames of a sequence at
// T, T + S, ... with time_step S are consecutive numbers).
int64_t jitterFrame(const RenderOptions& options);
// The radical inverse of `index` in `base` (Halton): 1 -> 1/2, 2 -> 1/4, 3 -> 3/4 in base 2.
double halton(uint64_t index, uint32_t base);
// The frame's sub-pixel offset in pixels (+x right, +y down; each in (-0.5, 0.5)): with jitter
// halton, (halton(i, 2) - 0.5, halton(i, 3) - 0.5) for i = 1 + (jitterFrame mod 16); zero when off.
// The projected image moves by it: a point at pixel p unjittered is drawn at p + jitter.
constexpr int kJitterPeriod = 16;
glm::dvec2 frameJitter(const RenderOptions& options);

// `camera` with its projection moved by `pixels` (clip x += 2 jx / width w, clip y += 2 jy / height w:
// a perspective's P20, P21), every derived matrix updated. Orthographic cameras move P30, P31.
Camera jitteredCamera(const Camera& camera, const glm::dvec2& pixels);

}  // namespace gb
