// Capture comparison: channel groups and their metrics, idiff's decision rule, the report.
#include "views/analysis/compare.h"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <functional>

#include "renderer/core/codec.h"
#include "renderer/core/statistics.h"

namespace gb {

const char* name(MetricKind k) {
  static const char* n[] = {"colour", "normal", "depth", "position", "exact"};
  return n[int(k)];
}

static bool startsWith(const std::string& s, const char* p) { return s.rfind(p, 0) == 0; }

static MetricKind channelKind(Target t, const CpuImage& img, const std::string& ch) {
  std::string target = targetName(t);
  if (img.encoding == Encoding::Uint || ch == "Stencil") return MetricKind::Exact;
  if (startsWith(ch, "N.")) return MetricKind::Normal;
  if (startsWith(ch, "P.") || target.find("position") != std::string::npos) return MetricKind::Position;
  if (ch == "Z" || ch == "Depth") return MetricKind::Depth;
  return MetricKind::Colour;
}

std::vector<ChannelGroup> channelGroups(Target t, const CpuImage& img) {
  std::vector<ChannelGroup> groups;
  for (uint32_t c = 0; c < img.channelCount(); ++c) {
    MetricKind k = channelKind(t, img, img.channels[c]);
    auto it = std::find_if(groups.begin(), groups.end(), [k](const ChannelGroup& g) { return g.kind == k; });
    if (it == groups.end()) {
      const std::string& ch = img.channels[c];
      groups.push_back({"", ch.substr(0, ch.find('.')), k, {}});
      it = groups.end() - 1;
    }
    it->channels.push_back(c);
  }
  for (ChannelGroup& g : groups) g.key = groups.size() == 1 ? targetName(t) : std::string(targetName(t)) + "." + g.group;
  return groups;
}

// ---- thresholds --------------------------------------------------------------------------------

bool ThresholdSettings::add(const std::string& param, const std::string& text, std::string& error) {
  std::string key, number = text;
  size_t eq = text.find('=');
  if (eq != std::string::npos) {
    key = text.substr(0, eq);
    number = text.substr(eq + 1);
    Target t;
    if (key.empty() || !parseTarget(key.substr(0, key.find('.')), t)) {
      error = "--" + param + " " + text + ": \"" + key + "\" names no target";
      return false;
    }
  }
  char* end = nullptr;
  double v = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || std::isnan(v) || v < 0.0) {
    error = "--" + param + " " + text + ": expected a non-negative number" + (key.empty() ? "" : " after =");
    return false;
  }
  byKey[key][param] = v;
  return true;
}

Thresholds ThresholdSettings::resolve(const std::string& target, const std::string& key) const {
  Thresholds t;
  for (const std::string& k : {std::string(), target, key}) {
    auto it = byKey.find(k);
    if (it == byKey.end()) continue;
    for (auto& [param, v] : it->second) {
      if (param == "fail") t.fail = v;
      if (param == "failpercent") t.failPercent = v;
      if (param == "hardfail") t.hardFail = v;
      if (param == "warn") t.warn = v;
      if (param == "warnpercent") t.warnPercent = v;
    }
  }
  return t;
}

Verdict decide(const Thresholds& t, uint64_t pixels, uint64_t overWarn, uint64_t overFail, double maxError) {
  if (double(overFail) > t.failPercent / 100.0 * double(pixels) || maxError > t.hardFail) return Verdict::Fail;
  if (double(overWarn) > t.warnPercent / 100.0 * double(pixels)) return Verdict::Warn;
  return Verdict::Pass;
}

// ---- metrics -----------------------------------------------------------------------------------

double angleDegrees(const glm::dvec3& a, const glm::dvec3& b) {
  bool za = glm::dot(a, a) == 0.0, zb = glm::dot(b, b) == 0.0;
  if (za || zb) return za == zb ? 0.0 : 180.0;
  // atan2 of |a x b| and a . b stays accurate for tiny angles, where acos loses digits.
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * (180.0 / M_PI);
}

// sRGB-stored channels compare in stored units (one 8-bit step = 1/255), as idiff does PNGs.
static double colourValue(const CpuImage& img, uint32_t x, uint32_t y, uint32_t c) {
  return img.encoding == Encoding::Srgb ? img.raw(x, y, c) / 255.0 : img.value(x, y, c);
}

static double absDiff(double a, double b) {
  if (std::isnan(a) || std::isnan(b)) return std::isnan(a) && std::isnan(b) ? 0.0 : INFINITY;
  if (a == b) return 0.0;  // equal infinities
  return std::abs(a - b);
}

static glm::dvec3 normalAt(Target t, const Capture& cap, const CpuImage& img, const ChannelGroup& g, uint32_t x,
                           uint32_t y) {
  if (t == Target::NormalShadow) return decodeNormalTexel(img, x, y, cap.frame.options.normalFormat).unit;
  glm::dvec3 v(0.0);
  for (size_t i = 0; i < g.channels.size() && i < 3; ++i) v[int(i)] = img.value(x, y, g.channels[i]);
  return v;
}

namespace {
// Running sums over a group's pixels (colour/exact: per channel sample; depth/position: per pixel).
struct ErrorSums {
  double sumAbs = 0.0, sumSq = 0.0, sumRel = 0.0, maxAbs = 0.0, maxRel = 0.0, sumErr = 0.0;
  uint64_t samples = 0, differing = 0;
};
}  // namespace

// The error of one pixel by the group's metric (largest channel difference, angle in degrees,
// relative depth or position distance), with the group's sums updated.
static double pixelError(Target t, const Capture& ca, const Capture& cb, const ChannelGroup& g, uint32_t x, uint32_t y,
                         ErrorSums& s) {
  const CpuImage& a = ca.frame.target(t).image;
  const CpuImage& b = cb.frame.target(t).image;
  double e = 0.0;
  switch (g.kind) {
    case MetricKind::Colour:
    case MetricKind::Exact:
      for (uint32_t c : g.channels) {
        double va = g.kind == MetricKind::Colour ? colourValue(a, x, y, c) : a.value(x, y, c);
        double vb = g.kind == MetricKind::Colour ? colourValue(b, x, y, c) : b.value(x, y, c);
        double d = absDiff(va, vb);
        e = std::max(e, d);
        s.sumAbs += d;
        s.sumSq += d * d;
        ++s.samples;
      }
      break;
    case MetricKind::Normal: e = angleDegrees(normalAt(t, ca, a, g, x, y), normalAt(t, cb, b, g, x, y)); break;
    case MetricKind::Depth:
    case MetricKind::Position: {
      double dist2 = 0.0, mag = 0.0, rel = 0.0;
      for (uint32_t c : g.channels) {
        double va = a.value(x, y, c), vb = b.value(x, y, c), d = absDiff(va, vb);
        dist2 += d * d;
        mag = std::max({mag, std::abs(va), std::abs(vb)});
        if (d > 0.0) rel = std::max(rel, d / std::max(std::abs(va), std::abs(vb)));
      }
      double abs = std::sqrt(dist2);
      if (std::isnan(rel) || std::isinf(abs)) rel = INFINITY;
      s.maxAbs = std::max(s.maxAbs, abs);
      s.maxRel = std::max(s.maxRel, rel);
      s.sumAbs += abs;
      s.sumRel += rel;
      e = g.kind == MetricKind::Depth ? rel : abs;
      break;
    }
  }
  return e;
}

// The group's metrics under its kind's names, the fractions over the thresholds.
static nlohmann::json groupMetrics(const GroupResult& r, const ErrorSums& s) {
  const double n = double(std::max<uint64_t>(r.pixels, 1));
  nlohmann::json m;
  switch (r.group.kind) {
    case MetricKind::Colour: {
      double rmse = std::sqrt(s.sumSq / double(std::max<uint64_t>(s.samples, 1)));
      m = {{"max_abs", r.maxError}, {"mean_abs", s.sumAbs / double(std::max<uint64_t>(s.samples, 1))}, {"rmse", rmse},
           {"psnr_db", rmse > 0.0 ? 20.0 * std::log10(1.0 / rmse) : INFINITY}};
      break;
    }
    case MetricKind::Normal: {
      const double p99 = percentile(std::vector<double>(r.errors.begin(), r.errors.end()), 0.99);
      m = {{"max_degrees", r.maxError}, {"mean_degrees", r.meanError}, {"p99_degrees", p99}};
      break;
    }
    case MetricKind::Depth:
    case MetricKind::Position:
      m = {{"max_abs", s.maxAbs}, {"mean_abs", s.sumAbs / n}, {"max_rel", s.maxRel}, {"mean_rel", s.sumRel / n}};
      break;
    case MetricKind::Exact: m = {{"differing_pixels", s.differing}, {"max_abs", r.maxError}}; break;
  }
  m["differing_pixels"] = s.differing;
  m["fraction_over_fail"] = double(r.overFail) / n;
  m["fraction_over_warn"] = double(r.overWarn) / n;
  return m;
}

static void compareGroup(Target t, const Capture& ca, const Capture& cb, GroupResult& r) {
  const CpuImage& a = ca.frame.target(t).image;
  r.width = a.width;
  r.height = a.height;
  r.pixels = uint64_t(a.width) * a.height;
  r.errors.assign(r.pixels, 0.0f);
  ErrorSums s;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x) {
      double e = pixelError(t, ca, cb, r.group, x, y, s);
      r.errors[size_t(y) * a.width + x] = float(e);
      r.maxError = std::max(r.maxError, e);
      s.sumErr += e;
      s.differing += e > 0.0;
      r.overWarn += e > r.thresholds.warn;
      r.overFail += e > r.thresholds.fail;
    }
  r.meanError = s.sumErr / double(std::max<uint64_t>(r.pixels, 1));
  r.metrics = groupMetrics(r, s);
  r.verdict = decide(r.thresholds, r.pixels, r.overWarn, r.overFail, r.maxError);
}

// Manifest fields whose difference a reader should know about: every option, the scene, the
// lights, the device and the build.
static void manifestDifferences(const nlohmann::json& a, const nlohmann::json& b, nlohmann::json& out) {
  nlohmann::json fa = nlohmann::json::object(), fb = nlohmann::json::object();
  for (const char* key : {"options", "scene", "device", "driver", "gblens", "lights", "sun"}) {
    fa[key] = a.is_object() ? a.value(key, nlohmann::json()) : nlohmann::json();
    fb[key] = b.is_object() ? b.value(key, nlohmann::json()) : nlohmann::json();
  }
  for (nlohmann::json* j : {&fa, &fb})
    if ((*j)["lights"].is_object()) (*j)["lights"].erase("file");
  nlohmann::json flatA = fa.flatten(), flatB = fb.flatten();
  for (auto& [k, v] : flatA.items())
    if (!flatB.contains(k) || flatB[k] != v) out.push_back({{"name", k.substr(1)}, {"a", v}, {"b", flatB.value(k, nlohmann::json())}});
  for (auto& [k, v] : flatB.items())
    if (!flatA.contains(k)) out.push_back({{"name", k.substr(1)}, {"a", nullptr}, {"b", v}});
  for (auto& d : out) std::replace(d["name"].get_ref<std::string&>().begin(), d["name"].get_ref<std::string&>().end(), '/', '.');
}

bool compareCaptures(const Capture& ca, const Capture& cb, const ThresholdSettings& settings, CompareReport& report,
                     std::string& error) {
  report = CompareReport{};
  report.a = ca.dir;
  report.b = cb.dir;
  manifestDifferences(ca.manifest, cb.manifest, report.differences);
  std::vector<std::string> knownKeys = {""};
  Verdict worst = Verdict::Pass;
  for (const TargetInfo& info : targetTable()) {
    const Target t = info.target;
    const TargetImage &a = ca.frame.target(t), &b = cb.frame.target(t);
    std::string tn = targetName(t);
    if (!a.present() && !b.present()) {
      report.skipped.push_back({tn, std::string("absent in both (A: ") + absentText(ca.frame.absence(t)) +
                                        "; B: " + absentText(cb.frame.absence(t)) + ")"});
      continue;
    }
    if (a.present() != b.present()) {
      const char* why = absentText(a.present() ? cb.frame.absence(t) : ca.frame.absence(t));
      report.mismatches.push_back({tn, std::string("only in ") + (a.present() ? "A" : "B") + " (" + why + ")"});
      continue;
    }
    if (a.image.width != b.image.width || a.image.height != b.image.height) {
      report.mismatches.push_back({tn, "size " + std::to_string(a.image.width) + "x" + std::to_string(a.image.height) +
                                           " vs " + std::to_string(b.image.width) + "x" + std::to_string(b.image.height)});
      continue;
    }
    if (a.image.channels != b.image.channels) {
      report.mismatches.push_back({tn, "different channels"});
      continue;
    }
    knownKeys.push_back(tn);
    for (const ChannelGroup& g : channelGroups(t, a.image)) {
      knownKeys.push_back(g.key);
      GroupResult r;
      r.group = g;
      r.target = tn;
      r.thresholds = settings.resolve(tn, g.key);
      compareGroup(t, ca, cb, r);
      worst = std::max(worst, r.verdict);
      report.groups.push_back(std::move(r));
    }
  }
  // A key for a target that was compared must name it or one of its groups; keys for targets
  // absent from both captures are ignored (one threshold file serves several configurations).
  for (auto& [key, params] : settings.byKey)
    if (std::find(knownKeys.begin(), knownKeys.end(), key.substr(0, key.find('.'))) != knownKeys.end() &&
        std::find(knownKeys.begin(), knownKeys.end(), key) == knownKeys.end()) {
      error = "threshold for \"" + key + "\": no such group (groups:";
      for (const GroupResult& g : report.groups) error += " " + g.group.key;
      error += ")";
      return false;
    }
  report.exitCode = report.mismatches.empty() ? int(worst) : kCompareMismatch;
  return true;
}

}  // namespace gb
