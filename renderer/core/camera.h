// The camera of one frame: every matrix the renderer and the probe need, in double, named
// destination-from-source (pbrt-v4). Vulkan conventions: clip y points down, depth in [0, 1].
#pragma once
#include <glm/glm.hpp>

#include <cstdint>
#include <string>

namespace gb {

struct CameraDesc {
  std::string name;
  glm::dmat4 worldFromEye{1.0};  // eye looks down -Z, +Y up (glTF convention)
  double yfov = 0.8;             // radians
  double aspect = 0.0;           // 0: from the output size
  double znear = 0.1, zfar = 100.0;
};

struct Camera {
  uint32_t width = 1, height = 1;
  // yfov: 0 for an orthographic projection (an imported camera's; gblens renders perspective only).
  double yfov = 0.8, aspect = 1.0, znear = 0.1, zfar = 100.0;
  bool reversedZ = false;  // depth 1 at the near plane, 0 at the far plane
  glm::dmat4 worldFromEye{1.0}, eyeFromWorld{1.0};
  glm::dmat4 clipFromEye{1.0}, eyeFromClip{1.0};
  glm::dmat4 clipFromWorld{1.0};
};

// Perspective projection to Vulkan clip space (y down, z in [0,1], or [1,0] when reversed).
glm::dmat4 perspective(double yfov, double aspect, double znear, double zfar, bool reversedZ);
// Orthographic projection to Vulkan clip space: the view volume x in [-halfWidth, halfWidth], y in
// [-halfHeight, halfHeight] (eye +Y at the top of the image), eye depth [znear, zfar] to depth 0..1
// (1..0 when reversed).
glm::dmat4 orthographicProjection(double halfWidth, double halfHeight, double znear, double zfar, bool reversedZ);

Camera makeCamera(const CameraDesc& camera, uint32_t width, uint32_t height, bool reversedZ);

// The kind of a projection to Vulkan clip space (after import's conversion, import.h): clip w is
// -z (perspective) or a constant (orthographic). Anything else (w depending on x, y, or on z and a
// constant at once; x and y mixed) is none of them: import refuses it, so a Camera never holds one.
enum class Projection : uint8_t { Perspective, Orthographic, Other };
Projection projectionOf(const glm::dmat4& clipFromEye);
const char* name(Projection p);
bool orthographic(const Camera& camera);

// Normalized device coordinates of a pixel centre (x right, y down, both in [-1, 1]).
glm::dvec2 pixelNdc(const Camera& camera, double px, double py);

// Eye-space position of a pixel from its eye depth (positive distance along -Z): the
// USE_EYE_DEPTH reconstruction, exactly as the shaders do it. Orthographic: the point at that depth
// on the pixel's ray, which starts on the plane z = 0 and runs along -Z.
glm::dvec3 eyeFromEyeDepth(const Camera& camera, double px, double py, double eyeDepth);

// The ray through a pixel centre, in eye space: where it starts (the eye; orthographic: on z = 0)
// and its unit direction (orthographic: -Z everywhere). Radial depth is the distance along it.
struct PixelRay {
  glm::dvec3 origin{0.0}, direction{0.0, 0.0, -1.0};
};
PixelRay pixelRay(const Camera& camera, double px, double py);

// Eye-space position of a pixel from its hardware depth value through eyeFromClip.
glm::dvec3 eyeFromHardwareDepth(const Camera& camera, double px, double py, double depth);

// Hardware depth value of an eye-space point (what the rasterizer writes, before rounding).
double hardwareDepth(const Camera& camera, const glm::dvec3& eye);

// A camera's combined clip_from_world (a perspective: clip w is the distance along the view
// direction) split into a rigid view_from_world (right-handed: looking down -Z, +Y up the image) and
// the clip_from_view that makes it up again (clip_from_world = clip_from_view * view_from_world).
// `clipYUp`: clip y points up the image (D3D, GL). False for an orthographic or singular matrix.
bool splitClipFromWorld(const glm::dmat4& clipFromWorld, bool clipYUp, glm::dmat4& viewFromWorld,
                        glm::dmat4& clipFromView);

// A camera looking from `eye` at `target` (+Y up).
glm::dmat4 lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up = {0, 1, 0});

// A camera description looking from `eye` at `target`; looking straight up or down, -Z is up.
CameraDesc lookAtCamera(std::string name, const glm::dvec3& eye, const glm::dvec3& target, double yfov,
                        double znear, double zfar);

}  // namespace gb
