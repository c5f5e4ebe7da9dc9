// The frame's geometry for the drafting (infer_internal.h): the hardware depth (a depth format the
// G-buffer pass stores) and where it says the surfaces are; stored positions, found as the
// 3-vector field a pinhole maps onto its own pixels (pinhole.h), in the space the fit says; eye-space
// points through a camera from any depth source, and the reference normals they give.
#include <algorithm>
#include <cmath>

#include "renderer/core/camera.h"
#include "views/infer/infer_internal.h"

namespace gb::infer {

void decideDepthTargets(State& s) {
  for (size_t t = 0; t < s.in.targets.size(); ++t) {
    const InferTarget& target = s.in.targets[t];
    if (!target.format.depth) continue;
    const CpuImage* img = s.image(t);
    Guess g;
    g.quantity = "depth";
    g.confidence = 1.0;
    g.evidence = "a depth format (" + target.format.name + ") written by " +
                 (target.writer == Writer::Forward ? "the pass that draws the frame" : "the G-buffer pass") +
                 " and stored by the application";
    nlohmann::json fields = {{"encoding", "hardware"}};
    DepthSource d{t, 0, DepthEncoding::Hardware, 1.0, std::nullopt};
    if (img) {
      size_t zeros = 0, ones = 0;
      for (uint32_t y = 0; y < img->height; ++y)
        for (uint32_t x = 0; x < img->width; ++x) {
          const double v = img->value(x, y, 0);
          zeros += v == 0.0, ones += v == 1.0;
        }
      const size_t n = size_t(img->width) * img->height;
      const double clear = ones >= zeros ? 1.0 : 0.0;
      const size_t at = std::max(zeros, ones);
      if (at > 0) {
        fields["background"] = clear;
        d.background = clear;
        g.evidence += "; " + numText(100.0 * double(at) / double(n)) + " % of pixels hold " + numText(clear) +
                      ", the clear value" + (clear == 0.0 ? " (reversed depth)" : "") + ": no surface there";
      } else {
        g.evidence += "; no pixel holds 0 or 1: every pixel has a surface";
      }
    }
    if (!s.hardware) s.hardware = d;
    s.add(t, QuantityKind::Depth, {0}, fields, g, s.hardware->target == t ? "depth" : "depth_" + std::to_string(t));
    if (target.format.stencil) {
      if (target.stencilStored) {
        Guess st;
        st.quantity = "stencil";
        st.confidence = 1.0;
        st.evidence = "the stencil aspect of " + target.format.name + ", stored by the application";
        s.add(t, QuantityKind::Stencil, {1}, nullptr, st);
      } else {
        s.claimed[t][1] = true;
        s.summary.push_back("the stencil of " + (target.label.empty() ? target.format.name : target.label) +
                            ": storeOp DONT_CARE (the application does not store it): no quantity, its texels mean nothing");
      }
    }
  }
}

void decideSurface(State& s) {
  if (s.hardware && s.hardware->background && s.image(s.hardware->target)) {
    const CpuImage& img = *s.image(s.hardware->target);
    s.surface.width = img.width, s.surface.height = img.height;
    s.surface.at.assign(size_t(img.width) * img.height, 0);
    for (uint32_t y = 0; y < img.height; ++y)
      for (uint32_t x = 0; x < img.width; ++x) s.surface.at[size_t(y) * img.width + x] = img.value(x, y, 0) != *s.hardware->background;
    s.surface.from = "the hardware depth where it is not " + numText(*s.hardware->background);
    return;
  }
  std::vector<const CpuImage*> images;
  for (size_t t = 0; t < s.in.targets.size(); ++t)
    if (s.in.targets[t].writer != Writer::Later && !s.in.targets[t].format.depth) images.push_back(s.image(t));
  s.surface = maskFromClearTexels(images);
}

namespace {

double pinholeBound(const StorageFormat& f) { return f.type == PixelType::F16 ? 1.5 : 0.5; }

}  // namespace

void decidePositions(State& s) {
  struct Tried {
    size_t target;
    PinholeFit fit;
  };
  std::vector<Tried> tried;
  for (size_t t = 0; t < s.in.targets.size(); ++t) {
    const InferTarget& target = s.in.targets[t];
    if (target.format.encoding != Encoding::Float || target.format.channels < 3 || !s.image(t) ||
        target.writer == Writer::Later || !s.isFree(t, {0, 1, 2}))
      continue;
    std::vector<PointSample> samples;
    for (const glm::uvec2& p : s.pixels) {
      const glm::dvec4 v = channelValues(*s.image(t), p.x, p.y, {0, 1, 2});
      samples.push_back({p.x + 0.5, p.y + 0.5, glm::dvec3(v)});
    }
    tried.push_back({t, fitPinhole(samples)});
    s.positionTested.insert(t);
  }
  std::sort(tried.begin(), tried.end(), [](const Tried& a, const Tried& b) { return a.fit.medianPx < b.fit.medianPx; });
  for (const Tried& c : tried) {
    const InferTarget& target = s.in.targets[c.target];
    const double bound = pinholeBound(target.format);
    const std::string fitText = "median " + numText(c.fit.medianPx) + " px, p90 " + numText(c.fit.p90Px) + " px over " +
                                std::to_string(c.fit.points) + " surface pixels";
    if (!c.fit.ok || !(c.fit.medianPx <= bound) || !(c.fit.p90Px <= 4.0 * bound)) {
      s.summary.push_back((target.label.empty() ? "target " + std::to_string(c.target) : target.label) +
                          " xyz: no pinhole maps it onto its own pixels (" + fitText + "): not a position");
      continue;
    }
    const std::string space = pointSpace(c.fit);
    Guess g;
    g.quantity = "position";
    g.confidence = std::clamp(1.0 - c.fit.medianPx / (2.0 * bound), 0.0, 1.0);
    g.evidence = std::string("a ") + (c.fit.orthographic ? "parallel" : "pinhole") +
                 " camera fitted to these points (direct linear transform) maps each onto its own pixel: " + fitText +
                 " (bound " + numText(bound) + " px for " + target.format.name + "); " +
                 (space == "view"              ? "the camera sits at their origin looking along an axis: view space"
                  : space == "camera_relative" ? "the camera sits at their origin, axes turned: camera-relative"
                                               : "the camera stands at (" + numText(c.fit.eye.x) + ", " + numText(c.fit.eye.y) +
                                                     ", " + numText(c.fit.eye.z) + "): world space");
    s.add(c.target, QuantityKind::Position, {0, 1, 2}, {{"space", space}}, g);
    if (s.positions.target < 0) {
      s.positions.target = int(c.target);
      s.positions.channels = {0, 1, 2};
      s.positions.space = space == "view" ? Space::View : space == "world" ? Space::World : Space::CameraRelative;
      s.positions.fit = c.fit;
    }
  }
}

PointField eyePoints(const State& s, const DepthSource& d, const Camera& camera) {
  const CpuImage* img = s.image(d.target);
  return [&s, d, camera, img](uint32_t x, uint32_t y) -> std::optional<glm::dvec3> {
    if (!img || !s.surface.surface(x, y)) return std::nullopt;
    const double v = img->value(x, y, d.channel);
    if (d.background && v == *d.background) return std::nullopt;
    if (d.encoding == DepthEncoding::Hardware) {
      if (!std::isfinite(v)) return std::nullopt;
      const glm::dvec3 e = eyeFromHardwareDepth(camera, x, y, v);
      return std::isfinite(e.x + e.y + e.z) && e.z < 0.0 ? std::optional(e) : std::nullopt;
    }
    const double dist = v * d.scale;
    if (!(dist > 0.0) || !std::isfinite(dist)) return std::nullopt;
    if (d.encoding == DepthEncoding::Eye) return eyeFromEyeDepth(camera, x, y, dist);
    const PixelRay ray = pixelRay(camera, x, y);
    return ray.origin + ray.direction * dist;
  };
}

glm::dvec3 layoutFromEye(const LayoutCamera& lc, const Camera& c, Space space, const glm::dvec3& v) {
  if (space == Space::View) return lc.leftHanded ? glm::dvec3(v.x, v.y, -v.z) : v;
  return layoutWorldFromWorld(lc) * (glm::dmat3(c.worldFromEye) * v);
}

std::vector<SpaceRef> referencesFromDepth(const State& s, const DepthSource& d, const LayoutCamera& lc, const Camera& c,
                                          const std::string& from) {
  const ReferenceNormals eye = surfaceNormals(eyePoints(s, d, c), s.surface, s.pixels, glm::dvec3(0.0));
  std::vector<SpaceRef> out;
  for (Space space : {Space::View, Space::World}) {
    SpaceRef r{space, eye};
    for (glm::dvec3& n : r.normals.normals) n = glm::normalize(layoutFromEye(lc, c, space, n));
    r.normals.from = from;
    out.push_back(std::move(r));
  }
  return out;
}

}  // namespace gb::infer
