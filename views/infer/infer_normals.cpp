// Normals by geometry (infer_internal.h): a normal is perpendicular to the surface that depth (through
// the camera) or the stored positions describe, in the space where it is stored. Every channel group
// and encoding a format allows is decoded and its angle to the rebuilt surface's normal measured in
// each space the evidence can express; the hypothesis far better than the others is kept. Unit
// length is reported, never decisive (a normal-mapped shader's TBN leaves lengths short of 1).
#include <algorithm>
#include <cmath>

#include "renderer/core/decode.h"
#include "views/infer/infer_internal.h"

namespace gb::infer {

namespace {

struct Candidate {
  size_t target = 0;
  std::vector<uint32_t> channels;
  NormalEncoding encoding = NormalEncoding::Xyz;
};

std::vector<Candidate> candidates(const State& s) {
  std::vector<Candidate> out;
  for (size_t t = 0; t < s.in.targets.size(); ++t) {
    const InferTarget& target = s.in.targets[t];
    const StorageFormat& f = target.format;
    if (f.depth || !s.image(t) || target.writer == Writer::Later || f.srgb || f.encoding == Encoding::Uint) continue;
    const bool signedValues = f.encoding == Encoding::Float || f.encoding == Encoding::Snorm;
    if (f.channels >= 3 && s.isFree(t, {0, 1, 2}))
      out.push_back({t, {0, 1, 2}, signedValues ? NormalEncoding::Xyz : NormalEncoding::XyzUnorm});
    if (f.channels >= 2 && s.isFree(t, {0, 1}))
      out.push_back({t, {0, 1}, signedValues ? NormalEncoding::Octahedral : NormalEncoding::OctahedralUnorm});
  }
  return out;
}

VectorField field(const State& s, const Candidate& c) {
  const CpuImage* img = s.image(c.target);
  return [img, c](uint32_t x, uint32_t y) -> std::optional<glm::dvec3> {
    const glm::dvec4 v = channelValues(*img, x, y, c.channels);
    const glm::dvec3 n = decodeNormalValues(c.encoding, {v.x, v.y, v.z, v.w}, channelRaw(*img, x, y, c.channels));
    return std::isfinite(n.x + n.y + n.z) ? std::optional(n) : std::nullopt;
  };
}

const char* spaceName(Space s) { return s == Space::View ? "view" : s == Space::World ? "world" : "camera_relative"; }

// The rounding a unit vector's length may show in this storage.
double lengthTolerance(const StorageFormat& f) {
  switch (f.type) {
    case PixelType::U8:
    case PixelType::I8: return 0.03;
    case PixelType::F16: return 0.004;
    case PixelType::U16:
    case PixelType::I16: return f.packed10 ? 0.01 : 0.001;
    default: return 1e-4;
  }
}

// The stored vectors' lengths: how far from 1 (p50, p99), for the "normalized" field.
void lengths(const State& s, const Candidate& c, double& p50, double& p99) {
  std::vector<double> off;
  const VectorField f = field(s, c);
  for (const glm::uvec2& p : s.pixels)
    if (auto v = f(p.x, p.y)) off.push_back(std::abs(glm::length(*v) - 1.0));
  p50 = quantileOf(off, 0.5), p99 = quantileOf(off, 0.99);
}

// How well a vector field fits the rebuilt surface's normals: the mean of the median and p90 angles
// (a normal map leaves a median of 10-15° but a short tail; a wrong space or encoding a long one).
double score(const AngleStats& a) { return 0.5 * (a.median + a.p90); }

// The reference pixels whose normal is not the frame's dominant direction (a big floor's): a constant
// field that happens to point that way (an emission pass's zeros read as octahedral (0, 0, 1) in a Z-up
// world) fits the dominant surface and nothing else.
ReferenceNormals offDominant(const ReferenceNormals& r) {
  ReferenceNormals out;
  out.from = r.from;
  if (r.normals.empty()) return out;
  size_t best = 0, bestCount = 0;
  const size_t step = std::max<size_t>(1, r.normals.size() / 200);
  for (size_t i = 0; i < r.normals.size(); i += step) {
    size_t n = 0;
    for (size_t k = 0; k < r.normals.size(); k += step) n += std::abs(glm::dot(r.normals[i], r.normals[k])) > 0.966;  // 15°
    if (n > bestCount) best = i, bestCount = n;
  }
  for (size_t i = 0; i < r.normals.size(); ++i)
    if (std::abs(glm::dot(r.normals[i], r.normals[best])) <= 0.966)
      out.pixels.push_back(r.pixels[i]), out.normals.push_back(r.normals[i]);
  return out;
}

struct Scored {
  Candidate c;
  Space space = Space::View;
  AngleStats best, other;  // in the best space, and in the other one (count 0: no reference there)
  std::string from;
};

Scored judge(const State& s, const Candidate& c, const std::vector<SpaceRef>& refs) {
  Scored r{c};
  const VectorField f = field(s, c);
  struct InSpace {
    Space space;
    AngleStats stats;
    std::string from;
  };
  std::vector<InSpace> bySpace;
  for (const SpaceRef& ref : refs) {
    AngleStats a = anglesTo(ref.normals, f);
    if (a.count < 16) continue;
    // The surfaces facing elsewhere than the dominant one must fit too (when the frame has enough):
    // 2 % of the pixels, since a frame that is mostly floor makes a constant target (an albedo read as
    // octahedral) lie 7 degrees from the floor's normal at p90 while failing every other surface.
    const ReferenceNormals others = offDominant(ref.normals);
    if (others.pixels.size() >= std::max<size_t>(64, ref.normals.pixels.size() / 50)) {
      const AngleStats o = anglesTo(others, f);
      if (score(o) > score(a)) a = o;
    }
    auto it = std::find_if(bySpace.begin(), bySpace.end(), [&](auto& e) { return e.space == ref.space; });
    if (it == bySpace.end()) bySpace.push_back({ref.space, a, ref.normals.from});
    else if (score(a) < score(it->stats)) it->stats = a, it->from = ref.normals.from;
  }
  std::sort(bySpace.begin(), bySpace.end(), [](auto& a, auto& b) { return score(a.stats) < score(b.stats); });
  if (bySpace.empty()) return r;
  r.space = bySpace[0].space, r.best = bySpace[0].stats, r.from = bySpace[0].from;
  if (bySpace.size() > 1) r.other = bySpace[1].stats;
  return r;
}

// Stored positions' own normals, in their space, and in the other space through the camera.
std::vector<SpaceRef> referencesFromPositions(const State& s) {
  std::vector<SpaceRef> out;
  if (s.positions.target < 0) return out;
  const CpuImage* img = s.image(size_t(s.positions.target));
  const std::vector<uint32_t> ch = s.positions.channels;
  PointField points = [img, ch](uint32_t x, uint32_t y) -> std::optional<glm::dvec3> {
    const glm::dvec3 p(channelValues(*img, x, y, ch));
    return std::isfinite(p.x + p.y + p.z) ? std::optional(p) : std::nullopt;
  };
  const PinholeFit& fit = s.positions.fit;
  const std::optional<glm::dvec3> eye = fit.orthographic ? std::nullopt : std::optional(fit.eye);
  SpaceRef own{s.positions.space, surfaceNormals(points, s.surface, s.pixels, eye)};
  own.normals.from = std::string("the surface of the stored positions (") + spaceName(s.positions.space) + " space)";
  out.push_back(own);
  if (!s.cam.present || s.positions.space == Space::CameraRelative) return out;
  const LayoutCamera& lc = s.cam.layout;
  const Camera& c = s.cam.camera;
  SpaceRef other{s.positions.space == Space::View ? Space::World : Space::View, own.normals};
  for (glm::dvec3& n : other.normals.normals) {
    const glm::dvec3 eyeN = s.positions.space == Space::View
                                ? (lc.leftHanded ? glm::dvec3(n.x, n.y, -n.z) : n)
                                : glm::dmat3(c.eyeFromWorld) * (worldFromLayoutWorld(lc) * n);
    n = glm::normalize(layoutFromEye(lc, c, other.space, eyeN));
  }
  other.normals.from = own.normals.from + " turned into " + spaceName(other.space) + " space by the camera";
  out.push_back(other);
  return out;
}

// Decides the normal candidates against `refs`; true when one was drafted.
bool decideAgainst(State& s, const std::vector<SpaceRef>& refs) {
  std::vector<Scored> scored;
  for (const Candidate& c : candidates(s)) scored.push_back(judge(s, c, refs));
  std::sort(scored.begin(), scored.end(), [](const Scored& a, const Scored& b) { return score(a.best) < score(b.best); });
  bool any = false;
  std::vector<size_t> targetsWithNormal;
  for (const Scored& r : scored) {
    if (r.best.count == 0 || !s.isFree(r.c.target, r.c.channels)) continue;
    if (std::count(targetsWithNormal.begin(), targetsWithNormal.end(), r.c.target)) continue;
    // The next best explanation of these channels: the other space, or no relation at all (70°: the
    // score of unrelated directions, whose |cos| angles have median 60° and p90 84°).
    double next = 70.0;
    Guess g;
    if (r.other.count) {
      next = std::min(next, score(r.other));
      g.rejected.push_back({std::string("normal (") + (r.space == Space::View ? "world" : "view") + " space)",
                            "angle to the rebuilt surface's normal: " + r.other.text()});
    }
    g.confidence = marginConfidence(score(r.best), next);
    if (!(score(r.best) <= 30.0) || g.confidence < kDecide) continue;
    double p50 = 0, p99 = 0;
    lengths(s, r.c, p50, p99);
    // Another encoding of the same channels (xyz and octahedral share x and y) that fits nearly as
    // well: the third channel decides. A unit xyz says xyz; a third channel that is no unit vector's
    // third component says the first two are octahedral.
    const Scored* rival = nullptr;
    for (const Scored& o : scored)
      if (o.c.target == r.c.target && o.c.encoding != r.c.encoding && o.best.count) rival = &o;
    if (rival) {
      const bool threeChannels = r.c.channels.size() == 3;
      const Candidate& xyz = threeChannels ? r.c : rival->c;
      double x50 = p50, x99 = p99;
      if (!threeChannels) lengths(s, xyz, x50, x99);
      const bool unit = x50 < 0.05;
      const bool keep = score(rival->best) > 2.0 * score(r.best) || unit == threeChannels;
      g.rejected.push_back({std::string("normal ") + name(rival->c.encoding) + " (" + std::to_string(rival->c.channels.size()) +
                                " channels)",
                            "angle: " + rival->best.text() + (keep && score(rival->best) <= 2.0 * score(r.best)
                                                                  ? std::string("; the xyz is ") + (unit ? "" : "not ") +
                                                                        "of unit length (median off 1 by " + numText(x50) + ")"
                                                                  : "")});
      if (!keep) continue;  // the rival is drafted when its turn comes
    }
    g.quantity = "normal";
    const bool normalized = r.c.encoding == NormalEncoding::Octahedral || r.c.encoding == NormalEncoding::OctahedralUnorm ||
                            !(p99 > lengthTolerance(s.in.targets[r.c.target].format));
    g.evidence = std::string(name(r.c.encoding)) + " in " + spaceName(r.space) + " space lies along the normal of " +
                 r.from + ": " + r.best.text() + "; lengths off 1 by " + numText(p50) + " (median), " + numText(p99) + " (p99)" +
                 (normalized ? "" : ": not renormalised");
    if (r.best.sameSide < 0.5) g.evidence += "; it points away from the camera at " + numText(100 * (1 - r.best.sameSide)) + " % of pixels (flipped?)";
    nlohmann::json fields = {{"encoding", name(r.c.encoding)}, {"space", spaceName(r.space)}};
    if (!normalized) fields["normalized"] = false;
    s.add(r.c.target, QuantityKind::Normal, r.c.channels, fields, g);
    targetsWithNormal.push_back(r.c.target);
    any = true;
  }
  return any;
}

}  // namespace

double bestNormalMedian(const State& s, const std::vector<SpaceRef>& refs) {
  double best = 180.0;
  for (const Candidate& c : candidates(s)) {
    const Scored r = judge(s, c, refs);
    if (r.best.count) best = std::min(best, score(r.best));
  }
  return best;
}

void decideNormalsAndDepths(State& s) {
  std::vector<SpaceRef> refs;
  if (s.cam.present && s.hardware)
    refs = referencesFromDepth(s, *s.hardware, s.cam.layout, s.cam.camera, "the surface the hardware depth and the camera rebuild");
  for (SpaceRef& r : referencesFromPositions(s)) refs.push_back(std::move(r));
  decideLinearDepths(s);
  if (refs.empty()) decideJointly(s);
  if (refs.empty() && s.linear && s.cam.present)
    refs = referencesFromDepth(s, *s.linear, s.cam.layout, s.cam.camera, "the surface the linear depth and the camera rebuild");
  s.normalsTested = !refs.empty();
  if (refs.empty()) {
    s.summary.push_back("normals: nothing to judge them by (no camera with a depth, no stored positions): vectors are shown as "
                        "stored");
    return;
  }
  decideAgainst(s, refs);
}

}  // namespace gb::infer
