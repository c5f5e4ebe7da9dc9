// A camera from stored points alone (views/infer drafts with it): the direct linear transform (Hartley and Zisserman, "Multiple
// View Geometry", ch. 7: the 3x4 projection that maps each stored point onto its own pixel, from the
// normalised points' linear system) and its decomposition into K [R | t]. No buffer and no name is
// needed: a 3-vector field that a pinhole maps onto its pixels is a position, and the fit says in
// which space (view space: the eye at the origin looking along an axis; camera-relative: the eye at
// the origin; world space otherwise), which way the camera looks and where it stands.
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

namespace gb {

struct PointSample {
  double px = 0.0, py = 0.0;  // the pixel's centre (x + 0.5, y + 0.5)
  glm::dvec3 p{0.0};          // the stored point, as stored
};

struct PinholeFit {
  bool ok = false;             // enough points, not degenerate
  size_t points = 0;
  glm::dmat4x3 projection{0.0};  // pixel (homogeneous) = projection * (p, 1), up to scale
  double medianPx = INFINITY, p90Px = INFINITY;  // reprojection distances, pixels
  bool orthographic = false;   // an affine camera fitted better (the rays are parallel)
  // The decomposition (perspective): intrinsics in pixels, the rotation from the points' space to
  // the camera's (rows: the image's right, down, and the view direction), the eye in the points' space.
  double fx = 0.0, fy = 0.0, cx = 0.0, cy = 0.0, skew = 0.0;
  glm::dmat3 eyeFromPoints{1.0};  // right-handed rows x right, y down, z forward (a mirror: det -1)
  glm::dvec3 eye{0.0};            // the camera centre in the points' space
  double sceneScale = 1.0;        // median distance of the points from the eye
};

// Fits the projection to the samples (at most `maxPoints`, spread over them) and measures every
// sample's reprojection distance.
PinholeFit fitPinhole(const std::vector<PointSample>& samples, size_t maxPoints = 4000);

// What space the fitted points are in: "view" (the eye at the origin and the axes those of a camera:
// each row of eyeFromPoints a signed axis), "camera_relative" (the eye at the origin, axes turned),
// "world" otherwise.
std::string pointSpace(const PinholeFit& fit);

// Eye depth of a point (distance along the view direction from the eye) under the fit.
double fittedEyeDepth(const PinholeFit& fit, const glm::dvec3& p);

// Smallest eigenvector of a symmetric n x n matrix (row-major, n <= 16), by Jacobi rotations.
std::vector<double> smallestEigenvector(std::vector<double> a, int n);

}  // namespace gb
