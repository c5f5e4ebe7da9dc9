// Linear depths (infer_internal.h): a float channel that is a distance of the surface from the eye
// — along the view axis (eye depth) or along the pixel's ray (radial), times one scale everywhere —
// is found by the ratio of the distance the hardware depth (through the camera) or the stored
// positions give to the stored value: the same at every surface pixel for the right hypothesis. The
// scale snaps to an exact value (1, a power of two, the far plane) within float rounding. Without a
// distance to compare with, a channel and a camera from the buffers are judged together by the normals
// the rebuilt surface has (decideJointly).
#include <algorithm>
#include <cmath>
#include <map>

#include "renderer/core/camera.h"
#include "views/infer/infer_internal.h"
#include "views/infer/suggest_camera.h"

namespace gb::infer {

std::vector<std::pair<size_t, uint32_t>> linearDepthCandidates(const State& s) {
  std::vector<std::pair<size_t, uint32_t>> out;
  for (size_t t = 0; t < s.in.targets.size(); ++t) {
    const InferTarget& target = s.in.targets[t];
    const StorageFormat& f = target.format;
    const bool kind = f.encoding == Encoding::Float || (f.encoding == Encoding::Unorm && f.type == PixelType::U16);
    if (f.depth || !kind || !s.image(t) || target.writer == Writer::Later) continue;
    for (uint32_t c = 0; c < f.channels; ++c) {
      if (s.claimed[t][c]) continue;
      // A distance is positive at the surfaces and varies: a channel holding one value at most of
      // them (a flat floor's albedo, a material index) would rebuild a plane facing the eye.
      std::map<double, size_t> counts;
      size_t positive = 0;
      for (const glm::uvec2& p : s.pixels) {
        const double v = stored(s, t, c, p.x, p.y);
        positive += v > 0.0 && std::isfinite(v);
        ++counts[v];
      }
      size_t most = 0;
      for (auto& [v, n] : counts) most = std::max(most, n);
      if (positive * 10 >= s.pixels.size() * 9 && most * 4 < s.pixels.size()) out.push_back({t, c});
    }
  }
  return out;
}

namespace {

// The distances the frame already knows at its sample pixels: eye depth and radial distance.
struct Distances {
  std::vector<glm::uvec2> pixels;
  std::vector<double> eye, radial;
  std::string from;
};

Distances knownDistances(const State& s) {
  Distances d;
  const bool ortho = s.cam.present && orthographic(s.cam.camera);
  if (s.cam.present && s.hardware) {
    const PointField p = eyePoints(s, *s.hardware, s.cam.camera);
    for (const glm::uvec2& px : s.pixels)
      if (auto e = p(px.x, px.y)) {
        d.pixels.push_back(px), d.eye.push_back(-e->z);
        d.radial.push_back(ortho ? NAN : glm::length(*e - pixelRay(s.cam.camera, px.x, px.y).origin));
      }
    d.from = "the hardware depth through the camera";
    return d;
  }
  if (s.positions.target < 0) return d;
  const CpuImage* img = s.image(size_t(s.positions.target));
  const PinholeFit& fit = s.positions.fit;
  const LayoutCamera& lc = s.cam.layout;
  for (const glm::uvec2& px : s.pixels) {
    const glm::dvec3 p(channelValues(*img, px.x, px.y, s.positions.channels));
    if (!std::isfinite(p.x + p.y + p.z)) continue;
    double eye = NAN, radial = NAN;
    if (s.cam.present) {  // through the camera: perspective or orthographic alike
      const glm::dvec3 e =
          s.positions.space == Space::View
              ? (lc.leftHanded ? glm::dvec3(p.x, p.y, -p.z) : p)
              : glm::dvec3(s.cam.camera.eyeFromWorld *
                           glm::dvec4(worldFromLayoutWorld(lc) * p, s.positions.space == Space::World ? 1.0 : 0.0));
      eye = -e.z;
      radial = ortho ? NAN : glm::length(e);
    } else if (!fit.orthographic) {  // through the camera the positions fit
      eye = s.positions.space == Space::View ? std::abs(fittedEyeDepth(fit, p)) : fittedEyeDepth(fit, p);
      radial = glm::length(p - (s.positions.space == Space::View ? glm::dvec3(0.0) : fit.eye));
    }
    if (!(eye > 0.0)) continue;
    d.pixels.push_back(px), d.eye.push_back(eye), d.radial.push_back(radial);
  }
  d.from = "the stored positions";
  return d;
}

struct Ratio {
  double k = NAN, spread = INFINITY;
  size_t n = 0;
};

Ratio ratio(const State& s, size_t t, uint32_t c, const Distances& d, const std::vector<double>& dist) {
  std::vector<double> r;
  for (size_t i = 0; i < d.pixels.size(); ++i) {
    const double v = stored(s, t, c, d.pixels[i].x, d.pixels[i].y);
    if (v > 0.0 && std::isfinite(v) && std::isfinite(dist[i])) r.push_back(dist[i] / v);
  }
  Ratio out;
  out.n = r.size();
  if (r.size() < 32 || r.size() * 10 < d.pixels.size() * 9) return out;  // most surfaces must hold a distance
  out.k = quantileOf(r, 0.5);
  out.spread = (quantileOf(r, 0.95) - quantileOf(r, 0.05)) / out.k;
  return out;
}

// An exact scale within float rounding: 1, a power of two, the camera's far or near plane.
double snap(double k, double spread, const State& s) {
  std::vector<double> exact = {1.0};
  for (int e = -16; e <= 16; ++e) exact.push_back(std::ldexp(1.0, e));
  if (s.cam.present) exact.insert(exact.end(), {s.cam.camera.zfar, s.cam.camera.znear});
  const double tol = std::max(2.0 * spread, 1e-5);
  for (double x : exact)
    if (x > 0.0 && std::abs(k / x - 1.0) < tol) return x;
  return k;
}

std::optional<double> background(const State& s, size_t t, uint32_t c) {
  if (!s.surface.known()) return std::nullopt;
  std::map<double, size_t> counts;
  for (uint32_t y = 0; y < s.height; ++y)
    for (uint32_t x = 0; x < s.width; ++x)
      if (!s.surface.surface(x, y)) ++counts[stored(s, t, c, x, y)];
  if (counts.empty()) return std::nullopt;
  return std::max_element(counts.begin(), counts.end(), [](auto& a, auto& b) { return a.second < b.second; })->first;
}

void draft(State& s, size_t t, uint32_t c, DepthEncoding e, double scale, const Guess& g) {
  nlohmann::json fields = {{"encoding", e == DepthEncoding::Eye ? "eye" : "radial"}};
  if (scale != 1.0) fields["scale"] = scale;
  const std::optional<double> bg = background(s, t, c);
  if (bg) fields["background"] = *bg;
  s.add(t, QuantityKind::Depth, {c}, fields, g, e == DepthEncoding::Eye ? "eye_depth" : "radial_depth");
  if (!s.linear) s.linear = DepthSource{t, c, e, scale, bg};
}

}  // namespace

void decideLinearDepths(State& s) {
  const Distances d = knownDistances(s);
  s.distancesKnown = !d.pixels.empty();
  if (d.pixels.empty()) return;
  for (auto [t, c] : linearDepthCandidates(s)) {
    const Ratio eye = ratio(s, t, c, d, d.eye), radial = ratio(s, t, c, d, d.radial);
    const bool isEye = eye.spread <= radial.spread;
    const Ratio& best = isEye ? eye : radial;
    const Ratio& other = isEye ? radial : eye;
    if (!(best.spread < 0.01)) continue;  // 1 %: the distances' own rounding is far below it
    Guess g;
    g.quantity = "depth";
    g.confidence = marginConfidence(best.spread, std::min(other.spread, 1.0));
    if (g.confidence < kDecide) continue;
    const double scale = snap(best.k, best.spread, s);
    g.evidence = "stored × " + numText(scale, 9) + " is the " + (isEye ? "eye depth" : "radial distance") + " " + d.from +
                 " give: their ratio spreads " + numText(best.spread) + " (p5..p95, relative) over " + std::to_string(best.n) +
                 " surface pixels" + (scale != best.k ? " (median " + numText(best.k, 9) + ", snapped)" : "");
    g.rejected.push_back({isEye ? "radial distance" : "eye depth", "ratio spread " + numText(other.spread)});
    draft(s, t, c, isEye ? DepthEncoding::Eye : DepthEncoding::Radial, scale, g);
  }
}

void decideJointly(State& s) {
  if (s.hardware || s.positions.target >= 0 || (!s.cam.present && s.in.buffers.empty())) return;
  std::vector<FoundCamera> cams;  // the candidates: at most 8 (each rebuilds every channel's surface)
  if (s.cam.present) {  // a camera given (a sidecar): only the depth is to decide
    FoundCamera given;
    given.found = true;
    given.layout = s.cam.layout, given.converted = s.cam.camera, given.camera = s.cam.block;
    cams.push_back(given);
  } else {
    CameraEvidence e;
    e.width = s.width, e.height = s.height, e.clipYUp = s.in.clipYUp, e.clipDepthGl = s.in.clipDepthGl;
    cams = searchCameras(s.in.buffers, e, s.in.bufferSource, s.in.livePass, 8);
  }
  struct Tried {
    size_t cam;
    DepthSource depth;
    double median;
  };
  std::vector<Tried> tried;
  for (size_t k = 0; k < cams.size(); ++k) {
    if (!cams[k].found) continue;
    for (auto [t, c] : linearDepthCandidates(s))
      for (DepthEncoding enc : {DepthEncoding::Eye, DepthEncoding::Radial}) {
        if (enc == DepthEncoding::Radial && orthographic(cams[k].converted)) continue;
        const DepthSource d{t, c, enc, 1.0, background(s, t, c)};
        const std::vector<SpaceRef> refs = referencesFromDepth(s, d, cams[k].layout, cams[k].converted, "");
        tried.push_back({k, d, bestNormalMedian(s, refs)});
      }
  }
  std::sort(tried.begin(), tried.end(), [](const Tried& a, const Tried& b) { return a.median < b.median; });
  if (tried.empty()) return;  // no channel could be a distance
  if (!(tried[0].median <= 30.0)) {
    s.summary.push_back("linear depth: no channel, as a distance through the buffers' cameras, rebuilds a surface a stored "
                        "normal fits");
    return;
  }
  const Tried& best = tried[0];
  // Is it a distance at all: against other channels and cameras (and unrelated directions, 70°).
  // Eye or radial (both rebuild nearly the same surface at a narrow field of view): the better,
  // when it is better by a tenth, else undecided.
  double next = 70.0, otherEncoding = INFINITY;
  for (const Tried& o : tried) {
    const bool sameChannel = o.depth.channel == best.depth.channel && o.depth.target == best.depth.target;
    if (sameChannel && o.cam == best.cam && o.depth.encoding != best.depth.encoding)
      otherEncoding = std::min(otherEncoding, o.median);
    else if (&o != &best && !(sameChannel && o.cam == best.cam))
      next = std::min(next, o.median);
  }
  Guess g;
  g.quantity = "depth";
  g.confidence = marginConfidence(best.median, next);
  if (g.confidence < kDecide) return;
  const bool encodingDecided = marginConfidence(best.median, otherEncoding) >= 0.1;
  if (!encodingDecided) g.undecided.push_back("encoding");
  const FoundCamera& cam = cams[best.cam];
  if (!s.cam.present) {
    s.cam.present = true;
    s.cam.layout = cam.layout;
    s.cam.camera = cam.converted;
    s.cam.block = cam.camera;
    s.cam.from = "the bound buffers, judged by the normals";
    s.cam.block["guess"] = cam.camera["guess"].get<std::string>() +
                           "; checked by the normals: the surface this camera and the linear depth rebuild lies perpendicular "
                           "to the stored normals (median " + numText(best.median) + "°; the next camera or depth: " + numText(next) + "°)";
  }
  g.evidence = std::string("as the ") + (best.depth.encoding == DepthEncoding::Eye ? "eye depth" : "radial distance") +
               " with the camera, it rebuilds a surface the stored normals lie along (score " + numText(best.median) +
               "°; another channel or camera " + numText(next) + "°; as the " +
               (best.depth.encoding == DepthEncoding::Eye ? "radial distance" : "eye depth") + " " + numText(otherEncoding) + "°)";
  g.undecided.push_back("scale");
  g.evidence += "; the scale is not in the evidence (normals do not change with it): 1";
  draft(s, best.depth.target, best.depth.channel, best.depth.encoding, 1.0, g);
}

}  // namespace gb::infer
