// The compare report: JSON (--json), the console summary, and heat-map PNGs (-o DIFFDIR); FLIP's
// entries come from compare_flip.cpp.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>

#include "renderer/core/file_name.h"
#include "views/analysis/compare.h"
#include "views/analysis/visualize.h"
#include "views/capture/image_io.h"

namespace gb {

static const char* verdictName(Verdict v) {
  static const char* n[] = {"pass", "warn", "fail"};
  return n[int(v)];
}

static const char* resultName(int exitCode) {
  static const char* n[] = {"pass", "warn", "fail", "mismatch", "file error"};
  return exitCode >= 0 && exitCode <= 4 ? n[exitCode] : "?";
}

// JSON has no infinity: write it as the string "inf".
static nlohmann::json number(double v) { return std::isinf(v) ? nlohmann::json("inf") : nlohmann::json(v); }

nlohmann::json CompareReport::json() const {
  nlohmann::json groupsJson = nlohmann::json::array();
  for (const GroupResult& g : groups) {
    nlohmann::json metrics = nlohmann::json::object();
    for (auto& [k, v] : g.metrics.items()) metrics[k] = v.is_number_float() ? number(v.get<double>()) : v;
    const Thresholds& t = g.thresholds;
    groupsJson.push_back({{"key", g.group.key},
                          {"target", g.target},
                          {"kind", name(g.group.kind)},
                          {"pixels", g.pixels},
                          {"max_error", number(g.maxError)},
                          {"mean_error", number(g.meanError)},
                          {"over_warn", g.overWarn},
                          {"over_fail", g.overFail},
                          {"thresholds",
                           {{"fail", t.fail}, {"failpercent", t.failPercent}, {"hardfail", number(t.hardFail)},
                            {"warn", t.warn}, {"warnpercent", t.warnPercent}}},
                          {"metrics", metrics},
                          {"masked_pixels", g.masked ? nlohmann::json(g.maskedPixels) : nlohmann::json(nullptr)},
                          {"masked_over_fail", g.masked ? nlohmann::json(g.maskedOverFail) : nlohmann::json(nullptr)},
                          {"result", verdictName(g.verdict)},
                          {"heatmap", g.heatmap.empty() ? nlohmann::json(nullptr) : nlohmann::json(g.heatmap)}});
  }
  nlohmann::json flipsJson = nlohmann::json::array();
  for (const FlipResult& f : flips) flipsJson.push_back(flipJson(f));
  nlohmann::json mism = nlohmann::json::array(), skip = nlohmann::json::array();
  for (auto& [t, why] : mismatches) mism.push_back({{"target", t}, {"reason", why}});
  for (auto& [t, why] : skipped) skip.push_back({{"target", t}, {"reason", why}});
  return {{"a", a},           {"b", b},
          {"result", resultName(exitCode)}, {"exit_code", exitCode},
          {"differences", differences},     {"mismatches", mism},
          {"skipped", skip},                {"groups", groupsJson},
          {"flip", flipsJson}};
}

static std::string fmt(double v) {
  char buf[32];
  if (std::isinf(v)) return "inf";
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

std::string CompareReport::text() const {
  std::string out = "gblens compare\n  A " + a + "\n  B " + b + "\n";
  if (!differences.empty()) {
    out += "manifest fields that differ:\n";
    for (const nlohmann::json& d : differences)
      out += "  " + d["name"].get<std::string>() + ": " + d["a"].dump() + " -> " + d["b"].dump() + "\n";
  }
  for (auto& [t, why] : mismatches) out += "MISMATCH " + t + ": " + why + "\n";
  for (auto& [t, why] : skipped) out += "skipped  " + t + ": " + why + "\n";
  char line[512];
  for (const GroupResult& g : groups) {
    std::string m;
    const nlohmann::json& j = g.metrics;
    switch (g.group.kind) {
      case MetricKind::Colour:
        m = "max " + fmt(j["max_abs"]) + " mean " + fmt(j["mean_abs"]) + " rmse " + fmt(j["rmse"]) + " psnr " +
            fmt(j["psnr_db"]) + " dB";
        break;
      case MetricKind::Normal:
        m = "angle max " + fmt(j["max_degrees"]) + " mean " + fmt(j["mean_degrees"]) + " p99 " + fmt(j["p99_degrees"]) +
            " deg";
        break;
      case MetricKind::Depth:
      case MetricKind::Position:
        m = "abs max " + fmt(j["max_abs"]) + " mean " + fmt(j["mean_abs"]) + ", rel max " + fmt(j["max_rel"]) +
            " mean " + fmt(j["mean_rel"]);
        break;
      case MetricKind::Exact: m = std::to_string(j["differing_pixels"].get<uint64_t>()) + " pixels differ"; break;
    }
    std::snprintf(line, sizeof(line), "%-5s %-26s %-8s %s; %.4g%% over fail %s, %.4g%% over warn %s\n",
                  g.verdict == Verdict::Pass ? "PASS" : g.verdict == Verdict::Warn ? "WARN" : "FAIL",
                  g.group.key.c_str(), name(g.group.kind), m.c_str(), 100.0 * double(g.overFail) / double(std::max<uint64_t>(g.pixels, 1)),
                  fmt(g.thresholds.fail).c_str(), 100.0 * double(g.overWarn) / double(std::max<uint64_t>(g.pixels, 1)),
                  fmt(g.thresholds.warn).c_str());
    out += line;
    if (g.masked && g.maskedPixels) {
      std::snprintf(line, sizeof(line), "      masked apart: %llu pixels, %llu over fail, max %s\n",
                    (unsigned long long)g.maskedPixels, (unsigned long long)g.maskedOverFail, fmt(g.maskedMaxError).c_str());
      out += line;
    }
  }
  for (const FlipResult& f : flips) out += flipText(f);
  std::string verdict = resultName(exitCode);
  for (char& c : verdict) c = char(std::toupper(c));
  out += verdict + " (exit " + std::to_string(exitCode) + ")\n";
  return out;
}

bool writeHeatmaps(CompareReport& report, const std::string& dir, std::string& error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    error = dir + ": cannot create (" + ec.message() + ")";
    return false;
  }
  for (GroupResult& g : report.groups) {
    if (!(g.maxError > 0.0)) continue;
    // Linear from 0 (black) to the largest finite error (red); infinite errors (NaN against a
    // number, a position where one frame has no surface) are drawn white; pixels not compared
    // (normals where neither frame has a surface) black.
    double top = 0.0;
    for (float e : g.errors)
      if (std::isfinite(e)) top = std::max(top, double(e));
    Rgba8Image img{g.width, g.height, std::vector<uint8_t>(size_t(g.width) * g.height * 4, 255)};
    for (size_t i = 0; i < g.errors.size(); ++i) {
      uint8_t* p = &img.pixels[i * 4];
      if (std::isnan(g.errors[i]))
        p[0] = p[1] = p[2] = 0;
      else if (std::isfinite(g.errors[i]))
        heatColor(top > 0.0 ? g.errors[i] / top * 1000.0 : 0.0, 1000.0, p);  // heatColor's max is >= 1
      else
        p[0] = p[1] = p[2] = 255;
    }
    // The name comes from the captures' layouts: never a path out of DIR (x/../../escaped).
    std::string why;
    if (!safeFileName(g.group.key + ".png", why)) {
      error = "heat map of \"" + g.group.key.substr(0, 80) + "\": not a file name (" + why + ")";
      return false;
    }
    std::string file = (std::filesystem::path(dir) / (g.group.key + ".png")).string();
    if (!writePng(file, img, error)) return false;
    g.heatmap = file;
  }
  for (FlipResult& f : report.flips)
    if (!writeFlipMap(f, dir, error)) return false;
  return true;
}

}  // namespace gb
