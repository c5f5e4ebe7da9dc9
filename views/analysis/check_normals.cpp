// `gblens check`'s normals against the geometry (check.h NormalCheck): a stored normal lies along the
// normal of the surface the camera depth rebuilds, in the space the layout declares. The declared
// decoding is measured beside the ones a mistake would have made it — the other space, one component
// negated, x and y swapped — and a mistake is named when it fits far better; a normal map's own
// deviation (a median of 10-15°) is no fault, since it moves every hypothesis alike.
#include <algorithm>
#include <cmath>

#include "renderer/core/decode.h"
#include "renderer/core/surface_normals.h"
#include "views/analysis/check.h"

namespace gb {

namespace {

double score(const AngleStats& a) { return 0.5 * (a.median + a.p90); }

const char* spaceText(Space s) { return s == Space::View ? "view space" : s == Space::World ? "world space" : "camera-relative"; }

// What decodes a stored vector into eye space under one hypothesis.
struct Hypothesis {
  std::string name;
  Space space;
  glm::dvec3 sign{1.0};
  bool swapXY = false;
};

NormalCheck judge(const FrameSnapshot& f, const Quantity& n, const ReferenceNormals& ref, const Quantity& depth) {
  NormalCheck c;
  c.normal = n.name;
  c.depth = depth.name;
  c.declared = std::string(name(n.normal)) + ", " + spaceText(n.space);
  auto field = [&](const Hypothesis& h) -> VectorField {
    return [&f, &n, h](uint32_t x, uint32_t y) -> std::optional<glm::dvec3> {
      if (!holds(f, n, x, y)) return std::nullopt;
      glm::dvec3 s = decodeNormal(f, n, x, y).stored * h.sign;
      if (h.swapXY) std::swap(s.x, s.y);
      const glm::dvec3 e = eyeFromSpace(f, h.space, s, false);
      return glm::length(e) > 0.0 ? std::optional(e) : std::nullopt;
    };
  };
  c.stats = anglesTo(ref, field({"as declared", n.space}));
  std::vector<Hypothesis> mistakes;
  for (Space s : {Space::View, Space::World})
    if (s != n.space) mistakes.push_back({std::string("stored in ") + spaceText(s), s});
  const char* axes[] = {"x", "y", "z"};
  for (int i = 0; i < 3; ++i) {
    Hypothesis h{std::string("its ") + axes[i] + " negated", n.space};
    h.sign[i] = -1.0;
    mistakes.push_back(h);
  }
  mistakes.push_back({"x and y swapped", n.space, glm::dvec3(1.0), true});
  for (const Hypothesis& h : mistakes) {
    const AngleStats a = anglesTo(ref, field(h));
    if (a.count && (c.better.empty() ? score(a) : score(a) < score(c.betterStats))) c.better = h.name, c.betterStats = a;
  }
  // A mistake is named only when it explains the data far better than the declared decoding.
  if (!(score(c.stats) > 10.0 && score(c.betterStats) < 0.5 * score(c.stats))) c.better.clear();
  c.facesAway = c.stats.count > 0 && c.stats.sameSide < 0.25;
  return c;
}

}  // namespace

std::vector<NormalCheck> checkNormals(const FrameSnapshot& f, const CheckPolicy& policy) {
  std::vector<NormalCheck> out;
  const Quantity* depth = surfaceDepth(f.layout);
  if (!f.layout.camera.present || !depth || !layoutImage(f, depth->target)) return out;
  const uint32_t w = f.camera.width, h = f.camera.height;
  SurfaceMask mask;
  mask.width = w, mask.height = h;
  mask.at.assign(size_t(w) * h, 0);
  std::vector<glm::uvec2> all;
  for (uint32_t y = 2; y + 2 < h; ++y)
    for (uint32_t x = 2; x + 2 < w; ++x)
      if ((mask.at[size_t(y) * w + x] = hasSurface(f, x, y))) all.push_back({x, y});
  for (uint32_t y = 0; y < h; ++y)  // the border rows too, for the windows' neighbours
    for (uint32_t x = 0; x < w; ++x) mask.at[size_t(y) * w + x] = hasSurface(f, x, y);
  std::vector<glm::uvec2> pixels;
  const size_t step = std::max<size_t>(1, all.size() / 8000);
  for (size_t i = 0; i < all.size(); i += step) pixels.push_back(all[i]);
  const PointField points = [&](uint32_t x, uint32_t y) { return decodePosition(f, *depth, x, y); };
  const ReferenceNormals ref = surfaceNormals(points, mask, pixels, glm::dvec3(0.0));
  if (ref.pixels.size() < 64) return out;
  for (const Quantity& n : f.layout.quantities) {
    if (n.kind != QuantityKind::Normal || !layoutImage(f, n.target)) continue;
    const Severity severity = policy.at(n.name, "normal");
    if (severity == Severity::Ignore) continue;
    NormalCheck c = judge(f, n, ref, *depth);
    c.severity = severity;
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace gb
