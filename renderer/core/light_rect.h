// The screen rectangle of a light's sphere: the pixels whose centres its projection can cover.
// One function for light culling (sub-pixel lights, the stencil layers' icosahedra), the ideal
// pair count and the CPU reference's light bins.
#pragma once
#include <cstdint>

#include <glm/glm.hpp>

#include "renderer/core/camera.h"

namespace gb {

// Inradius of the unit icosahedron (the light volumes): scaling by radius / this makes a sphere of
// `radius` inscribed.
constexpr double kIcosahedronInradius = 0.7946544722917661;

// Pixels [x0, x1] x [y0, y1] of a frame, inclusive; empty when x0 > x1 or y0 > y1.
struct PixelRect {
  int64_t x0 = 0, y0 = 0, x1 = -1, y1 = -1;
  bool empty() const { return x0 > x1 || y0 > y1; }
};

// The pixels whose centres can lie inside the projection of a sphere (centre `c` in eye space,
// radius `r`), widened by `margin` pixels and clipped to the frame. Exact for a sphere in front
// of the eye: along each screen axis the lines through the eye tangent to the sphere bound it.
// The whole frame when the sphere reaches the eye's plane (its projection is unbounded), empty
// when it lies behind it. The near plane is not applied (clipping only removes pixels).
PixelRect sphereScreenRect(const Camera& camera, const glm::dvec3& c, double r, double margin);

// Why a point light is drawn or not: the one rule of light culling (renderer/frame/light_culling.cpp)
// and of the probe's light ledger ("why is this pixel lit").
enum class LightCull : uint8_t {
  Empty,     // zero radius, intensity or colour (or not finite): lights nothing
  Frustum,   // the sphere lies outside the camera frustum (near, far and side planes)
  SubPixel,  // in front of the near plane, and its screen rectangle holds no pixel centre
  NearPlane, // drawn: its icosahedron may reach the near plane (no stencil mask for it)
  Stencil,   // drawn with the stencil mask
};
const char* name(LightCull c);
// The rule for one light (centre in eye space).
LightCull cullLight(const Camera& camera, const glm::dvec3& eyeCenter, double radius, double intensity,
                    const glm::dvec3& color);
bool sphereInFrustum(const Camera& camera, const glm::dvec3& c, double r);
// No pixel centre can be lit: the sphere is in front of the near plane and its exact screen
// rectangle (widened by 1/1000 pixel for rounding) holds no pixel centre.
bool coversNoPixelCentre(const Camera& camera, const glm::dvec3& eyeCenter, double radius);
// The light's icosahedron may reach the near plane (or contain the camera).
bool touchesNearPlane(const Camera& camera, const glm::dvec3& eyeCenter, double radius);

// Clustered shading's exponential depth slices (Olsson et al.): slice = floor(log2(eye depth) *
// scale + bias), clamped to [0, gpu::kClusterMaxSlices). The shaders get scale and bias as float
// (FrameData::clusterSlices); clusterSlice rounds as they do, so the probe names the GPU's slice.
struct ClusterSlicing {
  double scale = 1.0, bias = 0.0;
};
ClusterSlicing clusterSlicing(const Camera& camera);
uint32_t clusterSlice(const ClusterSlicing& s, double eyeDepth);

}  // namespace gb
