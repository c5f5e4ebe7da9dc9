// The compare report: JSON (--json), the console summary, and the images (-o DIFFDIR): a heat map
// with its legend per compared group, the FLIP maps, the mask. FLIP's entries come from
// compare_flip.cpp.
#include <OpenImageIO/imagebuf.h>
#include <OpenImageIO/imagebufalgo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tuple>

#include "renderer/core/file_name.h"
#include "views/analysis/compare.h"
#include "views/analysis/visualize.h"

namespace gb {

namespace {

const char* verdictName(Verdict v) {
  static const char* n[] = {"pass", "warn", "fail"};
  return n[int(v)];
}

const char* resultName(int exitCode) {
  static const char* n[] = {"pass", "warn", "fail", "mismatch", "file error"};
  return exitCode >= 0 && exitCode <= 4 ? n[exitCode] : "?";
}

// JSON has no infinity: write it as the string "inf".
nlohmann::json jsonNumber(double v) { return std::isinf(v) ? nlohmann::json("inf") : nlohmann::json(v); }

nlohmann::json figuresJson(const GroupFigures& f) {
  nlohmann::json metrics = nlohmann::json::object();
  for (auto& [k, v] : f.metrics.items()) metrics[k] = v.is_number_float() ? jsonNumber(v.get<double>()) : v;
  return {{"covers", name(f.covers)},          {"pixels", f.pixels},         {"max_error", jsonNumber(f.maxError)},
          {"mean_error", jsonNumber(f.meanError)}, {"over_warn", f.overWarn},    {"over_fail", f.overFail},
          {"metrics", metrics}};
}

std::string fmt(double v) {
  char buf[32];
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::snprintf(buf, sizeof(buf), "%.4g", v);
  return buf;
}

// One set's figures on one line, ending with the pixels they cover.
std::string figuresText(MetricKind kind, const GroupFigures& f) {
  const nlohmann::json& j = f.metrics;
  std::string m;
  switch (kind) {
    case MetricKind::Colour:
      m = "max " + fmt(j["max_abs"]) + " mean " + fmt(j["mean_abs"]) + " rmse " + fmt(j["rmse"]) + " psnr " +
          fmt(j["psnr_db"]) + " dB";
      break;
    case MetricKind::Normal:
      m = "angle max " + fmt(j["max_degrees"]) + " mean " + fmt(j["mean_degrees"]) + " p99 " + fmt(j["p99_degrees"]) + " deg";
      break;
    case MetricKind::Depth:
    case MetricKind::Position:
      m = "abs max " + fmt(j["max_abs"]) + " mean " + fmt(j["mean_abs"]) + ", rel max " + fmt(j["max_rel"]) + " mean " +
          fmt(j["mean_rel"]);
      break;
    case MetricKind::Exact: m = std::to_string(j["differing_pixels"].get<uint64_t>()) + " differ"; break;
  }
  return m + " over " + std::to_string(f.pixels) + " px (" + name(f.covers) + ")";
}

double percentOf(uint64_t n, uint64_t of) { return 100.0 * double(n) / double(std::max<uint64_t>(of, 1)); }

}  // namespace

std::string errorUnit(const GroupResult& g) {
  switch (g.group.kind) {
    case MetricKind::Colour: return "|A-B|";
    case MetricKind::Normal: return "angle, degrees";
    case MetricKind::Depth: return "relative |A-B|";
    case MetricKind::Position: return "|A-B|, scene units";
    case MetricKind::Exact: return "|A-B|";
  }
  return "";
}

namespace {

// A map of `w` x `h` colours with a legend strip below: a colour bar from 0 to `top` and its labels.
Rgba8Image withLegend(uint32_t w, uint32_t h, const std::function<void(size_t, uint8_t*)>& pixel,
                      const std::function<void(double, uint8_t*)>& bar, const std::string& left,
                      const std::string& centre, const std::string& right, std::string& error) {
  const uint32_t width = std::max(w, kLegendMinWidth), height = h + kLegendHeight;
  Rgba8Image img{width, height, std::vector<uint8_t>(size_t(width) * height * 4, 0)};
  for (size_t i = 0; i < img.pixels.size(); i += 4) img.pixels[i] = img.pixels[i + 1] = img.pixels[i + 2] = 40, img.pixels[i + 3] = 255;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      uint8_t* p = &img.pixels[(size_t(y) * width + x) * 4];
      pixel(size_t(y) * w + x, p);
      p[3] = 255;
    }
  const uint32_t x0 = 8, x1 = std::min(width, kLegendMaxWidth) - 8;  // a wide map's legend stays readable at 1:1
  for (uint32_t y = h + 4; y < h + 14; ++y)
    for (uint32_t x = x0; x < x1; ++x) bar(double(x - x0) / double(x1 - 1 - x0), &img.pixels[(size_t(y) * width + x) * 4]);
  OIIO::ImageBuf buf(OIIO::ImageSpec(int(width), int(height), 4, OIIO::TypeDesc::UINT8), img.pixels.data());
  const float white[4] = {0.92f, 0.92f, 0.92f, 1.0f};
  const int baseline = int(h) + 29;
  using Align = OIIO::ImageBufAlgo::TextAlignX;
  for (auto [text, x, align] : {std::tuple{left, int(x0), Align::Left}, {centre, int(x0 + x1) / 2, Align::Center},
                                {right, int(x1), Align::Right}})
    if (!text.empty() && !OIIO::ImageBufAlgo::render_text(buf, x, baseline, text, 13, "DejaVuSans", white, align)) {
      error = "cannot draw a legend (" + buf.geterror() + "; the font DejaVuSans is in fonts-dejavu-core: make deps)";
      return {};
    }
  return img;
}

}  // namespace

nlohmann::json CompareReport::json() const {
  nlohmann::json groupsJson = nlohmann::json::array();
  for (const GroupResult& g : groups) {
    const Thresholds& t = g.thresholds;
    nlohmann::json j = {{"key", g.group.key}, {"target", g.target}, {"kind", name(g.group.kind)}};
    j.update(figuresJson(g.figures));
    j["thresholds"] = {{"fail", t.fail}, {"failpercent", t.failPercent}, {"hardfail", jsonNumber(t.hardFail)},
                       {"warn", t.warn}, {"warnpercent", t.warnPercent}};
    const GroupFigures *masked = g.figuresOver(PixelSet::Masked), *all = g.figuresOver(PixelSet::All);
    j["masked"] = masked ? figuresJson(*masked) : nlohmann::json(nullptr);
    j["all"] = all && all != &g.figures ? figuresJson(*all) : nlohmann::json(nullptr);
    j["result"] = verdictName(g.verdict);
    j["heatmap"] = g.heatmap.empty() ? nlohmann::json(nullptr) : nlohmann::json(g.heatmap);
    groupsJson.push_back(j);
  }
  nlohmann::json flipsJson = nlohmann::json::array();
  for (const FlipResult& f : flips) flipsJson.push_back(flipJson(f));
  nlohmann::json mism = nlohmann::json::array(), skip = nlohmann::json::array();
  for (auto& [t, why] : mismatches) mism.push_back({{"target", t}, {"reason", why}});
  for (auto& [t, why] : skipped) skip.push_back({{"target", t}, {"reason", why}});
  nlohmann::json maskJson = nullptr;
  if (!mask.empty())
    maskJson = {{"parts", mask.parts}, {"pixels", mask.count()}, {"of", uint64_t(mask.width) * mask.height},
                {"image", maskImage.empty() ? nlohmann::json(nullptr) : nlohmann::json(maskImage)}};
  // The JSON is an interface (docs/schemas/compare.schema.json): a change of shape bumps the version.
  return {{"format", "gblens-compare"}, {"version", 1},
          {"a", a},           {"b", b},
          {"result", resultName(exitCode)}, {"exit_code", exitCode},
          {"error", error.empty() ? nlohmann::json(nullptr) : nlohmann::json(error)},
          {"seconds", seconds},
          {"differences", differences},     {"only_in_a", onlyInA},
          {"only_in_b", onlyInB},           {"mismatches", mism},
          {"skipped", skip},                {"mask", maskJson},
          {"groups", groupsJson},           {"flip", flipsJson}};
}

std::string groupText(const GroupResult& g) {
  char line[640];
  const GroupFigures& f = g.figures;
  std::snprintf(line, sizeof(line), "%-5s %-26s %-8s %s; %.4g%% over fail %s, %.4g%% over warn %s\n",
                g.verdict == Verdict::Pass ? "PASS" : g.verdict == Verdict::Warn ? "WARN" : "FAIL", g.group.key.c_str(),
                name(g.group.kind), figuresText(g.group.kind, f).c_str(), percentOf(f.overFail, f.pixels),
                fmt(g.thresholds.fail).c_str(), percentOf(f.overWarn, f.pixels), fmt(g.thresholds.warn).c_str());
  std::string out = line;
  for (const GroupFigures& apart : g.apart) {
    std::snprintf(line, sizeof(line), "      %-8s %s; %llu over fail (deciding nothing)\n",
                  (std::string(name(apart.covers)) + ":").c_str(), figuresText(g.group.kind, apart).c_str(),
                  (unsigned long long)apart.overFail);
    out += line;
  }
  return out;
}

std::string CompareReport::text() const {
  std::string out = "gblens compare\n  A " + a + "\n  B " + b + "\n";
  if (!differences.empty()) {
    out += "manifest fields that differ:\n";
    for (const nlohmann::json& d : differences)
      out += "  " + d["name"].get<std::string>() + ": " + d["a"].dump() + " -> " + d["b"].dump() + "\n";
  }
  for (auto [side, list] : {std::pair{"A", &onlyInA}, {"B", &onlyInB}}) {
    if (list->empty()) continue;
    out += std::string("manifest fields only in ") + side + " (the other's source does not say them; deciding nothing):\n";
    for (const nlohmann::json& d : *list) out += "  " + d["name"].get<std::string>() + ": " + d["value"].dump() + "\n";
  }
  for (auto& [t, why] : mismatches) out += "MISMATCH " + t + ": " + why + "\n";
  for (auto& [t, why] : skipped) out += "skipped  " + t + ": " + why + "\n";
  char line[640];
  if (!mask.empty()) {
    std::string parts;
    for (const std::string& p : mask.parts) parts += (parts.empty() ? "" : ",") + p;
    const uint64_t n = mask.count(), of = uint64_t(mask.width) * mask.height;
    std::snprintf(line, sizeof(line), "mask %s: %llu of %llu px (%.4g%%) masked, reported apart%s%s\n", parts.c_str(),
                  (unsigned long long)n, (unsigned long long)of, percentOf(n, of), maskImage.empty() ? "" : "; ",
                  maskImage.c_str());
    out += line;
  }
  for (const GroupResult& g : groups) out += groupText(g);
  for (const FlipResult& f : flips) out += flipText(f);
  std::string verdict = resultName(exitCode);
  for (char& c : verdict) c = char(std::toupper(c));
  out += verdict + " (exit " + std::to_string(exitCode) + ")\n";
  return out;
}

Rgba8Image heatmapImage(const GroupResult& g, std::string& error) {
  // Linear from 0 (black) to the largest finite error (red); infinite errors (NaN against a number,
  // a position where one frame has no surface) white; pixels not compared (normals where neither
  // frame has a surface) black.
  double top = 0.0;
  bool infinite = false;
  for (float e : g.errors) {
    if (std::isfinite(e)) top = std::max(top, double(e));
    infinite |= std::isinf(e);
  }
  auto pixel = [&](size_t i, uint8_t* p) {
    const float e = g.errors[i];
    if (std::isnan(e)) p[0] = p[1] = p[2] = 0;
    else if (std::isfinite(e)) heatColor(top > 0.0 ? e / top * 1000.0 : 0.0, 1000.0, p);  // heatColor's max is >= 1
    else p[0] = p[1] = p[2] = 255;
  };
  auto bar = [&](double t, uint8_t* p) { heatColor(t * 1000.0, 1000.0, p); };
  const std::string centre = errorUnit(g) + (top > 0.0 ? ", black: equal" : ": no difference") + (infinite ? ", white: inf" : "");
  return withLegend(g.width, g.height, pixel, bar, "0", centre, fmt(top), error);
}

Rgba8Image flipMapImage(const FlipResult& r, std::string& error) {
  auto pixel = [&](size_t i, uint8_t* p) { magmaColor(r.errors[i], p); };
  auto bar = [](double t, uint8_t* p) { magmaColor(t, p); };
  return withLegend(r.width, r.height, pixel, bar, "0", r.method == "hdr" ? "HDR-FLIP" : "LDR-FLIP", "1", error);
}

std::string compareFileName(const std::string& key, const std::string& suffix) {
  // Target names are [a-z0-9_]; quantity names come from layouts: anything else could leave the folder
  // (safeFileName), or need quoting in the report's page and scripts (the character set).
  std::string why;
  const bool safe = safeFileName(key + suffix, why) &&
                    key.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_.-") ==
                        std::string::npos;
  return safe ? key + suffix : "";
}

bool writeCompareImages(CompareReport& report, const std::string& dir, std::string& error) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) {
    error = dir + ": cannot create (" + ec.message() + ")";
    return false;
  }
  // The names come from the captures' layouts: never a path out of DIR (x/../../escaped).
  auto write = [&](const std::string& key, const std::string& suffix, const Rgba8Image& img, std::string& recorded) {
    const std::string name = compareFileName(key, suffix);
    if (name.empty()) {
      error = "image of \"" + key.substr(0, 80) + "\": not a file name (use a-z, A-Z, 0-9, _, . and -)";
      return false;
    }
    const std::string file = (std::filesystem::path(dir) / name).string();
    if (img.pixels.empty() || !writePng(file, img, error)) return false;
    recorded = file;
    return true;
  };
  for (GroupResult& g : report.groups)
    if (!write(g.group.key, ".png", heatmapImage(g, error), g.heatmap)) return false;
  for (FlipResult& f : report.flips)
    if (!write("flip_" + f.target, ".png", flipMapImage(f, error), f.heatmap)) return false;
  if (!report.mask.empty() && !write("mask", ".png", maskImage(report.mask), report.maskImage)) return false;
  return true;
}

}  // namespace gb
