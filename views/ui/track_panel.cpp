// The probe across a sequence's frames, in the Pixel panel (ImGui only): the probed view's decoded
// value over time, one plot per component with the frame shown marked, and the texel the point was
// followed to in each frame. The track itself is computed by views/analysis/probe_track.cpp.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <vector>

#include "views/ui/viewer_model.h"

namespace gb {

// One component's values over the frames the track reaches, as a plot with the frame shown marked.
static void componentPlot(const ProbeTrack& t, size_t c, int shown) {
  std::vector<float> values;
  float lo = std::numeric_limits<float>::infinity(), hi = -lo;
  for (size_t i = t.first; i <= t.last; ++i) {
    const double v = t.values[c][i];
    if (std::isfinite(v)) lo = std::min(lo, float(v)), hi = std::max(hi, float(v));
  }
  if (!(lo <= hi)) {
    ImGui::TextDisabled("%s: no value in any frame reached", t.components[c].c_str());
    return;
  }
  if (hi - lo < 1e-6f * std::max(1.0f, std::abs(hi))) lo -= 0.5f * std::max(1e-3f, std::abs(lo)), hi += 0.5f * std::max(1e-3f, std::abs(hi));
  for (size_t i = t.first; i <= t.last; ++i)  // frames without a value sit at the bottom
    values.push_back(std::isfinite(t.values[c][i]) ? float(t.values[c][i]) : lo);
  char overlay[160], top[32], bottom[32];
  const bool here = shown >= int(t.first) && shown <= int(t.last) && std::isfinite(t.values[c][size_t(shown)]);
  if (here)
    std::snprintf(overlay, sizeof overlay, "%s %.5g (this frame)", t.components[c].c_str(), t.values[c][size_t(shown)]);
  else
    std::snprintf(overlay, sizeof overlay, "%s", t.components[c].c_str());
  // The range beside the plot, its top and bottom (never over the line).
  std::snprintf(top, sizeof top, "%.4g", hi);
  std::snprintf(bottom, sizeof bottom, "%.4g", lo);
  const float labels = std::max(ImGui::CalcTextSize(top).x, ImGui::CalcTextSize(bottom).x) + ImGui::GetStyle().ItemSpacing.x;
  ImGui::PlotLines(("##track" + std::to_string(c)).c_str(), values.data(), int(values.size()), 0, overlay, lo, hi,
                   ImVec2(std::max(60.0f, ImGui::GetContentRegionAvail().x - labels), 46.0f));
  {
    const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax();
    ImDrawList* draw = ImGui::GetWindowDrawList();
    const ImU32 grey = ImGui::GetColorU32(ImGuiCol_TextDisabled);
    const float x = b.x + ImGui::GetStyle().ItemSpacing.x;
    draw->AddText(ImVec2(x, a.y), grey, top);
    draw->AddText(ImVec2(x, b.y - ImGui::GetTextLineHeight()), grey, bottom);
  }
  if (shown < int(t.first) || shown > int(t.last) || values.size() < 2) return;
  // The frame shown: a vertical line where PlotLines puts its sample (inside the frame padding).
  const ImVec2 a = ImGui::GetItemRectMin(), b = ImGui::GetItemRectMax(), pad = ImGui::GetStyle().FramePadding;
  const float x = a.x + pad.x + (b.x - a.x - 2 * pad.x) * float(shown - int(t.first)) / float(values.size() - 1);
  ImDrawList* draw = ImGui::GetWindowDrawList();
  draw->AddLine(ImVec2(x, a.y + 1), ImVec2(x, b.y - 1), IM_COL32(255, 210, 60, 255), 2.0f);
  if (here) {
    const float fy = (float(t.values[c][size_t(shown)]) - lo) / (hi - lo);
    draw->AddCircleFilled(ImVec2(x, b.y - pad.y - fy * (b.y - a.y - 2 * pad.y)), 3.5f, IM_COL32(255, 210, 60, 255));
  }
}

// The texel the point was followed to in each frame reached (the row of the frame shown highlighted).
static void followedTexels(const ViewerModel& m, const ProbeTrack& t) {
  const float rows = float(std::min<size_t>(t.last - t.first + 1, 6)) + 1.3f;
  if (!ImGui::BeginTable("followed", 3, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_ScrollY,
                         ImVec2(0, ImGui::GetTextLineHeightWithSpacing() * rows)))
    return;
  ImGui::TableSetupScrollFreeze(0, 1);
  ImGui::TableSetupColumn("frame");
  ImGui::TableSetupColumn("texel");
  ImGui::TableSetupColumn("position (continuous)");
  ImGui::TableHeadersRow();
  for (size_t i = t.first; i <= t.last; ++i) {
    ImGui::TableNextRow();
    if (int(i) == m.timeline.shown) ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg0, IM_COL32(110, 90, 20, 160));
    ImGui::TableNextColumn();
    ImGui::Text("%lld%s", i < m.timeline.numbers.size() ? (long long)m.timeline.numbers[i] : (long long)i, i == t.start ? " (probed)" : "");
    ImGui::TableNextColumn();
    ImGui::Text("%d, %d", t.texels[i]->x, t.texels[i]->y);
    ImGui::TableNextColumn();
    ImGui::Text("%.2f, %.2f", t.positions[i]->x, t.positions[i]->y);
  }
  ImGui::EndTable();
}

void trackSection(ViewerModel& m) {
  if (!m.track || !m.timeline.on) return;
  const ProbeTrack& t = *m.track;
  const auto number = [&](size_t i) { return i < m.timeline.numbers.size() ? (long long)m.timeline.numbers[i] : (long long)i; };
  if (!ImGui::CollapsingHeader("Across frames", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::TextWrapped("%s at pixel (%d, %d) of frame %lld, followed through frames %lld..%lld (%zu of %zu)", t.view.c_str(), t.pixel.x,
                     t.pixel.y, number(t.start), number(t.first), number(t.last), t.last - t.first + 1, t.frameCount);
  if (!t.stopBefore.empty()) ImGui::TextDisabled("before frame %lld: %s", number(t.first), t.stopBefore.c_str());
  if (!t.stopAfter.empty()) ImGui::TextDisabled("after frame %lld: %s", number(t.last), t.stopAfter.c_str());
  if (t.first == t.last)
    ImGui::TextDisabled("the point is in this frame only: nothing to plot");
  else {
    // The components the view shows (its channel checkboxes), all when it shows none of them.
    const int k = findView(m.views, t.view);
    uint32_t shownChannels = k >= 0 && size_t(k) < m.settings.size() ? m.settings[size_t(k)].channels : ~0u;
    if (!(shownChannels & ((1u << t.values.size()) - 1u))) shownChannels = ~0u;
    for (size_t c = 0; c < t.values.size(); ++c)
      if (shownChannels & (1u << c)) componentPlot(t, c, m.timeline.shown);
  }
  followedTexels(m, t);
  ImGui::Separator();
}

}  // namespace gb
