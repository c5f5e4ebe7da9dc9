// The pairs index page's thumbnails (report_internal.h): capture A's colour view box-filtered down and
// the worst group's heat map max-pooled down, so that one differing pixel still shows.
#include <algorithm>
#include <filesystem>

#include "views/analysis/visualize.h"
#include "views/capture/image_io.h"
#include "views/report/report_internal.h"

namespace gb {

namespace fs = std::filesystem;

namespace {

constexpr uint32_t kThumbWidth = 160;

// `img`'s top-left w x h reduced to at most kThumbWidth wide, the aspect kept (never enlarged). Each
// output pixel covers the source columns [x*w/tw, (x+1)*w/tw) and rows likewise (integer bounds, so
// a test can redo it exactly); `pool` averages (box filter) or takes each channel's maximum.
Rgba8Image reduce(const Rgba8Image& img, uint32_t w, uint32_t h, bool pool) {
  const uint32_t tw = std::min(w, kThumbWidth);
  const uint32_t th = std::max<uint32_t>(1, uint32_t((uint64_t(h) * tw + w / 2) / w));
  Rgba8Image out{tw, th, std::vector<uint8_t>(size_t(tw) * th * 4, 255)};
  for (uint32_t y = 0; y < th; ++y) {
    const uint32_t y0 = uint32_t(uint64_t(y) * h / th), y1 = std::max(y0 + 1, uint32_t(uint64_t(y + 1) * h / th));
    for (uint32_t x = 0; x < tw; ++x) {
      const uint32_t x0 = uint32_t(uint64_t(x) * w / tw), x1 = std::max(x0 + 1, uint32_t(uint64_t(x + 1) * w / tw));
      uint64_t sum[4] = {0, 0, 0, 0};
      uint8_t top[4] = {0, 0, 0, 0};
      for (uint32_t sy = y0; sy < y1; ++sy)
        for (uint32_t sx = x0; sx < x1; ++sx) {
          const uint8_t* p = &img.pixels[(size_t(sy) * img.width + sx) * 4];  // img.width: the row stride
          for (int c = 0; c < 4; ++c) sum[c] += p[c], top[c] = std::max(top[c], p[c]);
        }
      const uint64_t n = uint64_t(x1 - x0) * (y1 - y0);
      uint8_t* q = &out.pixels[(size_t(y) * tw + x) * 4];
      for (int c = 0; c < 4; ++c) q[c] = pool ? top[c] : uint8_t((sum[c] + n / 2) / n);
    }
  }
  return out;
}

// The view people look at first: `final` where the layout has it, else the first colour view.
int colourView(const std::vector<ViewDef>& views, const Layout& layout) {
  const int final = layout.findTarget("final");
  for (size_t i = 0; i < views.size(); ++i)
    if (final >= 0 && views[i].target == uint32_t(final)) return int(i);
  for (size_t i = 0; i < views.size(); ++i)
    if (views[i].visual == Visual::Color) return int(i);
  return -1;
}

}  // namespace

bool writeThumbnails(const Capture& a, const CompareReport& report, const std::string& dir, const std::string& prefix,
                     nlohmann::json& out, std::string& error) {
  out = {{"a", nullptr}, {"diff", nullptr}};
  const std::vector<ViewDef> views = layoutViews(a.frame.layout);
  if (const int v = colourView(views, a.frame.layout); v >= 0) {
    const Rgba8Image img = visualize(a.frame, views[size_t(v)], defaultSettings(views[size_t(v)]));
    if (!img.pixels.empty()) {
      if (!writePng((fs::path(dir) / "thumb_a.png").string(), reduce(img, img.width, img.height, false), error))
        return false;
      out["a"] = prefix + "thumb_a.png";
    }
  }
  // The worst group: the first failing one, else the first warning one, else the first.
  const GroupResult* worst = report.groups.empty() ? nullptr : &report.groups[0];
  for (Verdict v : {Verdict::Warn, Verdict::Fail})
    for (const GroupResult& g : report.groups)
      if (g.verdict == v) {
        worst = &g;
        break;
      }
  if (worst && worst->width > 0 && worst->height > 0 && !worst->errors.empty()) {
    const Rgba8Image map = heatmapImage(*worst, error);
    if (map.pixels.empty()) return false;
    // Only the map: heatmapImage adds a legend strip below it (and may be wider than the map).
    if (!writePng((fs::path(dir) / "thumb_diff.png").string(), reduce(map, worst->width, worst->height, true), error))
      return false;
    out["diff"] = prefix + "thumb_diff.png";
  }
  return true;
}

}  // namespace gb
