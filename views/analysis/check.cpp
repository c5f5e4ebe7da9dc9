// The NaN/Inf/denormal/out-of-range scan of a frame (see check.h): stored float bits are classified
// exactly; ranges are checked on the values the one decoder (renderer/core/decode.h) returns.
#include "views/analysis/check.h"

#include <cmath>
#include <cstdio>
#include <optional>

#include "renderer/core/decode.h"

namespace gb {

namespace {

// What a stored value's bits are when they are not an ordinary number (float types only).
std::optional<Anomaly> classify(PixelType type, uint32_t raw) {
  uint32_t exponent = 0, mantissa = 0, allOnes = 0;
  bool negative = false;
  if (type == PixelType::F16) {
    exponent = (raw >> 10) & 31u, mantissa = raw & 1023u, allOnes = 31u, negative = raw & 0x8000u;
  } else if (type == PixelType::F32) {
    exponent = (raw >> 23) & 255u, mantissa = raw & 0x7fffffu, allOnes = 255u, negative = raw >> 31;
  } else {
    return std::nullopt;
  }
  if (exponent == allOnes) return mantissa ? Anomaly::Nan : negative ? Anomaly::NegInf : Anomaly::PosInf;
  if (exponent == 0 && mantissa) return Anomaly::Denormal;
  return std::nullopt;
}

// The worst rounding of one stored channel in [-1, 1], in decoded units (half an integer step, or
// half an ulp below 1 for floats).
double channelRounding(const StorageFormat& f) {
  if (f.packed10) return 0.5 / 1023.0;
  switch (f.type) {
    case PixelType::U8: return 0.5 / 255.0;
    case PixelType::I8: return 0.5 / 127.0;
    case PixelType::U16: return 0.5 / 65535.0;
    case PixelType::I16: return 0.5 / 32767.0;
    case PixelType::F16: return std::ldexp(1.0, -12);
    case PixelType::F32: return std::ldexp(1.0, -25);
    case PixelType::U32: return 0.0;
  }
  return 0.0;
}

// How far from 1 a stored unit normal's length may be: twice the worst the storage can do to a unit
// vector (each of 3 components rounded: sqrt(3) * rounding; x2 for n * 0.5 + 0.5), at least 0.001.
double normalLengthTolerance(const Layout& l, const Quantity& q) {
  double e = channelRounding(l.targets[q.target].format) * (q.normal == NormalEncoding::XyzUnorm ? 2.0 : 1.0);
  return std::max(1e-3, 2.0 * std::sqrt(3.0) * e);
}


std::string number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.3g", v);
  return buf;
}

// What out of range means for a quantity ("" : nothing is).
std::string rangeText(const Layout& l, const Quantity& q) {
  switch (q.kind) {
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Display:
    case QuantityKind::Specular:
    case QuantityKind::Roughness:
    case QuantityKind::Metallic:
    case QuantityKind::Occlusion:
    case QuantityKind::Shadow: return "[0, 1]";
    case QuantityKind::Emission:
    case QuantityKind::Radiance: return ">= 0";
    case QuantityKind::Normal:
      switch (q.normal) {
        case NormalEncoding::Xyz:
        case NormalEncoding::XyzUnorm:
          return q.normalized ? "|n| = 1 ± " + number(normalLengthTolerance(l, q)) : "|n| > 0";
        case NormalEncoding::Octahedral: return "stored in [-1, 1]";
        case NormalEncoding::OctahedralUnorm: return "stored in [0, 1]";
        case NormalEncoding::Spheremap: return "|4c - 2| <= 2";
        case NormalEncoding::Lambert: return "|p| <= 1";
        case NormalEncoding::Octahedral12: return "";
      }
      return "";
    case QuantityKind::Depth: return q.depth == DepthEncoding::Hardware ? "[0, 1]" : ">= 0";
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count: return "an integer >= 0";
    default: return "";
  }
}

struct Outside {
  uint32_t component = 0;
  double value = 0.0;
  std::string what;  // what was measured when it is not a stored channel ("|Normal|")
};

// The first component of a quantity outside its range at (x, y), if any (stored values all finite).
std::optional<Outside> outOfRange(const FrameSnapshot& f, const Quantity& q, uint32_t x, uint32_t y, double tolerance) {
  auto outside01 = [](double v) { return !(v >= 0.0 && v <= 1.0); };
  switch (q.kind) {
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Display:
    case QuantityKind::Emission:
    case QuantityKind::Radiance: {
      const glm::dvec4 c = decodeColor(f, q, x, y);
      const bool unit = q.kind == QuantityKind::Albedo || q.kind == QuantityKind::BaseColor || q.kind == QuantityKind::Display;
      const uint32_t n = q.kind == QuantityKind::Display ? uint32_t(q.channels.size()) : 3u;
      for (uint32_t k = 0; k < n; ++k)
        if (unit ? outside01(c[int(k)]) : c[int(k)] < 0.0) return Outside{k, c[int(k)]};
      return std::nullopt;
    }
    case QuantityKind::Specular:
    case QuantityKind::Roughness:
    case QuantityKind::Metallic:
    case QuantityKind::Occlusion:
    case QuantityKind::Shadow: {
      const double v = decodeScalar(f, q, x, y);
      return outside01(v) ? std::optional(Outside{0, v}) : std::nullopt;
    }
    case QuantityKind::Normal: {
      const std::array<double, 4> s = storedValues(f, q, x, y);
      switch (q.normal) {
        case NormalEncoding::Xyz:
        case NormalEncoding::XyzUnorm: {
          const double length = glm::length(decodeNormal(f, q, x, y).stored);
          const bool bad = q.normalized ? !(std::abs(length - 1.0) <= tolerance) : !(length > 0.0);
          return bad ? std::optional(Outside{0, length, "|" + q.name + "|"}) : std::nullopt;
        }
        case NormalEncoding::Octahedral:
        case NormalEncoding::OctahedralUnorm:
          for (uint32_t k = 0; k < 2; ++k)
            if (q.normal == NormalEncoding::Octahedral ? std::abs(s[k]) > 1.0 : outside01(s[k])) return Outside{k, s[k]};
          return std::nullopt;
        case NormalEncoding::Spheremap: {
          const double r = glm::length(glm::dvec2(s[0], s[1]) * 4.0 - 2.0);
          return r > 2.0 ? std::optional(Outside{0, r, "|4c - 2| of " + q.name}) : std::nullopt;
        }
        case NormalEncoding::Lambert: {
          const double r = glm::length(glm::dvec2(s[0], s[1]));
          return r > 1.0 ? std::optional(Outside{0, r, "|p| of " + q.name}) : std::nullopt;
        }
        case NormalEncoding::Octahedral12: return std::nullopt;
      }
      return std::nullopt;
    }
    case QuantityKind::Depth: {
      const double v = storedValues(f, q, x, y)[0];
      if (q.background && v == *q.background) return std::nullopt;  // the layout says nothing was drawn here
      const bool bad = q.depth == DepthEncoding::Hardware ? outside01(v) : v < 0.0;
      return bad ? std::optional(Outside{0, v}) : std::nullopt;
    }
    case QuantityKind::Id:
    case QuantityKind::Stencil:
    case QuantityKind::Count: {
      const double v = storedValues(f, q, x, y)[0];
      return v < 0.0 || v != std::floor(v) ? std::optional(Outside{0, v}) : std::nullopt;
    }
    default: return std::nullopt;
  }
}

void note(AnomalyCount& a, uint32_t x, uint32_t y, const std::string& channel, double value) {
  if (a.count++ == 0) {
    a.x = x, a.y = y;
    a.channel = channel;
    a.value = value;
  }
}

// Where surfaces are, by texel of the surface depth's target (empty: every texel is one, or none
// can be told, e.g. a target of another size).
struct ScanMask {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> surface;
  explicit ScanMask(const FrameSnapshot& f) {
    for (const Quantity& q : f.layout.quantities) {
      if (q.kind != QuantityKind::Depth || q.ofSun) continue;
      const TargetImage* ti = layoutImage(f, q.target);
      if (!ti) continue;  // hasSurface uses the first camera depth the frame holds
      width = ti->targetWidth, height = ti->targetHeight;
      surface.resize(size_t(width) * height);
      for (uint32_t y = 0; y < height; ++y)
        for (uint32_t x = 0; x < width; ++x) surface[size_t(y) * width + x] = hasSurface(f, x, y);
      return;
    }
  }
  bool applies(const TargetImage& ti) const { return !surface.empty() && ti.targetWidth == width && ti.targetHeight == height; }
  bool at(uint32_t x, uint32_t y) const { return surface[size_t(y) * width + x]; }
};

// Scans `channels` of a target (and, for a quantity, its range), as the policy says.
CheckRow scan(const FrameSnapshot& f, uint32_t t, const std::vector<uint32_t>& channels, const Quantity* q,
              const ScanMask& mask, const CheckPolicy& policy) {
  const TargetImage& ti = f.images[t];
  const LayoutTarget& lt = f.layout.targets[t];
  CheckRow row;
  row.target = lt.name;
  row.quantity = q ? q->name : lt.channels[channels[0]];
  row.kind = q ? name(q->kind) : "channel";
  row.range = q ? rangeText(f.layout, *q) : "";
  row.surfacesOnly = q && surfaceQuantity(q->kind) && mask.applies(ti);
  const double tolerance = q && q->kind == QuantityKind::Normal ? normalLengthTolerance(f.layout, *q) : 0.0;
  for (size_t a = 0; a < kAnomalyCount; ++a) row.severity[a] = policy.at(row.quantity, anomalyClass(Anomaly(a)));
  auto reported = [&](Anomaly a) { return row.severity[size_t(a)] != Severity::Ignore; };
  for (uint32_t y = ti.y0; y < ti.y0 + ti.image.height; ++y)
    for (uint32_t x = ti.x0; x < ti.x0 + ti.image.width; ++x) {
      if (row.surfacesOnly && !mask.at(x, y)) continue;
      ++row.texels;
      bool finite = true;
      for (uint32_t c : channels)
        if (std::optional<Anomaly> a = classify(ti.image.type, ti.raw(x, y, c))) {
          if (reported(*a)) note(row.found[size_t(*a)], x, y, lt.channels[c], ti.value(x, y, c));
          finite = finite && *a == Anomaly::Denormal;
        }
      if (!finite || !q || row.range.empty() || !reported(Anomaly::OutOfRange)) continue;
      if (std::optional<Outside> o = outOfRange(f, *q, x, y, tolerance))
        note(row.found[size_t(Anomaly::OutOfRange)], x, y, o->what.empty() ? lt.channels[q->channels[o->component]] : o->what,
             o->value);
    }
  return row;
}

}  // namespace

bool surfaceQuantity(QuantityKind k) {
  switch (k) {
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Specular:
    case QuantityKind::Roughness:
    case QuantityKind::Metallic:
    case QuantityKind::Occlusion:
    case QuantityKind::Shadow:
    case QuantityKind::Normal:
    case QuantityKind::Position:
    case QuantityKind::Motion:
    case QuantityKind::Id: return true;
    default: return false;
  }
}

const char* name(Anomaly a) {
  static const char* n[] = {"nan", "+inf", "-inf", "denormal", "out_of_range"};
  return n[size_t(a)];
}

uint64_t CheckRow::total() const {
  uint64_t n = 0;
  for (const AnomalyCount& a : found) n += a.count;
  return n;
}

uint64_t CheckReport::total() const { return count(Severity::Fault) + count(Severity::Warn); }

uint64_t CheckReport::count(Severity s) const {
  uint64_t n = 0;
  for (const CheckRow& r : rows)
    for (size_t a = 0; a < kAnomalyCount; ++a)
      if (r.severity[a] == s) n += r.found[a].count;
  for (const PositionCheck& p : positions)
    if (p.severity == s) n += p.overBound;
  for (const NormalCheck& c : normals)
    if (c.severity == s && c.wrong()) ++n;
  return n;
}

uint64_t CheckReport::count(Anomaly a) const {
  uint64_t n = 0;
  for (const CheckRow& r : rows) n += r.found[size_t(a)].count;
  return n;
}

CheckReport checkFrame(const FrameSnapshot& f, const CheckPolicy& policy) {
  CheckReport report;
  const ScanMask mask(f);
  for (uint32_t t = 0; t < f.layout.targets.size(); ++t) {
    if (!layoutImage(f, t)) {
      report.absent.emplace_back(f.layout.targets[t].name, absentText(f.absences[t] == Absent::No ? Absent::NotCaptured : f.absences[t]));
      continue;
    }
    std::vector<bool> claimed(f.layout.targets[t].format.channels, false);
    for (const Quantity* q : f.layout.quantitiesOf(t)) {
      for (uint32_t c : q->channels) claimed[c] = true;
      report.rows.push_back(scan(f, t, q->channels, q, mask, policy));
    }
    for (uint32_t c = 0; c < claimed.size(); ++c)
      if (!claimed[c]) report.rows.push_back(scan(f, t, {c}, nullptr, mask, policy));
  }
  report.positions = checkPositions(f, policy);
  report.normals = checkNormals(f, policy);
  if (const Quantity* depth = surfaceDepth(f.layout); depth && layoutImage(f, depth->target)) {
    uint64_t n = 0;
    for (uint32_t y = 0; y < f.camera.height; ++y)
      for (uint32_t x = 0; x < f.camera.width; ++x) n += hasSurface(f, x, y);
    report.surfaces = "surfaces: where " + depth->name + " holds one, " + std::to_string(n) + " of " +
                      std::to_string(uint64_t(f.camera.width) * f.camera.height) + " pixels";
  } else {
    report.surfaces = "surfaces: unknown (the layout has no camera depth): every pixel is scanned as one";
  }
  return report;
}

}  // namespace gb
