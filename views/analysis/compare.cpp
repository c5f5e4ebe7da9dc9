// Capture comparison by meaning, per group: each pixel of a quantity decoded with its own frame's
// layout (renderer/core/decode.h) and compared with the metric its kind calls for, the figures over
// each set of pixels, idiff's verdict. compare_targets.cpp runs it over the targets.
#include "views/analysis/compare.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/decode.h"
#include "renderer/core/statistics.h"
#include "views/analysis/compare_internal.h"

namespace gb {

const char* name(MetricKind k) {
  static const char* n[] = {"colour", "normal", "depth", "position", "exact"};
  return n[int(k)];
}

MetricKind metricOf(QuantityKind k) {
  switch (k) {
    case QuantityKind::Normal: return MetricKind::Normal;
    case QuantityKind::Depth: return MetricKind::Depth;
    case QuantityKind::Position:
    case QuantityKind::Motion: return MetricKind::Position;
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count: return MetricKind::Exact;
    default: return MetricKind::Colour;
  }
}

std::vector<ChannelGroup> channelGroups(const Layout& layout, uint32_t target) {
  std::vector<ChannelGroup> groups;
  const std::vector<const Quantity*> qs = layout.quantitiesOf(target);
  for (const Quantity* q : qs) {
    const std::string& tn = layout.targets[target].name;
    groups.push_back({qs.size() == 1 ? tn : tn + "." + q->name, q->name, metricOf(q->kind), q->channels});
  }
  return groups;
}

double angleDegrees(const glm::dvec3& a, const glm::dvec3& b) {
  bool za = glm::dot(a, a) == 0.0, zb = glm::dot(b, b) == 0.0;
  if (za || zb) return za == zb ? 0.0 : 180.0;
  // atan2 of |a x b| and a . b stays accurate for tiny angles, where acos loses digits.
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * (180.0 / M_PI);
}

double absDifference(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0.0 : INFINITY;
  if (a == b) return 0.0;  // equal infinities
  return std::abs(a - b);
}

namespace {

using Side = CompareSide;

// Two projections equal to float precision (a camera read back from a uniform buffer is the double
// one rounded to float): hardware depths stored under them mean the same surfaces.
bool sameProjection(const Camera& a, const Camera& b) {
  if (a.reversedZ != b.reversedZ) return false;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (std::abs(a.clipFromEye[c][r] - b.clipFromEye[c][r]) > 1e-6 * std::max(1.0, std::abs(a.clipFromEye[c][r])))
        return false;
  return true;
}

// Both sides store the quantity the same way: then the stored values are compared as they are
// (bit-equal frames compare equal whatever the encoding, and thresholds keep their stored units).
bool sameStorage(const Side& a, const Side& b) {
  const LayoutTarget &ta = a.f.layout.targets[a.q.target], &tb = b.f.layout.targets[b.q.target];
  const Quantity &qa = a.q, &qb = b.q;
  // A hardware or radial depth means an eye depth only through its projection (standard and
  // reversed Z store the same surface as d and about 1 - d).
  const bool projected = qa.kind == QuantityKind::Depth && !qa.ofSun && qa.depth != DepthEncoding::Eye;
  if (projected && !sameProjection(a.f.camera, b.f.camera)) return false;
  return ta.format.name == tb.format.name && qa.channels.size() == qb.channels.size() && qa.kind == qb.kind &&
         qa.color == qb.color && qa.normal == qb.normal && qa.depth == qb.depth && qa.space == qb.space &&
         qa.background == qb.background && qa.scale == qb.scale && qa.bias == qb.bias && qa.units == qb.units;
}

// Stored values, sRGB-stored colour channels in stored units (one 8-bit step = 1/255, as idiff
// compares PNGs).
std::array<double, 4> storedUnits(const Side& s, uint32_t x, uint32_t y) {
  std::array<double, 4> v = storedValues(s.f, s.q, x, y);
  const TargetImage& ti = s.f.images[s.q.target];
  if (ti.image.encoding == Encoding::Srgb)
    for (size_t k = 0; k < s.q.channels.size() && k < 4; ++k) v[k] = ti.raw(x, y, s.q.channels[k]) / 255.0;
  return v;
}

// Decoded components of a colour/scalar/vector/integer quantity.
std::array<double, 4> decodedComponents(const Side& s, uint32_t x, uint32_t y) {
  switch (s.q.kind) {
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Radiance:
    case QuantityKind::Display: {
      glm::dvec4 c = decodeColor(s.f, s.q, x, y);
      return {c.r, c.g, c.b, c.a};
    }
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count: {
      std::array<double, 4> v = storedValues(s.f, s.q, x, y);
      for (double& c : v) c = std::isfinite(c) ? std::round(c) : c;
      return v;
    }
    default: {
      std::array<double, 4> v = storedValues(s.f, s.q, x, y);
      for (double& c : v) c = c * s.q.scale + s.q.bias;
      return v;
    }
  }
}

// Running sums over a group's compared pixels (colour/exact: per component; others: per pixel);
// one per pixel set, so every figure of a set covers the same pixels.
struct ErrorSums {
  double sumAbs = 0.0, sumSq = 0.0, sumRel = 0.0, maxAbs = 0.0, maxRel = 0.0, sumErr = 0.0, maxErr = 0.0;
  uint64_t samples = 0, differing = 0, compared = 0, coverage = 0, overWarn = 0, overFail = 0;
  void add(const ErrorSums& o) {
    sumAbs += o.sumAbs, sumSq += o.sumSq, sumRel += o.sumRel, sumErr += o.sumErr;
    maxAbs = std::max(maxAbs, o.maxAbs), maxRel = std::max(maxRel, o.maxRel), maxErr = std::max(maxErr, o.maxErr);
    samples += o.samples, differing += o.differing, compared += o.compared, coverage += o.coverage;
    overWarn += o.overWarn, overFail += o.overFail;
  }
};

// Largest component difference (colours, scalars, integers).
double componentError(const Side& a, const Side& b, bool stored, uint32_t x, uint32_t y, ErrorSums& s) {
  std::array<double, 4> va = stored ? storedUnits(a, x, y) : decodedComponents(a, x, y);
  std::array<double, 4> vb = stored ? storedUnits(b, x, y) : decodedComponents(b, x, y);
  const size_t n = std::min({a.q.channels.size(), b.q.channels.size(), size_t(4)});
  double e = 0.0;
  for (size_t k = 0; k < n; ++k) {
    double d = absDifference(va[k], vb[k]);
    e = std::max(e, d);
    s.sumAbs += d;
    s.sumSq += d * d;
    ++s.samples;
  }
  return e;
}

// Distance and relative distance of two vectors (positions, motion, depths as 1-vectors).
double distanceError(const std::array<double, 4>& va, const std::array<double, 4>& vb, size_t n, bool relative,
                     ErrorSums& s) {
  double dist2 = 0.0, rel = 0.0;
  for (size_t k = 0; k < n; ++k) {
    double d = absDifference(va[k], vb[k]);
    dist2 += d * d;
    if (d > 0.0) rel = std::max(rel, d / std::max(std::abs(va[k]), std::abs(vb[k])));
  }
  double abs = std::sqrt(dist2);
  if (std::isnan(rel) || std::isinf(abs)) rel = INFINITY;
  s.maxAbs = std::max(s.maxAbs, abs);
  s.maxRel = std::max(s.maxRel, rel);
  s.sumAbs += abs;
  s.sumRel += rel;
  return relative ? rel : abs;
}

std::array<double, 4> vec(const glm::dvec3& v) { return {v.x, v.y, v.z, 0.0}; }

// Whether pixel i belongs to a set (without a mask every pixel is in All).
bool inSet(PixelSet set, const CompareMask* mask, size_t i) {
  if (set == PixelSet::All || !mask) return true;
  return (mask->bits[i] != 0) == (set == PixelSet::Masked);
}

// The error of one pixel by the group's metric; nullopt where the pixel is not compared (normals
// where neither frame has a surface).
std::optional<double> pixelError(MetricKind kind, const Side& a, const Side& b, bool stored, uint32_t x, uint32_t y,
                                 ErrorSums& s) {
  switch (kind) {
    case MetricKind::Colour:
    case MetricKind::Exact: return componentError(a, b, stored, x, y, s);
    case MetricKind::Normal: {
      const bool sa = hasSurface(a.f, x, y), sb = hasSurface(b.f, x, y);
      if (!sa && !sb) return std::nullopt;
      if (sa != sb) return ++s.coverage, 180.0;
      return angleDegrees(decodeNormal(a.f, a.q, x, y).unit, decodeNormal(b.f, b.q, x, y).unit);
    }
    case MetricKind::Depth: {
      if (stored || a.q.ofSun || b.q.ofSun) return distanceError(storedValues(a.f, a.q, x, y), storedValues(b.f, b.q, x, y), 1, true, s);
      std::optional<double> da = decodeEyeDepth(a.f, a.q, x, y), db = decodeEyeDepth(b.f, b.q, x, y);
      if (!da && !db) return 0.0;
      if (!da || !db) return ++s.coverage, 1.0;  // a surface in one frame only: 100 %
      return distanceError({*da}, {*db}, 1, true, s);
    }
    case MetricKind::Position: {
      if (stored) return distanceError(storedValues(a.f, a.q, x, y), storedValues(b.f, b.q, x, y),
                                       std::min(a.q.channels.size(), b.q.channels.size()), false, s);
      if (a.q.kind == QuantityKind::Motion) {
        glm::dvec2 ma = decodeMotion(a.f, a.q, x, y), mb = decodeMotion(b.f, b.q, x, y);
        return distanceError({ma.x, ma.y}, {mb.x, mb.y}, 2, false, s);
      }
      std::optional<glm::dvec3> pa = decodePosition(a.f, a.q, x, y), pb = decodePosition(b.f, b.q, x, y);
      if (!pa && !pb) return 0.0;
      if (!pa || !pb) return ++s.coverage, INFINITY;
      return distanceError(vec(*pa), vec(*pb), 3, false, s);
    }
  }
  return 0.0;
}

// The figures of one pixel set: the kind's metrics under its names, the fractions over the thresholds.
GroupFigures figuresOf(const GroupResult& r, const ErrorSums& s, PixelSet set, const CompareMask* mask) {
  GroupFigures f;
  f.covers = set;
  f.pixels = s.compared;
  f.overWarn = s.overWarn;
  f.overFail = s.overFail;
  f.coverageDiffers = s.coverage;
  f.maxError = s.maxErr;
  const double n = double(std::max<uint64_t>(s.compared, 1));
  f.meanError = s.sumErr / n;
  const double samples = double(std::max<uint64_t>(s.samples, 1));
  nlohmann::json& m = f.metrics;
  switch (r.group.kind) {
    case MetricKind::Colour: {
      double rmse = std::sqrt(s.sumSq / samples);
      m = {{"max_abs", s.maxErr}, {"mean_abs", s.sumAbs / samples}, {"rmse", rmse},
           {"psnr_db", rmse > 0.0 ? 20.0 * std::log10(1.0 / rmse) : INFINITY}};
      break;
    }
    case MetricKind::Normal: {
      std::vector<double> compared;
      for (size_t i = 0; i < r.errors.size(); ++i)
        if (!std::isnan(r.errors[i]) && inSet(set, mask, i)) compared.push_back(r.errors[i]);
      m = {{"max_degrees", s.maxErr}, {"mean_degrees", f.meanError}, {"p99_degrees", percentile(compared, 0.99)}};
      break;
    }
    case MetricKind::Depth:
    case MetricKind::Position:
      m = {{"max_abs", s.maxAbs}, {"mean_abs", s.sumAbs / n}, {"max_rel", s.maxRel}, {"mean_rel", s.sumRel / n}};
      break;
    case MetricKind::Exact: m = {{"max_abs", s.maxErr}}; break;
  }
  m["differing_pixels"] = s.differing;
  if (r.group.kind == MetricKind::Normal || r.group.kind == MetricKind::Depth || r.group.kind == MetricKind::Position)
    m["coverage_differs"] = s.coverage;
  m["fraction_over_fail"] = double(s.overFail) / n;
  m["fraction_over_warn"] = double(s.overWarn) / n;
  return f;
}

}  // namespace

void compareGroup(const CompareSide& a, const CompareSide& b, const CompareMask* mask, GroupResult& r) {
  const TargetImage& ta = a.f.images[a.q.target];
  r.width = ta.image.width;
  r.height = ta.image.height;
  r.errors.assign(size_t(r.width) * r.height, 0.0f);
  if (mask && (mask->empty() || mask->width != r.width || mask->height != r.height)) mask = nullptr;
  const bool stored = sameStorage(a, b);
  ErrorSums sums[3];  // by PixelSet
  for (uint32_t y = 0; y < r.height; ++y)
    for (uint32_t x = 0; x < r.width; ++x) {
      const size_t i = size_t(y) * r.width + x;
      ErrorSums px;
      std::optional<double> e = pixelError(r.group.kind, a, b, stored, x + ta.x0, y + ta.y0, px);
      if (!e) {
        r.errors[i] = NAN;  // not compared (heat map: black; percentiles skip it)
        continue;
      }
      r.errors[i] = float(*e);
      px.compared = 1;
      px.sumErr = px.maxErr = *e;
      px.differing = *e > 0.0;
      px.overWarn = *e > r.thresholds.warn;
      px.overFail = *e > r.thresholds.fail;
      sums[int(PixelSet::All)].add(px);
      if (mask) sums[int(mask->bits[i] ? PixelSet::Masked : PixelSet::Unmasked)].add(px);
    }
  if (mask) {
    r.figures = figuresOf(r, sums[int(PixelSet::Unmasked)], PixelSet::Unmasked, mask);
    r.apart = {figuresOf(r, sums[int(PixelSet::Masked)], PixelSet::Masked, mask),
               figuresOf(r, sums[int(PixelSet::All)], PixelSet::All, mask)};
  } else {
    r.figures = figuresOf(r, sums[int(PixelSet::All)], PixelSet::All, nullptr);
  }
  const GroupFigures& d = r.figures;
  r.verdict = decide(r.thresholds, d.pixels, d.overWarn, d.overFail, d.maxError);
}

const char* name(PixelSet s) {
  static const char* n[] = {"all", "unmasked", "masked"};
  return n[int(s)];
}

const GroupFigures* GroupResult::figuresOver(PixelSet s) const {
  if (figures.covers == s) return &figures;
  for (const GroupFigures& f : apart)
    if (f.covers == s) return &f;
  return nullptr;
}

}  // namespace gb
