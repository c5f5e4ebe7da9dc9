// builtin:depth-range, a scene for depth precision: a grid of camera-facing cards, each filling
// its own screen cell, at depths spaced evenly in log between the near and far planes. The camera
// sits at the origin looking down -Z; the reference knows every depth exactly. With a gap, each
// card has a twin just behind it: the depth test's resolution (z-fighting) at every depth.
#include <cmath>

#include "renderer/scene/builtin.h"
#include "renderer/scene/mesh_builder.h"

namespace gb {

Scene depthRangeScene(double znear, double zfar, double gap) {
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
  // A card (inset: the fraction of its screen cell left out at each side) around depth d, its
  // vertices scaled by `scale` from the eye (same pixels, every depth x scale). Slanted (with a
  // gap): the plane through the cell's bottom-left corner at d / 1.25, its bottom-right at d and
  // its top-left at d x 1.25, so the depth differs from pixel to pixel (rounding outcomes too);
  // an inset card lies on the same plane.
  const bool slanted = gap > 0.0;
  auto card = [&](MeshBuilder& b, int k, double d, double inset, double scale) {
    int i = k % columns, j = k / columns;
    auto ray = [&](double x, double y) { return glm::dvec3(x * tanHalf * cam.aspect, y * tanHalf, -1.0); };
    double cx0 = -1.0 + 2.0 * i / columns, cx1 = -1.0 + 2.0 * (i + 1) / columns;
    double cy0 = 1.0 - 2.0 * (j + 1) / rows, cy1 = 1.0 - 2.0 * j / rows;
    double d0 = slanted ? d / 1.25 : d, d1 = slanted ? d * 1.25 : d;
    glm::dvec3 p0 = ray(cx0, cy0) * d0, p1 = ray(cx1, cy0) * d, p2 = ray(cx0, cy1) * d1;
    glm::dvec3 n = glm::cross(p1 - p0, p2 - p0);
    auto at = [&](double x, double y) {
      glm::dvec3 r = ray(x, y);
      return glm::vec3(r * (glm::dot(n, p0) / glm::dot(n, r) * scale));
    };
    double x0 = -1.0 + 2.0 * (i + inset) / columns, x1 = -1.0 + 2.0 * (i + 1.0 - inset) / columns;
    double y0 = 1.0 - 2.0 * (j + 1.0 - inset) / rows, y1 = 1.0 - 2.0 * (j + inset) / rows;
    const glm::vec3 up(0.0f, 0.0f, 1.0f);
    uint32_t a = b.vertex(at(x0, y0), up, {0, 1}), c = b.vertex(at(x1, y0), up, {1, 1});
    uint32_t e = b.vertex(at(x1, y1), up, {1, 0}), g = b.vertex(at(x0, y1), up, {0, 0});
    b.triangle(a, c, e);
    b.triangle(a, e, g);
  };
  auto depth = [&](int k) { return std::exp(lo + (hi - lo) * (k + 0.5) / cards); };
  MeshBuilder b{s};
  b.begin("cards", 0);
  // With a gap, the twins behind come first (triangles 2k, 2k + 1), inset a little more than the
  // front cards (every twin pixel is also a front-card pixel). The G-buffer's depth test is
  // strict (LESS, or GREATER reversed): where it cannot tell a card from its twin, the twin drawn
  // first stays, and primitive_id shows it.
  for (int k = 0; k < cards && gap > 0.0; ++k) card(b, k, depth(k), 0.12, 1.0 + gap);
  // The cells inset by 10% so neighbouring cards never touch.
  for (int k = 0; k < cards; ++k) card(b, k, depth(k), 0.1, 1.0);
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), false});
  s.sun.enabled = false;
  s.sky.ambient = glm::vec3(0.2f);
  computeBounds(s);
  return s;
}

}  // namespace gb
