// The one decoder: a frame's quantities at a pixel, as its layout says they are stored
// (renderer/core/layout.h). Views, the probe, compare, check, error and import all decode here, for
// gblens's own frames (nativeLayout) and imported ones alike. Vectors come out in gblens's eye
// space (right-handed, looking down -Z, Y up), colours linear, depths as eye depth.
#pragma once
#include <array>
#include <optional>

#include <glm/glm.hpp>

#include "renderer/core/layout.h"
#include "renderer/core/snapshot.h"

namespace gb {

// The image holding a layout target's texels (null when the frame does not hold the target).
const TargetImage* layoutImage(const FrameSnapshot& f, uint32_t target);
// Whether the frame holds the quantity's texel (x, y) (target coordinates).
bool holds(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);

// The quantity's channels at (x, y), decoded by the storage format only (unorm, snorm, half, ...).
std::array<double, 4> storedValues(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);

// Colour quantities (albedo, base colour, emission, radiance, display): linear RGB(A).
glm::dvec4 decodeColor(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);
// One-channel quantities with scale and bias (specular, roughness, shadow, scalar, ...).
double decodeScalar(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);
// Integer quantities (id, stencil, count): the stored integer (float channels rounded).
uint32_t decodeInteger(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);

struct NormalSample {
  glm::dvec3 unit{0.0};    // eye space, unit length (zero when nothing was stored)
  glm::dvec3 stored{0.0};  // the decoded vector before normalisation, in its own space
};
// The vector an encoding stores in channel values `c` (raw: the integers, for packed encodings).
glm::dvec3 decodeNormalValues(NormalEncoding e, const std::array<double, 4>& c, const std::array<uint32_t, 4>& raw);
NormalSample decodeNormal(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);

// A depth quantity as eye depth (positive distance along -Z); nothing where the pixel holds the
// background value (nothing drawn). Sun depths (shadow maps) come back as stored.
std::optional<double> decodeEyeDepth(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);
// The eye-space position from a depth quantity (reconstructed with the camera) or a stored position.
std::optional<glm::dvec3> decodePosition(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);
// A motion vector in pixels, toward the previous frame, +y down (the layout's units, direction and y
// axis undone; jitter is not: that needs the sequence, views/analysis/motion.h).
glm::dvec2 decodeMotion(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y);

// The depth quantity that says where surfaces are: the layout's first camera depth (null: none).
const Quantity* surfaceDepth(const Layout& layout);
// Whether the pixel holds a surface, by the first camera depth quantity the frame holds (every
// pixel does when the layout has no depth; a pixel outside the frame's region does not).
bool hasSurface(const FrameSnapshot& f, uint32_t x, uint32_t y);

// Eye space <-> the space a layout stores vectors in (normals: directions; positions: points). World
// space is the layout's own world (its up axis), not gblens's Y-up world: what users see and script.
glm::dvec3 eyeFromSpace(const FrameSnapshot& f, Space space, const glm::dvec3& v, bool point);
glm::dvec3 spaceFromEye(const FrameSnapshot& f, Space space, const glm::dvec3& eye, bool point);

}  // namespace gb
