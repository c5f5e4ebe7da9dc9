// The "Reference error" section of the controls: computes, for the live frame on request, the maps
// `gblens error -o` writes and the lighting decomposition of `gblens decompose` (app/viewer/
// reference_error.cpp, a worker thread) with its progress and a cancel; the maps then are views of
// the frame ("error/<map>", "decompose/<term>": the grid, the View menu, hover and probe), and the
// legend of the one last used is here.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "views/ui/viewer_model.h"

namespace gb {

// A button for each map view, showing it alone (its hover, probe and legend are those of a view),
// and one for the grid of every view: where the maps went, said where they were asked for.
static void mapButtons(ViewerModel& m) {
  float x = 0.0f;
  const float right = ImGui::GetContentRegionAvail().x;
  for (size_t k = 0; k < m.views.size(); ++k) {
    const std::string& n = m.views[k].name;
    if (n.rfind("error/", 0) != 0 && n.rfind("decompose/", 0) != 0) continue;
    const float w = ImGui::CalcTextSize(n.c_str()).x + 2.0f * ImGui::GetStyle().FramePadding.x;
    if (x > 0.0f && x + ImGui::GetStyle().ItemSpacing.x + w <= right)
      ImGui::SameLine(), x += ImGui::GetStyle().ItemSpacing.x;
    else
      x = 0.0f;
    x += w;
    const bool shown = m.layout != LayoutMode::Grid && m.primary == int(k);
    if (shown) ImGui::PushStyleColor(ImGuiCol_Button, ImGui::GetStyle().Colors[ImGuiCol_ButtonActive]);
    if (ImGui::SmallButton(n.c_str())) {
      m.primary = m.edited = int(k);
      if (m.layout == LayoutMode::Grid) m.layout = LayoutMode::Single;
      m.uiChanged = true;
    }
    if (shown) ImGui::PopStyleColor();
  }
  if (ImGui::SmallButton("every view in the grid (1)")) m.layout = LayoutMode::Grid, m.uiChanged = true;
}

void referenceErrorSection(ViewerModel& m) {
  auto& e = m.referenceError;
  if (e.computing) {
    char overlay[64];
    std::snprintf(overlay, sizeof overlay, "%.0f%%  (%.1f s)", e.progress * 100.0, e.seconds);
    ImGui::ProgressBar(float(e.progress), ImVec2(-80.0f, 0.0f), overlay);
    ImGui::SameLine();
    if (ImGui::Button("Cancel")) e.cancelRequested = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("Escape cancels too");
  } else if (ImGui::Button(e.ready ? "Recompute for this frame" : "Compute for this frame")) {
    e.computeRequested = true;
  }
  if (!e.error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", e.error.c_str());
  if (!e.ready) {
    if (!e.computing && ImGui::IsItemHovered())
      ImGui::SetTooltip("The maps of gblens error -o for the frame on screen (fairy sprites off, primitive_id on, as\n"
                        "gblens error renders it) against the double-precision ray-traced reference, and the lighting\n"
                        "terms of gblens decompose, as views of the frame (the grid, the View menu). Seconds on a CPU\n"
                        "device; the viewer stays usable meanwhile.");
    return;
  }
  ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
  ImGui::TextWrapped("%s (%.1f s)", e.summary.c_str(), e.seconds);
  ImGui::PopStyleColor();
  mapButtons(m);
  if (e.stale) ImGui::TextColored(ImVec4(1, 0.7f, 0.3f, 1), "stale: the frame changed since (recompute)");
  if (!e.decomposeNote.empty()) ImGui::TextWrapped("%s", e.decomposeNote.c_str());
  if (m.edited >= 0 && size_t(m.edited) < m.views.size())
    if (auto it = e.legends.find(m.views[size_t(m.edited)].name); it != e.legends.end())
      ImGui::TextWrapped("%s: %s", it->first.c_str(), it->second.c_str());
}

}  // namespace gb
