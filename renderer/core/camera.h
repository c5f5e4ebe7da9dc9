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
  double yfov = 0.8, aspect = 1.0, znear = 0.1, zfar = 100.0;
  bool reversedZ = false;  // depth 1 at the near plane, 0 at the far plane
  glm::dmat4 worldFromEye{1.0}, eyeFromWorld{1.0};
  glm::dmat4 clipFromEye{1.0}, eyeFromClip{1.0};
  glm::dmat4 clipFromWorld{1.0};
};

// Perspective projection to Vulkan clip space (y down, z in [0,1], or [1,0] when reversed).
glm::dmat4 perspective(double yfov, double aspect, double znear, double zfar, bool reversedZ);

Camera makeCamera(const CameraDesc& camera, uint32_t width, uint32_t height, bool reversedZ);

// Normalized device coordinates of a pixel centre (x right, y down, both in [-1, 1]).
glm::dvec2 pixelNdc(const Camera& camera, double px, double py);

// Eye-space position of a pixel from its eye depth (positive distance along -Z): the
// USE_EYE_DEPTH reconstruction, exactly as the shaders do it.
glm::dvec3 eyeFromEyeDepth(const Camera& camera, double px, double py, double eyeDepth);

// Eye-space position of a pixel from its hardware depth value through eyeFromClip.
glm::dvec3 eyeFromHardwareDepth(const Camera& camera, double px, double py, double depth);

// Hardware depth value of an eye-space point (what the rasterizer writes, before rounding).
double hardwareDepth(const Camera& camera, const glm::dvec3& eye);

// A camera looking from `eye` at `target` (+Y up).
glm::dmat4 lookAt(const glm::dvec3& eye, const glm::dvec3& target, const glm::dvec3& up = {0, 1, 0});

// A camera description looking from `eye` at `target`; looking straight up or down, -Z is up.
CameraDesc lookAtCamera(std::string name, const glm::dvec3& eye, const glm::dvec3& target, double yfov,
                        double znear, double zfar);

}  // namespace gb
