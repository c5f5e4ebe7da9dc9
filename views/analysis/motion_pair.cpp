// One pair of consecutive frames checked (`gblens motion`): every surface pixel of frame N reprojected
// into N-1 by its depth and both cameras; the convention that makes most pixels agree is detected
// (a field only where the alternatives explain clearly fewer); then each pixel is classed: static
// (and N-1 saw the point there), moving (N-1's G-buffer warped by the vector shows the same surface),
// disoccluded, or wrong.
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "renderer/core/decode.h"
#include "renderer/core/statistics.h"
#include "views/analysis/motion.h"
#include "renderer/core/parallel_rows.h"

namespace gb {

namespace {

struct MotionSample {
  uint32_t x = 0, y = 0;
  glm::dvec2 stored{0.0}, m{0.0}, mLag{0.0};
  bool hasLag = false;
  glm::dvec3 world{0.0};
  double ulp = 0.0;  // of the stored vector's larger component, in stored units
};

struct ConventionCandidate {
  MotionConvention c;
  uint64_t inliers = 0;
};

glm::dvec2 unitsPerPixel(const MotionConvention& c, uint32_t w, uint32_t h) {
  if (c.units == MotionUnits::Ndc) return glm::dvec2(2.0 / w, 2.0 / h) * c.scale;
  if (c.units == MotionUnits::Uv) return glm::dvec2(1.0 / w, 1.0 / h) * c.scale;
  return glm::dvec2(c.scale);
}

struct MotionPairContext {
  const FrameSnapshot *cur = nullptr, *prev = nullptr, *before = nullptr;
  uint32_t w = 0, h = 0;
  glm::dvec2 dj{0.0}, djLag{0.0}, jc{0.0}, jp{0.0};
  bool jitterKnown = true;
  double fixedBound = 0.0;

  // The inlier bound in pixels for a sample under a convention: the reprojection's own error (a
  // hundredth of a pixel plus 0.2 % of the motion: depth and matrix rounding), two storage ulps, and
  // when the sequence does not say the jitter, the half pixel it may have moved the depth samples by.
  double bound(const MotionSample& s, const MotionConvention& c) const {
    if (fixedBound > 0.0) return fixedBound;
    const glm::dvec2 upp = unitsPerPixel(c, w, h);
    return 0.02 + 0.002 * glm::length(s.m) + 2.0 * s.ulp / std::min(upp.x, upp.y) + (jitterKnown ? 0.0 : 0.75);
  }
  double residual(const MotionSample& s, const MotionConvention& c) const {
    const glm::dvec2 m = c.lag ? s.mLag : s.m;
    return glm::length(motionFromStored(c, s.stored, c.lag ? djLag : dj, w, h) - m);
  }
};

std::vector<MotionSample> gatherSamples(const MotionPairContext& pc, const Quantity& q) {
  const FrameSnapshot& C = *pc.cur;
  const TargetImage* img = layoutImage(C, q.target);
  std::vector<std::vector<MotionSample>> parts(pc.h);  // per row, joined in order: the same on any core count
  parallelRows(pc.h, size_t(pc.w) * pc.h, [&](uint32_t y0, uint32_t y1) {
  for (uint32_t y = y0; y < y1; ++y)
    for (uint32_t x = 0; x < pc.w; ++x) {
      std::vector<MotionSample>& out = parts[y];
      if (!holds(C, q, x, y)) continue;
      const std::optional<glm::dvec3> p = surfacePoint(C, x, y, pc.jc);
      if (!p) continue;
      const std::optional<glm::dvec2> up = projectToPixel(pc.prev->camera, *p);
      if (!up) continue;
      MotionSample s;
      s.x = x, s.y = y, s.world = *p;
      s.m = *up - glm::dvec2(x + 0.5 - pc.jc.x, y + 0.5 - pc.jc.y);
      const std::array<double, 4> v = storedValues(C, q, x, y);
      s.stored = glm::dvec2(v[0], v[1]);
      const double big = std::max(std::fabs(v[0]), std::fabs(v[1]));
      s.ulp = img ? storageUlp(img->image.type, img->image.encoding, big) : 0.0;
      if (pc.before) {
        if (auto pp = surfacePoint(*pc.prev, x, y, pc.jp)) {
          if (auto upp = projectToPixel(pc.before->camera, *pp)) {
            s.mLag = *upp - glm::dvec2(x + 0.5 - pc.jp.x, y + 0.5 - pc.jp.y);
            s.hasLag = true;
          }
        }
      }
      if (std::isfinite(s.stored.x) && std::isfinite(s.stored.y)) out.push_back(s);
    }
  });
  std::vector<MotionSample> all;
  for (std::vector<MotionSample>& p : parts) all.insert(all.end(), p.begin(), p.end());
  return all;
}

std::vector<ConventionCandidate> hypotheses(bool withLag) {
  std::vector<ConventionCandidate> out;
  for (int lag = 0; lag <= (withLag ? 1 : 0); ++lag)
    for (MotionUnits u : {MotionUnits::Pixels, MotionUnits::Ndc, MotionUnits::Uv})
      for (bool toPrev : {true, false})
        for (bool yUp : {false, true})
          for (double scale : {1.0, 0.5, 2.0})
            for (bool jit : {false, true}) {
              ConventionCandidate h;
              h.c.units = u, h.c.toPrevious = toPrev, h.c.yUp = yUp, h.c.scale = scale, h.c.jitterIncluded = jit, h.c.lag = lag;
              out.push_back(h);
            }
  return out;
}

int fieldsDiffering(const MotionConvention& a, const MotionConvention& b) {
  return (a.units != b.units) + (a.toPrevious != b.toPrevious) + (a.yUp != b.yUp) + (a.scale != b.scale) +
         (a.jitterIncluded != b.jitterIncluded) + (a.lag != b.lag);
}

// The best convention (ties: the one nearest the declared, then scale 1) and which fields are decided:
// every alternative differing in that field alone explains clearly fewer pixels.
void detect(const MotionPairContext& pc, const std::vector<MotionSample>& all, MotionPair& out) {
  const size_t stride = std::max<size_t>(1, all.size() / 40000);
  std::vector<const MotionSample*> sub;
  for (size_t i = 0; i < all.size(); i += stride)
    if (!pc.before || all[i].hasLag) sub.push_back(&all[i]);
  std::vector<ConventionCandidate> hs = hypotheses(pc.before != nullptr);
  parallelRows(uint32_t(hs.size()), hs.size() * sub.size(), [&](uint32_t a, uint32_t b) {
    for (uint32_t i = a; i < b; ++i)
      for (const MotionSample* s : sub) hs[i].inliers += pc.residual(*s, hs[i].c) < pc.bound(*s, hs[i].c);
  });
  auto better = [&](const ConventionCandidate& a, const ConventionCandidate& b) {
    if (a.inliers != b.inliers) return a.inliers > b.inliers;
    const int da = fieldsDiffering(a.c, out.declared), db = fieldsDiffering(b.c, out.declared);
    if (da != db) return da < db;
    return (a.c.scale == 1.0) > (b.c.scale == 1.0);
  };
  const ConventionCandidate best = *std::min_element(hs.begin(), hs.end(), [&](auto& a, auto& b) { return better(a, b); });
  const double n = double(sub.size());
  const uint64_t margin = uint64_t(std::max(10.0, 0.02 * n));
  auto decided = [&](auto same) {  // same(h): h differs from best in this field only
    uint64_t alt = 0;
    for (const ConventionCandidate& h : hs)
      if (same(h.c)) alt = std::max(alt, h.inliers);
    return best.inliers >= alt + margin;
  };
  const MotionConvention& b = best.c;
  auto eqExcept = [&](const MotionConvention& c, int field) {
    return (field == 0 || c.units == b.units) && (field == 1 || c.toPrevious == b.toPrevious) && (field == 2 || c.yUp == b.yUp) &&
           (field == 3 || c.scale == b.scale) && (field == 4 || c.jitterIncluded == b.jitterIncluded) &&
           (field == 5 || c.lag == b.lag) && fieldsDiffering(c, b) == 1;
  };
  MotionDecided& d = out.decided;
  d.units = decided([&](auto& c) { return eqExcept(c, 0); });
  d.direction = decided([&](auto& c) { return eqExcept(c, 1); });
  d.y = decided([&](auto& c) { return eqExcept(c, 2); });
  d.scale = decided([&](auto& c) { return eqExcept(c, 3); });
  d.jitter = decided([&](auto& c) { return eqExcept(c, 4); });
  d.lag = pc.before && decided([&](auto& c) { return eqExcept(c, 5); });
  out.found = b;
  // An undecided field keeps the declared value: nothing is claimed about it.
  if (!d.units) out.found.units = out.declared.units;
  if (!d.direction) out.found.toPrevious = out.declared.toPrevious;
  if (!d.y) out.found.yUp = out.declared.yUp;
  if (!d.scale) out.found.scale = out.declared.scale;
  if (!d.jitter) out.found.jitterIncluded = out.declared.jitterIncluded;
  if (!d.lag) out.found.lag = out.declared.lag;
  const bool any = d.units || d.direction || d.y || d.scale || d.jitter || d.lag;
  out.detected = n > 0 && best.inliers >= std::max(16.0, 0.2 * n) && any;
  if (n == 0) out.undecided = "no surface pixel reprojects into the previous frame";
  else if (best.inliers < std::max(16.0, 0.2 * n))
    out.undecided = "no convention explains the camera's motion at more than " +
                    std::to_string(int(100.0 * best.inliers / n)) + " % of the surface (wrong cameras, or vectors of another kind)";
  else if (!any) out.undecided = "the camera's motion is too small to tell conventions apart";
}

}  // namespace

// Classes in MotionPair::classMap.
enum : uint32_t { kNone = 0, kStatic = 1, kMoving = 2, kDisoccluded = 3, kWrong = 4 };

std::optional<double> viewDepthOf(const Camera& c, const glm::dvec3& world) {
  const double z = -(c.eyeFromWorld * glm::dvec4(world, 1.0)).z;
  return z > 0.0 ? std::optional<double>(z) : std::nullopt;
}

// Whether N-1's texel (tx, ty) shows the same surface as N's (x, y): ids equal, normals within 30
// degrees, albedo within 0.1, whichever the layout has; with none of them, depth within 10 %.
static bool sameSurface(const FrameSnapshot& C, uint32_t x, uint32_t y, const FrameSnapshot& P, uint32_t tx, uint32_t ty,
                        const glm::dvec3& world, glm::dvec2 jp) {
  bool checked = false;
  if (const Quantity* id = C.layout.find(QuantityKind::Id); id && holds(C, *id, x, y) && holds(P, *id, tx, ty)) {
    if (decodeInteger(C, *id, x, y) != decodeInteger(P, *id, tx, ty)) return false;
    checked = true;
  }
  if (const Quantity* nq = C.layout.find(QuantityKind::Normal); nq && holds(C, *nq, x, y) && holds(P, *nq, tx, ty)) {
    const glm::dvec3 a = glm::dmat3(C.camera.worldFromEye) * decodeNormal(C, *nq, x, y).unit;
    const glm::dvec3 b = glm::dmat3(P.camera.worldFromEye) * decodeNormal(P, *nq, tx, ty).unit;
    if (glm::dot(a, b) < std::cos(30.0 * 3.14159265358979 / 180.0)) return false;
    checked = true;
  }
  if (const Quantity* aq = C.layout.find(QuantityKind::Albedo); aq && holds(C, *aq, x, y) && holds(P, *aq, tx, ty)) {
    const glm::dvec4 a = decodeColor(C, *aq, x, y), b = decodeColor(P, *aq, tx, ty);
    if (glm::length(glm::dvec3(a) - glm::dvec3(b)) > 0.1) return false;
    checked = true;
  }
  if (checked) return true;
  const auto pw = surfacePoint(P, tx, ty, jp);
  const auto dc = viewDepthOf(C.camera, world);
  if (!pw || !dc) return false;
  const auto dp = viewDepthOf(P.camera, *pw);
  return dp && std::fabs(*dp - *dc) < 0.1 * *dc;
}

// The class of one surface pixel under the convention F (motion_pair.cpp's classes).
static uint32_t classify(const MotionPairContext& pc, const MotionConvention& F, const MotionSample& s) {
  const FrameSnapshot& C = *pc.cur;
  const FrameSnapshot& P = *pc.prev;
  const glm::dvec2 d = motionFromStored(F, s.stored, F.lag ? pc.djLag : pc.dj, pc.w, pc.h);
  const glm::dvec2 u(s.x + 0.5 - pc.jc.x, s.y + 0.5 - pc.jc.y);
  const bool agrees = pc.residual(s, F) < pc.bound(s, F);
  // Where N-1 shows this pixel's surface: by the camera alone (static) or by the stored vector.
  const glm::dvec2 target = (agrees ? u + (F.lag ? s.mLag : s.m) : u + d) + pc.jp;
  const double tx = std::floor(target.x), ty = std::floor(target.y);
  uint32_t c = kWrong;
  if (tx < 0 || ty < 0 || tx >= pc.w || ty >= pc.h) {
    c = kDisoccluded;  // off screen in N-1
  } else {
    bool same = false, nearer = false;
    // Static: N-1 saw the point where the camera puts it when its depth lies within the range of
    // N-1's depths around that place (a grazing surface changes depth fast from texel to texel).
    const std::optional<double> here = viewDepthOf(P.camera, s.world);
    const std::optional<double> dc = agrees ? std::nullopt : viewDepthOf(C.camera, s.world);
    double lo = 1e300, hi = -1e300;
    for (int oy = -1; oy <= 1 && !same; ++oy)
      for (int ox = -1; ox <= 1 && !same; ++ox) {
        const double nx = tx + ox, ny = ty + oy;
        if (nx < 0 || ny < 0 || nx >= pc.w || ny >= pc.h) continue;
        const uint32_t ix = uint32_t(nx), iy = uint32_t(ny);
        const auto pw = surfacePoint(P, ix, iy, pc.jp);
        const auto there = pw ? viewDepthOf(P.camera, *pw) : std::nullopt;
        if (agrees) {
          if (there) lo = std::min(lo, *there), hi = std::max(hi, *there);
        } else {
          same = sameSurface(C, s.x, s.y, P, ix, iy, s.world, pc.jp);
          nearer = nearer || (dc && there && *there < 0.98 * *dc);
        }
      }
    if (agrees && here) {
      const double tol = 0.01 * *here + 1e-4;
      same = lo <= hi && *here >= lo - tol && *here <= hi + tol;
      nearer = lo <= hi && *here > hi + tol;
    }
    c = same ? (agrees ? kStatic : kMoving) : nearer ? kDisoccluded : kWrong;
  }
  return c;
}

MotionPair checkMotionPair(const TemporalFrame& previous, const TemporalFrame& current, const TemporalFrame* beforePrevious,
                           const MotionPairOptions& options) {
  MotionPair out;
  out.previous = previous.number, out.current = current.number;
  const FrameSnapshot& C = *current.frame;
  const FrameSnapshot& P = *previous.frame;
  const Quantity* q = options.motion ? options.motion : C.layout.find(QuantityKind::Motion);
  if (!q) {
    out.undecided = "the layout has no motion quantity";
    return out;
  }
  out.declared = declaredConvention(*q);
  MotionPairContext pc;
  pc.cur = &C, pc.prev = &P, pc.before = beforePrevious ? beforePrevious->frame : nullptr;
  pc.w = C.camera.width, pc.h = C.camera.height;
  if (P.camera.width != pc.w || P.camera.height != pc.h) {
    out.undecided = "the frames differ in size";
    return out;
  }
  // An imported frame whose layout gives no camera has none to reproject with (gblens's own frames
  // always have the renderer's).
  auto noCamera = [](const FrameSnapshot& f) { return !f.unknown.empty() && !f.layout.camera.present; };
  if (noCamera(C) || noCamera(P)) {
    out.undecided = "the layout gives no camera: reprojection needs both frames' cameras";
    return out;
  }
  pc.jitterKnown = current.jitter.has_value() && previous.jitter.has_value();
  pc.jc = current.jitter.value_or(glm::dvec2(0.0)), pc.jp = previous.jitter.value_or(glm::dvec2(0.0));
  pc.dj = pc.jp - pc.jc;
  if (beforePrevious) pc.djLag = beforePrevious->jitter.value_or(glm::dvec2(0.0)) - pc.jp;
  pc.fixedBound = options.inlierPixels;
  const std::vector<MotionSample> all = gatherSamples(pc, *q);
  out.surfacePixels = all.size();
  detect(pc, all, out);
  if (out.detected) out.differences = conventionDifferences(out.declared, out.found, out.decided);
  out.bound = all.empty() ? pc.bound(MotionSample{}, out.declared) : pc.bound(all[all.size() / 2], out.declared);

  out.errorMap.name = "motion_error", out.errorMap.channels = {"error"}, out.errorMap.type = PixelType::F32;
  out.classMap.name = "motion_class", out.classMap.channels = {"class"}, out.classMap.type = PixelType::U32;
  out.errorMap.width = out.classMap.width = pc.w;
  out.errorMap.height = out.classMap.height = pc.h;
  std::vector<float> err(size_t(pc.w) * pc.h, std::numeric_limits<float>::quiet_NaN());
  std::vector<uint32_t> cls(size_t(pc.w) * pc.h, kNone);
  const MotionConvention& F = out.detected ? out.found : out.declared;
  std::vector<double> staticErrors;
  parallelRows(uint32_t(all.size()), all.size() * 16, [&](uint32_t i0, uint32_t i1) {
    for (uint32_t i = i0; i < i1; ++i) {
      const MotionSample& s = all[i];
      if (out.declared.lag == 0 || s.hasLag) err[size_t(s.y) * pc.w + s.x] = float(pc.residual(s, out.declared));
      if (!F.lag || s.hasLag) cls[size_t(s.y) * pc.w + s.x] = classify(pc, F, s);
    }
  });
  for (const MotionSample& s : all) {
    const uint32_t c = cls[size_t(s.y) * pc.w + s.x];
    if (c == kStatic) {
      ++out.staticPixels;
      const float e = err[size_t(s.y) * pc.w + s.x];
      if (std::isfinite(e)) staticErrors.push_back(e);
    }
    out.movingPixels += c == kMoving;
    out.disoccluded += c == kDisoccluded;
    out.wrongMoving += c == kWrong;
  }
  out.staticFraction = all.empty() ? 0.0 : double(out.staticPixels) / double(all.size());
  out.medianError = median(staticErrors);
  out.p95Error = percentile(staticErrors, 0.95);
  out.maxError = staticErrors.empty() ? 0.0 : *std::max_element(staticErrors.begin(), staticErrors.end());
  out.errorMap.data.resize(err.size() * 4);
  std::memcpy(out.errorMap.data.data(), err.data(), out.errorMap.data.size());
  out.classMap.data.resize(cls.size() * 4);
  std::memcpy(out.classMap.data.data(), cls.data(), out.classMap.data.size());
  return out;
}

nlohmann::json motionPairJson(const MotionPair& p) {
  nlohmann::json j = {{"previous", p.previous},
                      {"current", p.current},
                      {"declared", conventionJson(p.declared)},
                      {"detected", p.detected ? conventionJson(p.found, &p.decided) : nlohmann::json()},
                      {"differences", p.differences},
                      {"undecided", p.undecided.empty() ? nlohmann::json() : nlohmann::json(p.undecided)},
                      {"bound_pixels", p.bound},
                      {"pixels", {{"surface", p.surfacePixels}, {"static", p.staticPixels}, {"moving", p.movingPixels},
                                  {"disoccluded", p.disoccluded}, {"wrong", p.wrongMoving}}},
                      {"static_error_pixels", {{"median", p.medianError}, {"p95", p.p95Error}, {"max", p.maxError}}}};
  return j;
}

}  // namespace gb
