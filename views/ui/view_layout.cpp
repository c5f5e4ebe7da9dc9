// View rectangles and the linked zoom/pan transform.
#include "views/ui/view_layout.h"

#include <algorithm>
#include <cmath>

namespace gb {

std::vector<Rect> layoutViews(const Rect& a, LayoutMode mode, size_t count, double aspect, double gap) {
  std::vector<Rect> out;
  if (mode == LayoutMode::Single || count <= 1) return {a};
  if (mode == LayoutMode::SideBySide) count = 2;
  aspect = aspect > 0.0 ? aspect : 1.0;
  // The grid whose cells show the image largest (ties: fewer rows, so views read left to right).
  int bestCols = 1;
  double bestScale = -1.0;
  for (int cols = 1; cols <= int(count); ++cols) {
    const int rows = int((count + size_t(cols) - 1) / size_t(cols));
    const double w = (a.w - gap * (cols - 1)) / cols, h = (a.h - gap * (rows - 1)) / rows;
    const double scale = std::min(w / aspect, h);
    if (w > 0 && h > 0 && scale > bestScale * 1.0001) bestScale = scale, bestCols = cols;
  }
  if (mode == LayoutMode::SideBySide) bestCols = 2;  // "two": side by side, as people compare
  const int cols = bestCols, rows = int((count + size_t(cols) - 1) / size_t(cols));
  const double w = std::floor((a.w - gap * (cols - 1)) / cols), h = std::floor((a.h - gap * (rows - 1)) / rows);
  for (size_t i = 0; i < count; ++i) {
    const int row = int(i) / cols, col = int(i) % cols;
    out.push_back({a.x + col * (w + gap), a.y + row * (h + gap), w, h});
  }
  return out;
}

static double fitScale(const Rect& r, uint32_t width, uint32_t height) {
  return std::max(1e-6, std::min(r.w / std::max(width, 1u), r.h / std::max(height, 1u)));
}

double zoomForOneToOne(const Rect& rect, uint32_t width, uint32_t height) { return 1.0 / fitScale(rect, width, height); }

Placement placeImage(const Rect& r, uint32_t width, uint32_t height, const ViewTransform& t) {
  double scale = fitScale(r, width, height) * t.zoom;
  // Snap to an exact 1:1 (or n:1) when within half a percent: texels map to whole pixels.
  double rounded = scale >= 1.0 ? std::round(scale) : 1.0 / std::round(1.0 / scale);
  if (std::abs(scale / rounded - 1.0) < 0.005) scale = rounded;
  Placement p;
  p.scale = scale;
  p.originX = std::round(r.x + r.w * 0.5 - t.center.x * width * scale);
  p.originY = std::round(r.y + r.h * 0.5 - t.center.y * height * scale);
  return p;
}

ViewTransform framing(double x, double y, double w, double h, uint32_t width, uint32_t height) {
  const double iw = std::max(width, 1u), ih = std::max(height, 1u);
  ViewTransform t;
  t.zoom = std::clamp(0.5 * std::min(iw / std::max(w, 1.0), ih / std::max(h, 1.0)), 1.0, 256.0);
  t.center = {(x + 0.5 * w) / iw, (y + 0.5 * h) / ih};
  return t;
}

glm::dvec2 texelAt(const Placement& p, glm::dvec2 w) { return {(w.x - p.originX) / p.scale, (w.y - p.originY) / p.scale}; }
glm::dvec2 windowAt(const Placement& p, glm::dvec2 t) { return {p.originX + t.x * p.scale, p.originY + t.y * p.scale}; }

void zoomAbout(ViewTransform& t, const Rect& r, uint32_t width, uint32_t height, glm::dvec2 window, double factor) {
  Placement before = placeImage(r, width, height, t);
  glm::dvec2 texel = texelAt(before, window);
  t.zoom = std::clamp(t.zoom * factor, 0.1, 4096.0);
  // Choose the centre so that `texel` stays under `window` at the new scale.
  double scale = fitScale(r, width, height) * t.zoom;
  t.center.x = (texel.x - (window.x - (r.x + r.w * 0.5)) / scale) / std::max(width, 1u);
  t.center.y = (texel.y - (window.y - (r.y + r.h * 0.5)) / scale) / std::max(height, 1u);
}

void panBy(ViewTransform& t, const Rect& r, uint32_t width, uint32_t height, glm::dvec2 delta) {
  double scale = fitScale(r, width, height) * t.zoom;
  t.center.x -= delta.x / scale / std::max(width, 1u);
  t.center.y -= delta.y / scale / std::max(height, 1u);
}

}  // namespace gb
