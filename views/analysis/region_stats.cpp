// Region statistics (region_stats.h): values gathered per series over the rect, then one
// computation (seriesStats) for every series, stored or decoded.
#include "views/analysis/region_stats.h"

#include "views/analysis/visualize.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "renderer/core/camera.h"
#include "renderer/core/decode.h"
#include "views/analysis/check.h"

namespace gb {

bool parseRegionRect(const std::string& text, uint32_t frameWidth, uint32_t frameHeight, RegionRect& out,
                     std::string& error) {
  long v[4];
  char tail = 0;
  if (std::sscanf(text.c_str(), "%ld,%ld,%ld,%ld%c", &v[0], &v[1], &v[2], &v[3], &tail) != 4) {
    error = "\"" + text + "\" is not X,Y,W,H";
    return false;
  }
  if (v[0] < 0 || v[1] < 0 || v[2] <= 0 || v[3] <= 0) {
    error = "\"" + text + "\": X and Y must be >= 0, W and H > 0";
    return false;
  }
  if (v[0] + v[2] > long(frameWidth) || v[1] + v[3] > long(frameHeight)) {
    error = "\"" + text + "\" reaches outside the " + std::to_string(frameWidth) + "x" + std::to_string(frameHeight) +
            " frame";
    return false;
  }
  out = {uint32_t(v[0]), uint32_t(v[1]), uint32_t(v[2]), uint32_t(v[3])};
  return true;
}

SeriesStats seriesStats(const std::vector<double>& values, int bins) {
  SeriesStats s;
  std::vector<double> finite;
  finite.reserve(values.size());
  for (double v : values) {
    if (std::isnan(v))
      ++s.nan;
    else if (std::isinf(v))
      ++(v > 0 ? s.posInf : s.negInf);
    else
      finite.push_back(v);
  }
  s.count = finite.size();
  if (finite.empty()) return s;
  std::sort(finite.begin(), finite.end());
  const size_t n = finite.size();
  s.min = finite.front();
  s.max = finite.back();
  double sum = 0.0;
  for (double v : finite) sum += v;
  s.mean = sum / double(n);
  double squares = 0.0;
  for (double v : finite) squares += (v - s.mean) * (v - s.mean);
  s.stddev = std::sqrt(squares / double(n));
  auto rank = [&](double p) {  // nearest rank
    const size_t k = size_t(std::ceil(p / 100.0 * double(n)));
    return finite[std::min(n, std::max<size_t>(k, 1)) - 1];
  };
  s.p1 = rank(1.0), s.p50 = rank(50.0), s.p99 = rank(99.0);
  s.histogram.assign(size_t(std::max(bins, 1)), 0);
  const double span = s.max - s.min;
  for (double v : finite) {
    size_t b = span > 0.0 ? size_t((v - s.min) / span * double(s.histogram.size())) : 0;
    ++s.histogram[std::min(b, s.histogram.size() - 1)];
  }
  return s;
}

namespace {

// Values of one series while the rect is walked.
struct Gathered {
  std::string target, series, unit;
  bool surfacesOnly = false, integer = false;
  std::vector<double> values;
};

struct Gatherer {
  std::vector<Gathered> list;
  Gathered& at(const std::string& target, const std::string& series, const std::string& unit, bool surfacesOnly,
               bool integer = false) {
    for (Gathered& g : list)
      if (g.target == target && g.series == series) return g;
    list.push_back({target, series, unit, surfacesOnly, integer, {}});
    return list.back();
  }
};

// A quantity's decoded components at one pixel, as named series: the view's values (in the layout's
// own space and units, visualize.h), and for normals their angle to the view direction, for depths
// stored otherwise their eye depth.
void decodeAt(const FrameSnapshot& f, const ViewDef& v, uint32_t x, uint32_t y, bool surfaceOnly, Gatherer& out) {
  const Quantity& q = f.layout.quantities[size_t(v.quantity)];
  const std::string& t = f.layout.targets[q.target].name;
  auto put = [&](const std::string& series, const std::string& unit, double value, bool integer = false) {
    out.at(t, series, unit, surfaceOnly, integer).values.push_back(value);
  };
  std::optional<std::array<double, 4>> value = viewValue(f, v, x, y);
  if (!value) return;
  const std::string unit = !v.unit.empty() ? v.unit : v.space;
  const uint32_t n = v.visual == Visual::Color ? std::min(v.components, 3u) : v.components;
  for (uint32_t c = 0; c < n; ++c) put(componentLabel(v, int(c)), unit, (*value)[c], v.integer);
  if (v.visual == Visual::Normal) {
    const glm::dvec3 unitEye = decodeNormal(f, q, x, y).unit;
    const glm::dvec3 toViewer = -pixelRay(f.camera, x, y).direction;
    put(q.name + ".angle_to_view_deg", "deg", glm::degrees(std::acos(std::clamp(glm::dot(unitEye, toViewer), -1.0, 1.0))));
  }
  if (v.visual == Visual::Depth && !q.ofSun && q.depth != DepthEncoding::Eye)
    if (std::optional<double> z = decodeEyeDepth(f, q, x, y)) put(q.name + ".eye_depth", "eye depth", *z);
}

}  // namespace

RegionStats regionStats(const FrameSnapshot& f, const RegionRect& r, const std::string& target, int bins) {
  RegionStats s;
  s.rect = r;
  Gatherer channels, quantities;
  const bool surfaceKnown = surfaceDepth(f.layout) != nullptr;
  s.surfaceKnown = surfaceKnown;
  const std::vector<ViewDef> views = layoutViews(f.layout);
  for (uint32_t y = r.y; y < r.y + r.height; ++y)
    for (uint32_t x = r.x; x < r.x + r.width; ++x) {
      ++s.pixels;
      const bool surface = !surfaceKnown || hasSurface(f, x, y);
      s.surfacePixels += surface;
      for (uint32_t t = 0; t < f.layout.targets.size(); ++t) {
        const LayoutTarget& lt = f.layout.targets[t];
        const TargetImage* ti = layoutImage(f, t);
        if (!target.empty() && lt.name != target) continue;
        if (!ti || !ti->contains(x, y) || ti->targetWidth != f.camera.width) continue;  // the shadow map: not this frame's pixels
        for (uint32_t c = 0; c < ti->image.channelCount() && c < lt.channels.size(); ++c)
          channels.at(lt.name, lt.channels[c], "stored", false).values.push_back(ti->value(x, y, c));
        for (const ViewDef& v : views) {
          const Quantity& q = f.layout.quantities[size_t(v.quantity)];
          if (q.target != t || !holds(f, q, x, y)) continue;
          // Camera depths have no value where nothing was drawn (their background), like normals:
          // their figures are over the surfaces too, and say so.
          const bool cameraDepth = v.visual == Visual::Depth && !q.ofSun;
          const bool surfaceOnly = surfaceKnown && (surfaceQuantity(q.kind) || cameraDepth);
          if (surfaceOnly && !surface) continue;
          decodeAt(f, v, x, y, surfaceOnly, quantities);
        }
      }
    }
  auto finish = [&](const Gatherer& g, std::vector<SeriesStats>& out) {
    for (const Gathered& v : g.list) {
      SeriesStats st = seriesStats(v.values, bins);
      st.target = v.target, st.series = v.series, st.unit = v.unit, st.surfacesOnly = v.surfacesOnly;
      if (v.integer)
        for (double id : v.values) st.ids[uint32_t(id)]++;
      out.push_back(std::move(st));
    }
  };
  finish(channels, s.channels);
  finish(quantities, s.quantities);
  return s;
}

static const SeriesStats* findSeries(const std::vector<SeriesStats>& list, const std::string& target,
                                     const std::string& series) {
  for (const SeriesStats& s : list)
    if (s.target == target && s.series == series) return &s;
  return nullptr;
}
const SeriesStats* RegionStats::channel(const std::string& t, const std::string& s) const { return findSeries(channels, t, s); }
const SeriesStats* RegionStats::quantity(const std::string& t, const std::string& s) const { return findSeries(quantities, t, s); }

namespace {

std::string num(double v) {
  char b[32];
  std::snprintf(b, sizeof(b), "%.6g", v);
  return b;
}

nlohmann::json seriesJson(const SeriesStats& s) {
  nlohmann::json j = {{"target", s.target}, {"series", s.series},   {"unit", s.unit},   {"surfaces_only", s.surfacesOnly},
                      {"count", s.count},   {"nan", s.nan},         {"+inf", s.posInf}, {"-inf", s.negInf},
                      {"min", s.min},       {"max", s.max},         {"mean", s.mean},   {"stddev", s.stddev},
                      {"p1", s.p1},         {"p50", s.p50},         {"p99", s.p99},     {"histogram", s.histogram}};
  if (!s.ids.empty()) {
    nlohmann::json ids = nlohmann::json::object();
    for (const auto& [id, n] : s.ids) ids[std::to_string(id)] = n;
    j["ids"] = ids;
  }
  return j;
}

void textRows(const std::vector<SeriesStats>& list, std::ostringstream& o) {
  for (const SeriesStats& s : list) {
    o << "  " << s.target << " " << s.series << (s.surfacesOnly ? " (surfaces)" : "") << ": n " << s.count;
    if (s.count)
      o << "  min " << num(s.min) << "  max " << num(s.max) << "  mean " << num(s.mean) << "  sd " << num(s.stddev)
        << "  p1 " << num(s.p1) << "  p50 " << num(s.p50) << "  p99 " << num(s.p99);
    if (s.nan + s.posInf + s.negInf) o << "  NaN " << s.nan << "  +Inf " << s.posInf << "  -Inf " << s.negInf;
    if (!s.ids.empty()) {
      o << "  ids";
      size_t shown = 0;
      for (const auto& [id, n] : s.ids) {
        if (++shown > 8) {
          o << " ...";
          break;
        }
        o << " " << id << ":" << n;
      }
    }
    o << "\n";
  }
}

}  // namespace

std::string regionStatsText(const RegionStats& s) {
  std::ostringstream o;
  o << "region " << s.rect.x << "," << s.rect.y << " " << s.rect.width << "x" << s.rect.height << ": " << s.pixels
    << " pixels, " << s.surfacePixels
    << (s.surfaceKnown ? " with a surface" : " counted as surfaces (the layout has no camera depth: surfaces unknown)")
    << "\nstored channels (every pixel):\n";
  textRows(s.channels, o);
  o << "decoded quantities:\n";
  textRows(s.quantities, o);
  return o.str();
}

nlohmann::json regionStatsJson(const RegionStats& s) {
  // The JSON is an interface (docs/schemas/stats.schema.json): a change of shape bumps the version.
  nlohmann::json j = {{"format", "gblens-stats"}, {"version", 1},
                      {"rect", {{"x", s.rect.x}, {"y", s.rect.y}, {"width", s.rect.width}, {"height", s.rect.height}}},
                      {"pixels", s.pixels},
                      {"surface_pixels", s.surfacePixels}, {"surfaces_known", s.surfaceKnown},
                      {"channels", nlohmann::json::array()},
                      {"quantities", nlohmann::json::array()}};
  for (const SeriesStats& c : s.channels) j["channels"].push_back(seriesJson(c));
  for (const SeriesStats& q : s.quantities) j["quantities"].push_back(seriesJson(q));
  return j;
}

}  // namespace gb
