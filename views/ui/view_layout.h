// Where views go in the viewer's view area and how linked zoom/pan map window pixels to texels.
// Zoom and pan are shared by every view: zoom is relative to "fit the image in its rectangle",
// pan is the image point (in [0,1]^2 of the image) at the rectangle's centre.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "views/ui/view_params.h"

namespace gb {

struct Rect {
  double x = 0, y = 0, w = 0, h = 0;
  bool contains(double px, double py) const { return px >= x && py >= y && px < x + w && py < y + h; }
};

enum class LayoutMode { Single, SideBySide, Grid };

// Rectangles for `count` views in `area`, `gap` pixels apart: one; two side by side; or a grid of
// as many cells, its columns and rows chosen so that images of aspect `aspect` (width / height) show
// largest (cells keep that aspect: a 16:9 target fills its cell's width or height).
std::vector<Rect> layoutViews(const Rect& area, LayoutMode mode, size_t count, double aspect, double gap = 4.0);

struct ViewTransform {
  double zoom = 1.0;                // 1: the whole image fits the rectangle
  glm::dvec2 center{0.5, 0.5};      // image point at the rectangle's centre, normalized
};

// Where an image of `width` x `height` texels lies in `rect`. Scales that are whole numbers
// (or 1/n) stay exact when the fit is close to one, so texels do not shimmer at 1:1.
Placement placeImage(const Rect& rect, uint32_t width, uint32_t height, const ViewTransform& t);
// The transform that shows texels [x, x + w) x [y, y + h) of a width x height image centred, at half
// the fitted image's extent (zoom 1 to 256): "zoom to marks".
ViewTransform framing(double x, double y, double w, double h, uint32_t width, uint32_t height);
// Texel coordinates (continuous) under a window point, and back.
glm::dvec2 texelAt(const Placement& p, glm::dvec2 window);
glm::dvec2 windowAt(const Placement& p, glm::dvec2 texel);

// Zooms by `factor` keeping the image point under `window` fixed (mouse-wheel zoom).
void zoomAbout(ViewTransform& t, const Rect& rect, uint32_t width, uint32_t height, glm::dvec2 window, double factor);
// Pans by a window-pixel delta.
void panBy(ViewTransform& t, const Rect& rect, uint32_t width, uint32_t height, glm::dvec2 delta);
// Zoom so that one texel is one framebuffer pixel.
double zoomForOneToOne(const Rect& rect, uint32_t width, uint32_t height);

}  // namespace gb
