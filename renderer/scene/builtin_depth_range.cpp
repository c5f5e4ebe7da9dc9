// builtin:depth-range, a scene for depth precision: a grid of camera-facing cards, each filling
// its own screen cell, at depths spaced evenly in log between the near and far planes. The camera
// sits at the origin looking down -Z; the reference knows every depth exactly.
#include <cmath>

#include "renderer/scene/builtin.h"
#include "renderer/scene/mesh_builder.h"

namespace gb {

Scene depthRangeScene(double znear, double zfar) {
  Scene s;
  s.source = "builtin:depth-range";
  MaterialDesc m;
  m.name = "card";
  m.baseColor = glm::vec4(0.6f, 0.6f, 0.6f, 1.0f);
  m.specular = 0.0f;
  s.materials.push_back(m);
  CameraDesc cam;
  cam.name = "depth-range";
  cam.yfov = 0.8;
  cam.aspect = 16.0 / 9.0;
  cam.znear = znear;
  cam.zfar = zfar;
  s.cameras.push_back(cam);
  const int columns = 8, rows = 4, cards = columns * rows;
  const double tanHalf = std::tan(cam.yfov * 0.5);
  // Card depths from 1.5 near to far / 1.5, evenly in log: every decade of the range is covered.
  const double lo = std::log(znear * 1.5), hi = std::log(zfar / 1.5);
  MeshBuilder b{s};
  b.begin("cards", 0);
  for (int k = 0; k < cards; ++k) {
    int i = k % columns, j = k / columns;
    double d = std::exp(lo + (hi - lo) * (k + 0.5) / cards);
    // The cell in NDC, inset by 10% so neighbouring cards never touch.
    double x0 = -1.0 + 2.0 * (i + 0.1) / columns, x1 = -1.0 + 2.0 * (i + 0.9) / columns;
    double y0 = 1.0 - 2.0 * (j + 0.9) / rows, y1 = 1.0 - 2.0 * (j + 0.1) / rows;
    double sx = d * tanHalf * cam.aspect, sy = d * tanHalf;
    glm::vec3 o(float(x0 * sx), float(y0 * sy), float(-d));
    b.quad(o, glm::vec3(float((x1 - x0) * sx), 0.0f, 0.0f), glm::vec3(0.0f, float((y1 - y0) * sy), 0.0f));
  }
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), false});
  s.sun.enabled = false;
  s.sky.ambient = glm::vec3(0.2f);
  computeBounds(s);
  return s;
}

}  // namespace gb
