// builtin:normal-sphere, a scene for normal encodings: one camera-filling card whose vertex
// normals cover the whole sphere of directions uniformly, so a frame's pixels sample normal
// storage as a Monte-Carlo over uniformly distributed unit vectors would (the published figures
// of octahedral encodings are such averages and maxima). The camera looks down -Z from the origin.
#include <algorithm>
#include <cmath>

#include "renderer/scene/builtin.h"
#include "renderer/scene/mesh_builder.h"

namespace gb {

// Archimedes' equal-area map of the unit square onto the sphere: u -> longitude, v -> height
// (the area of a band of the sphere is proportional to its height), so uniform (u, v) gives
// uniformly distributed directions. v = 0 is +Z (toward the camera), v = 1 is -Z.
glm::dvec3 normalSphereDirection(double u, double v) {
  const double pi = 3.14159265358979323846;
  double z = 1.0 - 2.0 * v, phi = pi * (2.0 * u - 1.0), r = std::sqrt(std::max(0.0, 1.0 - z * z));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

Scene normalSphereScene(int lightCount) {
  Scene s;
  s.source = "builtin:normal-sphere";
  MaterialDesc m;
  m.name = "sphere of normals";
  m.baseColor = glm::vec4(0.7f, 0.7f, 0.7f, 1.0f);
  m.specular = 0.5f;
  s.materials.push_back(m);
  CameraDesc cam;
  cam.name = "normal-sphere";
  cam.yfov = 0.6;
  cam.aspect = 16.0 / 9.0;  // the card fills exactly this aspect (other output sizes stretch it)
  cam.znear = 0.5;
  cam.zfar = 4.0;
  s.cameras.push_back(cam);
  // The card at eye depth 2 spans the view exactly: screen position and (u, v) are proportional,
  // so pixels are uniform in (u, v). 251 x 127 cells: between vertices the normal is interpolated
  // (and renormalized) over at most 1.5 degrees of longitude. Odd counts: no pixel centre of an
  // even-sized frame lies on a cell edge ((2x + 1) 251 != 2 W i), where the rasterizer's tie rule and
  // the reference's could pick different triangles.
  const int columns = 251, rows = 127;
  const double depth = 2.0, halfH = depth * std::tan(cam.yfov * 0.5), halfW = halfH * cam.aspect;
  MeshBuilder b{s};
  b.begin("normal sphere", 0);
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= columns; ++i) {
      double u = double(i) / columns, v = double(j) / rows;
      glm::vec3 p(float(-halfW + 2.0 * halfW * u), float(halfH - 2.0 * halfH * v), float(-depth));
      b.vertex(p, glm::vec3(normalSphereDirection(u, v)), glm::vec2(float(u), float(v)));
    }
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      uint32_t a = uint32_t(j * (columns + 1) + i), c = a + uint32_t(columns + 1);
      b.triangle(a, c, c + 1);  // counter-clockwise seen from the camera (+Z)
      b.triangle(a, c + 1, a + 1);
    }
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
  s.sun.enabled = true;
  s.sun.toSun = glm::normalize(glm::dvec3(0.3, 0.5, 0.8));
  computeBounds(s);
  generateLights(s, lightCount);
  return s;
}

}  // namespace gb
