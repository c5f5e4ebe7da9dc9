// The view area: every shown view drawn through the app's callback (GPU mapping), labels,
// legends, the linked hover mark, and the mouse: click probes, wheel zooms, middle-drag pans,
// right-drag turns the camera.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "views/ui/texel_values.h"
#include "views/ui/view_input.h"
#include "views/ui/view_legends.h"
#include "views/ui/viewer_model.h"

namespace gb {

void setViews(ViewerModel& m, std::vector<ViewDef> views) {
  std::vector<ViewSettings> settings;
  for (const ViewDef& v : views) {
    int before = findView(m.views, v.name);
    settings.push_back(before >= 0 && m.views[size_t(before)].visual == v.visual ? m.settings[size_t(before)] : defaultSettings(v));
  }
  auto keep = [&](int index, int fallback) {
    int i = index >= 0 && size_t(index) < m.views.size() ? findView(views, m.views[size_t(index)].name) : -1;
    return i >= 0 ? i : std::min(fallback, int(views.size()) - 1);
  };
  m.primary = keep(m.primary, 0);
  m.secondary = keep(m.secondary, 1);
  m.edited = keep(m.edited, 0);
  m.views = std::move(views);
  m.settings = std::move(settings);
  const size_t n = m.views.size();
  m.ranges.assign(n, {});
  m.gpuSources.assign(n, ViewGpuSource{});
  m.unavailable.resize(n);
  m.differenceMax.resize(n, 0.0);
  m.flipPools.resize(n);
  m.hoverView.reset();
}

glm::uvec2 viewImageSize(const ViewerModel& m, int v) {
  if (v >= 0 && size_t(v) < m.views.size() && m.views[size_t(v)].sun) return m.shadowMapSize;
  if (m.reducedBy > 1) return m.fullSize;
  return {m.rendered.width, m.rendered.height};
}

std::vector<int> gridViews(const ViewerModel& m) {
  std::vector<int> out;
  for (size_t i = 0; i < m.views.size(); ++i)
    if (m.unavailable[i].empty()) out.push_back(int(i));
  return out;
}

std::vector<int> visibleViews(const ViewerModel& m) {
  if (m.views.empty()) return {};
  switch (m.layout) {
    case LayoutMode::Single: return {m.primary};
    case LayoutMode::SideBySide: return {m.primary, m.secondary};
    case LayoutMode::Grid: return gridViews(m);
  }
  return {};
}

// What a compare slot of view `view` shows in the compare mode: FLIP is of colour views (others
// show |A - B| instead, labelled so).
static FrameSide compareSide(const ViewerModel& m, int view) {
  switch (m.compareMode) {
    case CompareMode::Difference: return FrameSide::Difference;
    case CompareMode::Flip:
      return m.views[size_t(view)].visual == Visual::Color ? FrameSide::Flip : FrameSide::Difference;
    default: return m.compareSide;
  }
}

std::vector<ViewSlot> viewSlots(const ViewerModel& m, const Rect& area) {
  std::vector<int> views = visibleViews(m);
  if (views.empty()) return {};
  std::vector<ViewSlot> out;
  if (m.source == FrameSource::Compare && m.layout == LayoutMode::Single && m.compareMode == CompareMode::Row) {
    // A, B and |A - B| in a row (a column when the area is taller than wide).
    const double gap = 4.0;
    const bool row = area.w >= area.h;
    double len = std::floor(((row ? area.w : area.h) - 2 * gap) / 3);
    for (int i = 0; i < 3; ++i)
      out.push_back({views[0], FrameSide(i),
                     row ? Rect{area.x + i * (len + gap), area.y, len, area.h} : Rect{area.x, area.y + i * (len + gap), area.w, len}});
    return out;
  }
  const glm::uvec2 size = viewImageSize(m, views[0]);
  std::vector<Rect> rects = layoutViews(area, m.layout, views.size(), double(size.x) / double(std::max(size.y, 1u)));
  // Compare: every view in the same mode (the grid flips, swipes or differs as a whole).
  const bool compare = m.source == FrameSource::Compare;
  for (size_t i = 0; i < views.size() && i < rects.size(); ++i)
    out.push_back({views[i], compare ? compareSide(m, views[i]) : FrameSide::A, rects[i],
                   compare && m.compareMode == CompareMode::Swipe});
  return out;
}

bool applyViewKey(ViewerModel& m, int digit) {
  if (digit == 1) {
    m.layout = LayoutMode::Grid;
    return true;
  }
  for (size_t k = 0; k < m.views.size(); ++k) {
    const ViewDef& d = m.views[k];
    if (!d.key.empty() && d.key[0] - '0' == digit) {
      m.primary = m.edited = int(k);
      if (m.layout == LayoutMode::Grid) m.layout = LayoutMode::Single;
      return true;
    }
  }
  return false;
}

static ImU32 panelColour(float r, float g, float b, float a = 1.0f) { return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, a)); }

// Outline of one texel (or a crosshair where a texel is smaller than a few pixels).
static void markTexel(ImDrawList* dl, const Placement& pl, glm::ivec2 t, ImU32 colour, const Rect& clip) {
  glm::dvec2 a = windowAt(pl, glm::dvec2(t)), b = windowAt(pl, glm::dvec2(t) + 1.0);
  dl->PushClipRect(ImVec2(float(clip.x), float(clip.y)), ImVec2(float(clip.x + clip.w), float(clip.y + clip.h)), true);
  if (pl.scale >= 4.0) {
    dl->AddRect(ImVec2(float(a.x) - 1, float(a.y) - 1), ImVec2(float(b.x) + 1, float(b.y) + 1), panelColour(0, 0, 0), 0, 0, 3.0f);
    dl->AddRect(ImVec2(float(a.x) - 1, float(a.y) - 1), ImVec2(float(b.x) + 1, float(b.y) + 1), colour, 0, 0, 1.5f);
  } else {
    glm::dvec2 c = (a + b) * 0.5;
    const float gap = 3.0f, len = 9.0f;
    for (int s : {-1, 1}) {
      ImVec2 h0(float(c.x) + s * gap, float(c.y)), h1(float(c.x) + s * (gap + len), float(c.y));
      ImVec2 v0(float(c.x), float(c.y) + s * gap), v1(float(c.x), float(c.y) + s * (gap + len));
      dl->AddLine(h0, h1, panelColour(0, 0, 0), 3.0f);
      dl->AddLine(v0, v1, panelColour(0, 0, 0), 3.0f);
      dl->AddLine(h0, h1, colour, 1.5f);
      dl->AddLine(v0, v1, colour, 1.5f);
    }
  }
  dl->PopClipRect();
}

// Marks use the hover of the previous interface frame (this frame's is found while the views are
// laid out; a change asks for another frame).
struct HoverMarks {
  std::optional<glm::ivec2> texel, shadowTexel;
};

// One view slot of this interface frame, and what drawing it needs from around it.
namespace {
struct SlotDraw {
  int view = 0;
  Rect rect;
  int index = 0;                 // the ImGui id of the slot's button
  FrameSide side = FrameSide::A;
  bool split = false;            // A | B split at ViewerModel::splitAt
  bool showKey = false;          // the grid labels views with their keys
  HoverMarks hover;
  ViewDrawCallback callback = nullptr;  // draws a view through the GPU mapping, in ImGui's order
  std::vector<ViewDraw>* draws = nullptr;  // the callback's data: one entry per drawn view
};
}  // namespace

// The view's GPU draw (mapping parameters in framebuffer pixels), queued as an ImDrawList
// callback clipped to the slot.
static void queueViewDraw(ViewerModel& m, const SlotDraw& v, const Placement& pl, const ResolvedRange& range) {
  const ViewDef& def = m.views[size_t(v.view)];
  const ImGuiIO& io = ImGui::GetIO();
  const Rect& r = v.rect;
  std::optional<glm::ivec2> mark = m.shadowMark;
  ViewDraw vd;
  vd.view = v.view;
  vd.side = v.side;
  Placement fb = pl;  // framebuffer pixels (the same as window pixels unless the display scales)
  fb.originX *= io.DisplayFramebufferScale.x;
  fb.originY *= io.DisplayFramebufferScale.y;
  fb.scale *= io.DisplayFramebufferScale.x;
  // A reduced frame covers the full frame's placement: its texels are fullSize / rendered larger.
  if (m.reducedBy > 1 && !def.sun && m.rendered.width > 0)
    fb.scale *= double(m.fullSize.x) / double(m.rendered.width);
  if (m.source != FrameSource::Live) mark.reset();  // marks need the live frame's matrices on the GPU
  vd.params = viewParams(def, m.settings[size_t(v.view)], m.gpuSources[size_t(v.view)], range, fb, m.grid, mark, m.shadowMapSize);
  if (v.side == FrameSide::Difference) {
    // |A - B| over the selected channels as a heat map from 0 to the largest difference.
    vd.params.mode.x = gpu::kViewMapDiff;
    vd.params.mode.z &= gpu::kViewFlagGrid;
    vd.params.range = glm::vec4(0.0f, float(std::max(m.differenceMax[size_t(v.view)], 1e-30)), vd.params.range.z, 1.0f);
    if (def.visual == Visual::Normal || def.visual == Visual::Color || def.visual == Visual::Position) vd.params.mode.y &= 0x7u;
  } else if (v.side == FrameSide::Flip) {
    // The FLIP map: magma colours (linear, decoded like a capture's view), drawn as they are.
    ViewDef map;
    map.visual = Visual::Color;
    map.components = 3;
    map.negativeSuspicious = false;
    vd.params = viewParams(map, defaultSettings(map), ViewGpuSource{}, ResolvedRange{}, fb, m.grid, std::nullopt, m.shadowMapSize);
  }
  if (v.split) vd.splitX = (r.x + r.w * m.splitAt) * io.DisplayFramebufferScale.x;
  vd.rect = {r.x * io.DisplayFramebufferScale.x, r.y * io.DisplayFramebufferScale.y, r.w * io.DisplayFramebufferScale.x,
             r.h * io.DisplayFramebufferScale.y};
  v.draws->push_back(vd);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(ImVec2(float(r.x), float(r.y)), ImVec2(float(r.x + r.w), float(r.y + r.h)), true);
  dl->AddCallback(v.callback, reinterpret_cast<void*>(intptr_t(v.draws->size() - 1)));
  dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
  dl->PopClipRect();
}

bool zoomToShadowMarks(ViewerModel& m) {
  if (!m.shadowMark || !m.shadowMarks || !m.shadowMarks->box) return false;
  const RegionRect& b = *m.shadowMarks->box;
  m.transform = framing(b.x, b.y, b.width, b.height, m.rendered.width, m.rendered.height);
  m.uiChanged = true;
  return true;
}

// The pixels a clicked shadow-map texel marks, seen at any zoom: their box, never smaller than
// 12 window pixels; in a capture (the live frame's shader marks the pixels themselves) each pixel,
// never smaller than 2.
static void drawShadowMarks(const ViewerModel& m, ImDrawList* dl, const Placement& pl, const Rect& r) {
  const ShadowMarks& s = *m.shadowMarks;
  const RegionRect& g = *s.box;
  const ImU32 magenta = panelColour(1, 0, 1);
  dl->PushClipRect(ImVec2(float(r.x), float(r.y)), ImVec2(float(r.x + r.w), float(r.y + r.h)), true);
  if (m.source != FrameSource::Live) {
    const float size = float(std::max(pl.scale, 2.0));
    for (const glm::ivec2& p : s.some) {
      const glm::dvec2 c = windowAt(pl, glm::dvec2(p) + 0.5);
      dl->AddRectFilled(ImVec2(float(c.x) - size / 2, float(c.y) - size / 2), ImVec2(float(c.x) + size / 2, float(c.y) + size / 2), magenta);
    }
  }
  glm::dvec2 a = windowAt(pl, glm::dvec2(g.x, g.y)), b = windowAt(pl, glm::dvec2(g.x + g.width, g.y + g.height));
  const glm::dvec2 centre = (a + b) * 0.5, half = glm::max((b - a) * 0.5, glm::dvec2(6.0)) + 3.0;
  a = centre - half, b = centre + half;
  dl->AddRect(ImVec2(float(a.x), float(a.y)), ImVec2(float(b.x), float(b.y)), panelColour(0, 0, 0), 0, 0, 3.0f);
  dl->AddRect(ImVec2(float(a.x), float(a.y)), ImVec2(float(b.x), float(b.y)), magenta, 0, 0, 1.5f);
  dl->PopClipRect();
}

// Marks: the hovered pixel on every screen view; on the shadow map, the texel the hovered (or
// probed) pixel's lookup reads, and the clicked texel.
static void drawMarks(const ViewerModel& m, const SlotDraw& v, const Placement& pl) {
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const Rect& r = v.rect;
  if (!m.views[size_t(v.view)].sun) {
    if (v.hover.texel) markTexel(dl, pl, *v.hover.texel, panelColour(1, 1, 1), r);
    if (m.probePixel) markTexel(dl, pl, *m.probePixel, panelColour(0.2f, 1.0f, 0.4f), r);
    if (m.shadowMark && m.shadowMarks && m.shadowMarks->box) drawShadowMarks(m, dl, pl, r);
    if (m.region) {  // the region statistics' rectangle, in every screen view
      const RegionRect& g = *m.region;
      glm::dvec2 a = windowAt(pl, glm::dvec2(g.x, g.y)), b = windowAt(pl, glm::dvec2(g.x + g.width, g.y + g.height));
      dl->PushClipRect(ImVec2(float(r.x), float(r.y)), ImVec2(float(r.x + r.w), float(r.y + r.h)), true);
      dl->AddRect(ImVec2(float(a.x), float(a.y)), ImVec2(float(b.x), float(b.y)), panelColour(0, 0, 0), 0, 0, 3.0f);
      dl->AddRect(ImVec2(float(a.x), float(a.y)), ImVec2(float(b.x), float(b.y)), panelColour(1.0f, 0.8f, 0.1f), 0, 0, 1.5f);
      dl->PopClipRect();
    }
  } else {
    if (v.hover.shadowTexel) markTexel(dl, pl, *v.hover.shadowTexel, panelColour(1, 1, 1), r);
    if (m.shadowTexelOfProbe) markTexel(dl, pl, *m.shadowTexelOfProbe, panelColour(0.2f, 1.0f, 0.4f), r);
    if (m.shadowMark) markTexel(dl, pl, *m.shadowMark, panelColour(1, 0, 1), r);
  }
}

// The second label line: the largest difference, the automatic range, NaN/Inf counts.
static std::string rangeLine(const ViewerModel& m, const SlotDraw& v, const ResolvedRange& range) {
  std::string line;
  char buf[128];
  if (v.side == FrameSide::Flip) {
    const FlipPool& p = *m.flipPools[size_t(v.view)];
    std::snprintf(buf, sizeof buf, "mean %.4g, weighted median %.4g, max %.4g", p.mean, p.weightedMedian, p.max);
    line = buf;
  } else if (v.side == FrameSide::Difference) {
    double worst = m.differenceMax[size_t(v.view)];
    if (worst > 0.0)
      std::snprintf(buf, sizeof buf, "largest |A - B| %.6g", worst);
    else
      std::snprintf(buf, sizeof buf, "identical (every texel, selected channels)");
    line = buf;
  } else if (m.settings[size_t(v.view)].autoRange) {
    if (range.fromData)
      std::snprintf(buf, sizeof buf, "auto %.6g .. %.6g", range.black, range.white);
    else if (m.ranges[size_t(v.view)].empty())  // not measured yet: its texels are being decoded
      std::snprintf(buf, sizeof buf, "auto: decoding...");
    else
      std::snprintf(buf, sizeof buf, "auto: no valid texels");
    line = buf;
  }
  if (range.stats.nan || range.stats.inf) {
    std::snprintf(buf, sizeof buf, "%s%llu NaN, %llu Inf", line.empty() ? "" : "  ", (unsigned long long)range.stats.nan,
                  (unsigned long long)range.stats.inf);
    line += buf;
  }
  return line;
}

// The last part of a capture's path (labels stay short).
static std::string shortName(const std::string& dir) {
  std::string d = dir;
  while (d.size() > 1 && d.back() == '/') d.pop_back();
  const size_t slash = d.find_last_of('/');
  return slash == std::string::npos ? d : d.substr(slash + 1);
}

// A compare slot's side: "A  capA", "B  capB", "A | B", "|A-B|", "FLIP".
static std::string compareLabel(const ViewerModel& m, const SlotDraw& v) {
  if (v.split) return "A | B";
  switch (v.side) {
    case FrameSide::A: return "A  " + shortName(m.captureA);
    case FrameSide::B: return "B  " + shortName(m.captureB);
    case FrameSide::Difference:
      return m.compareMode == CompareMode::Flip && !v.showKey ? "|A-B| (FLIP is of colour views)" : "|A-B|";
    case FrameSide::Flip: return "FLIP";
  }
  return "";
}

// Which legend a slot shows: beside the image, in a strip below it (never over the picture), where
// the slot is large enough for one (grid cells too, from 200 x 200 px).
enum class LegendKind { None, Flip, Difference, Count, Words, Ramp, Classes };
static LegendKind legendOf(const ViewerModel& m, int view, FrameSide side, const Rect& r) {
  if (r.w <= 200 || r.h <= 200) return LegendKind::None;
  const ViewDef& def = m.views[size_t(view)];
  if (side == FrameSide::Flip) return LegendKind::Flip;
  if (side == FrameSide::Difference) return LegendKind::Difference;
  if (def.visual == Visual::Count) return LegendKind::Count;
  if (m.referenceError.legends.count(def.name)) return LegendKind::Words;
  if (def.visual == Visual::Id && m.classNames.count(def.name)) return LegendKind::Classes;
  const ViewMapping mapping = viewMapping(def, m.settings[size_t(view)]);
  if (mapping.mapping == gpu::kViewMapDepth || (mapping.mapping == gpu::kViewMapGrey && (mapping.flags & gpu::kViewFlagFalseColor)))
    return LegendKind::Ramp;
  return LegendKind::None;
}
static std::string wordsOf(const ViewerModel& m, int view) {
  const ViewDef& def = m.views[size_t(view)];
  return def.name + ": " + m.referenceError.legends.at(def.name);
}
constexpr double kLegendStrip = 48.0;  // a ramp's box: its unit line, the bar and the tick labels
static double stripHeight(const ViewerModel& m, int view, FrameSide side, const Rect& r) {
  const LegendKind k = legendOf(m, view, side, r);
  if (k == LegendKind::None) return 0.0;
  if (k != LegendKind::Words) return kLegendStrip;
  return double(ImGui::CalcTextSize(wordsOf(m, view).c_str(), nullptr, false, float(std::min(r.w - 24, 420.0))).y) + 20.0;
}

Rect imageRectOf(const ViewerModel& m, const ViewSlot& s) {
  Rect r = s.rect;
  r.h = std::max(1.0, r.h - stripHeight(m, s.view, s.side, s.rect));
  return r;
}

// The legend in the strip between the image's rectangle `ir` and the slot's bottom.
static void drawLegend(const ViewerModel& m, int view, FrameSide side, const Rect& r, const Rect& ir, const ResolvedRange& range) {
  const LegendKind k = legendOf(m, view, side, r);
  if (k == LegendKind::None) return;
  const ViewDef& def = m.views[size_t(view)];
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const float top = float(ir.y + ir.h), width = float(std::min(r.w - 24, 240.0));
  dl->AddRectFilled(ImVec2(float(r.x), top), ImVec2(float(r.x + r.w), float(r.y + r.h)), panelColour(0.08f, 0.08f, 0.08f));
  const ImVec2 bar(float(r.x) + 12, top + 20);  // the bar's top-left: its unit line above, ticks below
  switch (k) {
    case LegendKind::Flip: magmaLegend(dl, bar, width); break;
    case LegendKind::Difference:
      heatLegend(dl, bar, width, float(m.differenceMax[size_t(view)]), "|A - B|, max over the selected channels");
      break;
    case LegendKind::Count: heatLegend(dl, bar, width, range.white, viewUnit(def, m.stats.method).c_str()); break;
    case LegendKind::Words: textLegend(dl, r, float(std::min(r.w - 24, 420.0)), wordsOf(m, view)); break;
    case LegendKind::Classes: classLegend(dl, bar, float(r.w - 24), def.name, m.classNames.at(def.name)); break;
    case LegendKind::Ramp:
      rampLegend(dl, bar, width, viewMapping(def, m.settings[size_t(view)]), range, def.unit.empty() ? def.name : def.unit);
      break;
    case LegendKind::None: break;
  }
}

// The label box (side, key, name; the range line), the heat legend and the split handle.
static void drawLabels(const ViewerModel& m, const SlotDraw& v, const ResolvedRange& range) {
  const ViewDef& def = m.views[size_t(v.view)];
  ImDrawList* dl = ImGui::GetWindowDrawList();
  const Rect& r = v.rect;
  char label[400];
  const std::string prefix = m.source == FrameSource::Compare ? compareLabel(m, v) + "  " : "";
  std::snprintf(label, sizeof label, "%s%s%s%s", prefix.c_str(), v.showKey && !def.key.empty() ? def.key.c_str() : "",
                v.showKey && !def.key.empty() ? "  " : "", def.name.c_str());
  std::string line2 = rangeLine(m, v, range);
  ImVec2 ls = ImGui::CalcTextSize(label);
  float boxW = std::max(ls.x, ImGui::CalcTextSize(line2.c_str()).x) + 10;
  float boxH = ls.y * (line2.empty() ? 1 : 2) + 6;
  // Compare: the box is coloured by the side shown (A blue, B orange), so a flip is seen at once.
  const ImU32 box = m.source != FrameSource::Compare || v.split ? panelColour(0, 0, 0, 0.6f)
                    : v.side == FrameSide::A                    ? panelColour(0.1f, 0.25f, 0.6f, 0.85f)
                    : v.side == FrameSide::B                    ? panelColour(0.6f, 0.3f, 0.05f, 0.85f)
                                                                : panelColour(0, 0, 0, 0.6f);
  dl->AddRectFilled(ImVec2(float(r.x), float(r.y)), ImVec2(float(r.x) + boxW, float(r.y) + boxH), box);
  dl->AddText(ImVec2(float(r.x) + 5, float(r.y) + 3), panelColour(1, 1, 1), label);
  if (!line2.empty())
    dl->AddText(ImVec2(float(r.x) + 5, float(r.y) + 3 + ls.y),
                range.stats.nan || range.stats.inf ? panelColour(1, 0.4f, 1) : panelColour(0.8f, 0.8f, 0.8f), line2.c_str());
  if (v.split) {  // the split line, its handle and which side is which (A blue, B orange, as the labels)
    float x = float(r.x + r.w * m.splitAt);
    dl->AddLine(ImVec2(x, float(r.y)), ImVec2(x, float(r.y + r.h)), panelColour(1, 1, 1), 2.0f);
    dl->AddCircleFilled(ImVec2(x, float(r.y + r.h * 0.5)), 6.0f, panelColour(1, 1, 1));
    const float y = float(r.y + boxH + 4), h = ImGui::GetFontSize() + 4;
    const float wa = ImGui::CalcTextSize("A").x + 8, wb = ImGui::CalcTextSize("B").x + 8;
    dl->AddRectFilled(ImVec2(x - 4 - wa, y), ImVec2(x - 4, y + h), panelColour(0.1f, 0.25f, 0.6f, 0.9f));
    dl->AddText(ImVec2(x - wa, y + 2), panelColour(1, 1, 1), "A");
    dl->AddRectFilled(ImVec2(x + 4, y), ImVec2(x + 4 + wb, y + h), panelColour(0.6f, 0.3f, 0.05f, 0.9f));
    dl->AddText(ImVec2(x + 8, y + 2), panelColour(1, 1, 1), "B");
  }
}

// One view slot: its button (for the mouse), the view or why it is unavailable, marks, labels.
static void drawOneView(ViewerModel& m, const SlotDraw& v) {
  const ViewDef& def = m.views[size_t(v.view)];
  const Rect& r = v.rect;
  const glm::uvec2 size = viewImageSize(m, v.view);

  ImGui::SetCursorScreenPos(ImVec2(float(r.x), float(r.y)));
  ImGui::PushID(v.index);
  ImGui::InvisibleButton("view", ImVec2(float(std::max(r.w, 1.0)), float(std::max(r.h, 1.0))),
                         ImGuiButtonFlags_MouseButtonLeft | ImGuiButtonFlags_MouseButtonRight |
                             ImGuiButtonFlags_MouseButtonMiddle);
  const bool hovered = ImGui::IsItemHovered(), active = ImGui::IsItemActive();
  ImGui::PopID();

  // The image in the slot above its legend strip: placement, drawing, marks and the mouse use it.
  SlotDraw vi = v;
  vi.rect = imageRectOf(m, {v.view, v.side, v.rect, v.split});
  Placement pl = placeImage(vi.rect, size.x, size.y, m.transform);
  if (v.index == 0) m.texelScale = pl.scale;
  std::string why = m.unavailable[size_t(v.view)];
  if (why.empty() && v.side == FrameSide::Flip && !m.flipPools[size_t(v.view)]) why = m.flipStatus;
  if (!why.empty()) {
    ImDrawList* dl = ImGui::GetWindowDrawList();
    dl->AddRectFilled(ImVec2(float(r.x), float(r.y)), ImVec2(float(r.x + r.w), float(r.y + r.h)), panelColour(0.12f, 0.12f, 0.12f));
    // Wrapped: the reason must be readable in a grid tile too.
    dl->AddText(ImGui::GetFont(), ImGui::GetFontSize(), ImVec2(float(r.x) + 8, float(r.y + r.h * 0.4)),
                panelColour(0.8f, 0.8f, 0.8f), why.c_str(), nullptr, float(r.w) - 16.0f);
  } else {
    ResolvedRange range = resolveRange(def, m.settings[size_t(v.view)], &m.ranges[size_t(v.view)]);
    queueViewDraw(m, vi, pl, range);
    // A split slot shows A and B in one rectangle: values would not say which side they are.
    if (!v.split) drawTexelValues(m, v.view, v.side, vi.rect, pl, range);
    drawMarks(m, vi, pl);
    drawLabels(m, vi, range);
    drawLegend(m, v.view, v.side, r, vi.rect, range);
  }
  if (hovered || active) handleViewMouse(m, {v.view, vi.rect, v.split}, pl, hovered, active);
}

void drawViewArea(ViewerModel& m, const Rect& area, ViewDrawCallback callback, std::vector<ViewDraw>& draws) {
  ImGui::SetNextWindowPos(ImVec2(float(area.x), float(area.y)));
  ImGui::SetNextWindowSize(ImVec2(float(area.w), float(area.h)));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(0, 0));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowBorderSize, 0.0f);
  ImGui::Begin("##views", nullptr,
               ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoBackground |
                   ImGuiWindowFlags_NoBringToFrontOnFocus | ImGuiWindowFlags_NoScrollWithMouse |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoFocusOnAppearing);
  ImGui::PopStyleVar(2);
  std::optional<glm::ivec2> hoverBefore = m.hover, shadowBefore = m.hoverShadowTexel;
  m.hover.reset();
  m.hoverView.reset();
  m.hoverShadowTexel.reset();
  m.texelValuesDrawn.clear();
  std::vector<ViewSlot> slots = viewSlots(m, area);
  for (size_t i = 0; i < slots.size(); ++i)
    drawOneView(m, {.view = slots[i].view,
                    .rect = slots[i].rect,
                    .index = int(i),
                    .side = slots[i].side,
                    .split = slots[i].split,
                    .showKey = m.layout == LayoutMode::Grid,
                    .hover = {hoverBefore, shadowBefore},
                    .callback = callback,
                    .draws = &draws});
  if (m.hover != hoverBefore || m.hoverShadowTexel != shadowBefore) m.uiChanged = true;
  ImGui::End();
}

}  // namespace gb
