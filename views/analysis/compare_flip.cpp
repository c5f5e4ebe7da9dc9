// FLIP in compare (compare.h, FlipResult): LDR-FLIP of `final`, HDR-FLIP of `hdr`, their pooled
// values in the report, thresholds on the mean, and the magma error maps.
#include <cmath>
#include <cstdio>
#include <cstdlib>

#include "renderer/core/decode.h"
#include "views/analysis/compare.h"
#include "views/analysis/compare_internal.h"

namespace gb {

namespace {

// The targets FLIP looks at, and which FLIP: the display output is LDR, the radiance HDR.
struct FlipTarget {
  const char* name;
  QuantityKind kind;
  bool hdr;
};
constexpr FlipTarget kFlipTargets[] = {{"final", QuantityKind::Display, false}, {"hdr", QuantityKind::Radiance, true}};

// The target's colour decoded to linear RGB (sRGB-stored values linearised); false when the frame
// does not hold it.
bool flipImage(const FrameSnapshot& f, const FlipTarget& t, FlipImage& out) {
  const int index = f.indexOf(t.name);
  if (index < 0 || !f.images[size_t(index)].present()) return false;
  const Quantity* q = nullptr;
  for (const Quantity* c : f.layout.quantitiesOf(uint32_t(index)))
    if (c->kind == t.kind && c->channels.size() >= 3) q = c;
  if (!q) return false;
  const TargetImage& ti = f.images[size_t(index)];
  out.width = ti.image.width;
  out.height = ti.image.height;
  out.rgb.resize(size_t(out.width) * out.height * 3);
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x) {
      const glm::dvec4 c = decodeColor(f, *q, x + ti.x0, y + ti.y0);
      for (int k = 0; k < 3; ++k) out.rgb[(size_t(y) * out.width + x) * 3 + k] = float(c[k]);
    }
  return true;
}

std::optional<double> setting(const std::map<std::string, double>& m, const std::string& target) {
  if (auto it = m.find(target); it != m.end()) return it->second;
  if (auto it = m.find(""); it != m.end()) return it->second;
  return std::nullopt;
}

nlohmann::json poolJson(const FlipPool& p) {
  return {{"pixels", p.pixels}, {"mean", p.mean}, {"weighted_median", p.weightedMedian},
          {"weighted_quartile_1", p.weightedQuartile1}, {"weighted_quartile_3", p.weightedQuartile3},
          {"min", p.min}, {"max", p.max}};
}

std::string flipFigure(double v) {
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

// A pool's figures and the pixels they cover, on one line.
std::string poolText(const FlipPool& p, PixelSet covers) {
  return "mean " + flipFigure(p.mean) + " weighted median " + flipFigure(p.weightedMedian) + " quartiles " + flipFigure(p.weightedQuartile1) +
         ".." + flipFigure(p.weightedQuartile3) + " min " + flipFigure(p.min) + " max " + flipFigure(p.max) + " over " +
         std::to_string(p.pixels) + " px (" + name(covers) + ")";
}

}  // namespace

bool FlipSettings::add(const std::string& flag, const std::string& text, std::string& error) {
  std::string key, number = text;
  if (size_t eq = text.find('='); eq != std::string::npos) {
    key = text.substr(0, eq);
    number = text.substr(eq + 1);
    if (key != "final" && key != "hdr") {
      error = flag + " " + text + ": FLIP applies to final or hdr, not \"" + key + "\"";
      return false;
    }
  }
  char* end = nullptr;
  const double v = std::strtod(number.c_str(), &end);
  if (number.empty() || *end != '\0' || !std::isfinite(v) || v < 0.0) {
    error = flag + " " + text + ": expected a non-negative number (a mean FLIP, 0 to 1)";
    return false;
  }
  (flag == "--fail-flip" ? fail : warn)[key] = v;
  return true;
}

Verdict decideFlip(const FlipResult& r) {
  if (r.fail && r.pool.mean > *r.fail) return Verdict::Fail;
  if (r.warn && r.pool.mean > *r.warn) return Verdict::Warn;
  return Verdict::Pass;
}

void compareFlip(const Capture& a, const Capture& b, const FlipSettings& settings, CompareReport& report) {
  Verdict worst = Verdict::Pass;
  for (const FlipTarget& t : kFlipTargets) {
    FlipImage ia, ib;
    if (!flipImage(a.frame, t, ia) || !flipImage(b.frame, t, ib) || ia.width != ib.width || ia.height != ib.height ||
        ia.rgb.empty())
      continue;  // absent or mismatched: the target's own entry says why
    const auto started = std::chrono::steady_clock::now();
    FlipResult r;
    r.target = t.name;
    r.method = t.hdr ? "hdr" : "ldr";
    r.ppd = settings.ppd;
    r.width = ia.width;
    r.height = ia.height;
    if (t.hdr) {
      r.exposures = hdrFlipExposures(ia);  // from the reference, A
      r.errors = hdrFlip(ia, ib, r.ppd, r.exposures);
    } else {
      r.errors = ldrFlip(ia, ib, r.ppd);
    }
    r.pool = poolFlip(r.errors);
    if (const CompareMask& m = report.mask; !m.empty() && m.width == r.width && m.height == r.height) {
      std::vector<uint8_t> unmasked(m.bits.size());
      for (size_t i = 0; i < m.bits.size(); ++i) unmasked[i] = !m.bits[i];
      r.masked = true;
      r.covers = PixelSet::Unmasked;
      r.allPool = r.pool;
      r.pool = poolFlip(r.errors, m.bits);
      r.maskedPool = poolFlip(r.errors, unmasked);
    }
    r.fail = setting(settings.fail, t.name);
    r.warn = setting(settings.warn, t.name);
    r.verdict = decideFlip(r);
    worst = std::max(worst, r.verdict);
    r.seconds = secondsSince(started);
    report.flips.push_back(std::move(r));
  }
  if (report.exitCode != kCompareMismatch && report.exitCode != kCompareFileError)
    report.exitCode = std::max(report.exitCode, int(worst));
}

nlohmann::json flipJson(const FlipResult& r) {
  static const char* verdicts[] = {"pass", "warn", "fail"};
  nlohmann::json j = {{"target", r.target}, {"method", r.method == "hdr" ? "HDR-FLIP" : "LDR-FLIP"},
                      {"ppd", r.ppd}};
  if (r.method == "hdr")
    j["exposures"] = {{"start", r.exposures.start}, {"stop", r.exposures.stop}, {"count", r.exposures.count},
                      {"tone_mapper", "aces"}};
  j["covers"] = name(r.covers);
  j.update(poolJson(r.pool));
  j["histogram"] = {{"buckets", r.pool.histogram.size()}, {"range", {0.0, 1.0}},
                    {"weighting", "pixel count x bucket centre, per megapixel (2^20 pixels)"},
                    {"values", r.pool.histogram}};
  j["thresholds"] = {{"fail", r.fail ? nlohmann::json(*r.fail) : nlohmann::json(nullptr)},
                     {"warn", r.warn ? nlohmann::json(*r.warn) : nlohmann::json(nullptr)}, {"on", "mean"}};
  j["masked"] = r.masked ? poolJson(r.maskedPool) : nlohmann::json(nullptr);
  j["all"] = r.masked ? poolJson(r.allPool) : nlohmann::json(nullptr);
  if (r.masked) j["masked"]["covers"] = "masked", j["all"]["covers"] = "all";
  j["result"] = verdicts[int(r.verdict)];
  j["heatmap"] = r.heatmap.empty() ? nlohmann::json(nullptr) : nlohmann::json(r.heatmap);
  return j;
}

std::string flipText(const FlipResult& r) {
  const FlipPool& p = r.pool;
  std::string thresholds = r.fail || r.warn ? "" : "; no threshold (reported only)";
  if (r.fail) thresholds += "; fail over " + flipFigure(*r.fail);
  if (r.warn) thresholds += "; warn over " + flipFigure(*r.warn);
  std::string out = std::string(r.verdict == Verdict::Pass ? "PASS " : r.verdict == Verdict::Warn ? "WARN " : "FAIL ") +
                    " " + r.target + std::string(26 - std::min<size_t>(26, r.target.size()), ' ') + " " +
                    (r.method == "hdr" ? "HDR-FLIP" : "LDR-FLIP") + " " + poolText(p, r.covers) + thresholds + "\n";
  if (r.method == "hdr")
    out += "      exposures " + flipFigure(r.exposures.start) + " to " + flipFigure(r.exposures.stop) + " in " +
           std::to_string(r.exposures.count) + " (ACES), " + flipFigure(r.ppd) + " pixels per degree\n";
  if (r.masked) {
    out += "      masked (deciding nothing): " + poolText(r.maskedPool, PixelSet::Masked) + "\n";
    out += "      all (deciding nothing):    " + poolText(r.allPool, PixelSet::All) + "\n";
  }
  return out;
}

}  // namespace gb
