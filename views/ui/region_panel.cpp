// The Region panel: statistics of the rectangle selected with ctrl + left drag (the numbers of
// `gblens stats`, views/analysis/region_stats.h), a histogram of the chosen series, and "auto range
// from this region" for the view being edited (a highlight no longer decides the whole range).
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "views/ui/viewer_model.h"

namespace gb {

namespace {

std::string seriesLabel(const SeriesStats& s) {
  return s.target + " " + s.series + (s.surfacesOnly ? " (surfaces)" : "");
}

void histogram(const SeriesStats& s) {
  if (s.histogram.empty()) return;
  std::vector<float> bins(s.histogram.begin(), s.histogram.end());
  const float top = *std::max_element(bins.begin(), bins.end());
  char overlay[96];
  std::snprintf(overlay, sizeof overlay, "%.5g .. %.5g", s.min, s.max);
  ImGui::PlotHistogram("##region histogram", bins.data(), int(bins.size()), 0, overlay, 0.0f, top * 1.05f,
                       ImVec2(ImGui::GetContentRegionAvail().x, 80.0f));
  if (!s.ids.empty()) {
    std::string ids = "ids:";
    int shown = 0;
    for (const auto& [id, n] : s.ids) {
      if (++shown > 12) {
        ids += " ...";
        break;
      }
      ids += " " + std::to_string(id) + "x" + std::to_string(n);
    }
    ImGui::TextWrapped("%s", ids.c_str());
  }
}

// The view's decoded components in the region: p1 of the lowest to p99 of the highest selected one.
void autoRangeButton(ViewerModel& m) {
  if (m.views.empty()) return;
  const ViewDef& d = m.views[size_t(m.edited)];
  ViewSettings& s = m.settings[size_t(m.edited)];
  if (!m.regionStats || d.visual == Visual::Id || d.visual == Visual::Stencil) return;
  const std::string& target = m.frameLayout.targets[d.target].name;
  double lo = 0.0, hi = 0.0;
  bool any = false;
  const uint32_t mask = viewMapping(d, s).mask;
  for (int c = 0; c < int(d.components); ++c) {
    if (!(mask & (1u << c))) continue;
    const SeriesStats* st = m.regionStats->quantity(target, componentLabel(d, c));
    if (!st || st->count == 0) continue;
    lo = any ? std::min(lo, st->p1) : st->p1;
    hi = any ? std::max(hi, st->p99) : st->p99;
    any = true;
  }
  if (!any) {
    ImGui::TextDisabled("auto range: no values of %s in the region", d.name.c_str());
    return;
  }
  char label[128];
  std::snprintf(label, sizeof label, "Auto range from this region (%s: %.4g .. %.4g)", d.name.c_str(), lo, hi);
  if (ImGui::Button(label)) {
    s.autoRange = false;
    s.black = float(lo);
    s.white = float(hi > lo ? hi : lo + 1e-6);
    m.uiChanged = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("black point: 1st percentile, white point: 99th, over the view's selected channels");
}

}  // namespace

void drawRegion(ViewerModel& m) {
  const RegionRect& r = *m.region;
  ImGui::Text("%u,%u %ux%u (ctrl + drag to select)", r.x, r.y, r.width, r.height);
  ImGui::SameLine();
  if (ImGui::SmallButton("clear")) {
    m.region.reset();
    m.regionStats.reset();
    m.uiChanged = true;
    return;
  }
  if (!m.regionStats) {
    ImGui::TextWrapped("%s", m.regionNote.empty() ? "computing..." : m.regionNote.c_str());
    return;
  }
  const RegionStats& st = *m.regionStats;
  ImGui::Text("%llu pixels, %llu with a surface", (unsigned long long)st.pixels, (unsigned long long)st.surfacePixels);
  if (!m.regionNote.empty()) ImGui::TextWrapped("%s", m.regionNote.c_str());
  autoRangeButton(m);
  std::vector<const SeriesStats*> all;
  for (const SeriesStats& s : st.channels) all.push_back(&s);
  for (const SeriesStats& s : st.quantities) all.push_back(&s);
  if (all.empty()) return;
  if (m.regionSeries < 0 || m.regionSeries >= int(all.size())) m.regionSeries = 0;
  const SeriesStats& chosen = *all[size_t(m.regionSeries)];
  ImGui::Text("%s: n %llu  NaN %llu  +Inf %llu  -Inf %llu", seriesLabel(chosen).c_str(), (unsigned long long)chosen.count,
              (unsigned long long)chosen.nan, (unsigned long long)chosen.posInf, (unsigned long long)chosen.negInf);
  if (chosen.count)
    ImGui::Text("p1 %.6g  p50 %.6g  p99 %.6g  sd %.6g", chosen.p1, chosen.p50, chosen.p99, chosen.stddev);
  histogram(chosen);
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY | ImGuiTableFlags_BordersInnerV;
  if (!ImGui::BeginTable("region", 4, flags, ImVec2(0.0f, 200.0f))) return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("series (click: histogram)", ImGuiTableColumnFlags_WidthStretch);
  for (const char* h : {"min", "max", "mean"}) ImGui::TableSetupColumn(h, ImGuiTableColumnFlags_WidthFixed, 64.0f);
  ImGui::TableHeadersRow();
  for (size_t i = 0; i < all.size(); ++i) {
    const SeriesStats& s = *all[i];
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    if (ImGui::Selectable(seriesLabel(s).c_str(), int(i) == m.regionSeries, ImGuiSelectableFlags_SpanAllColumns)) {
      m.regionSeries = int(i);
      m.uiChanged = true;
    }
    for (double v : {s.min, s.max, s.mean}) {
      ImGui::TableNextColumn();
      if (s.count)
        ImGui::Text("%.5g", v);
      else
        ImGui::TextDisabled("-");
    }
  }
  ImGui::EndTable();
}

}  // namespace gb
