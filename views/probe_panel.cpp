// The pixel panel: the value under the mouse and the probe's dossier (views/probe.h, the same
// JSON `gblens probe` prints), shown as a tree, with "Copy as JSON".
#include <imgui.h>

#include <cstdio>
#include <string>

#include "views/viewer_model.h"

namespace gb {

// A scalar as JSON writes it: the shortest text that reads back as the same double.
static std::string scalarText(const nlohmann::json& j) {
  if (j.is_string()) return j.get<std::string>();
  return j.dump();
}

static bool isSmallVector(const nlohmann::json& j) {
  if (!j.is_array() || j.empty() || j.size() > 4) return false;
  for (const auto& e : j)
    if (!e.is_primitive()) return false;
  return true;
}

static void jsonTree(const std::string& key, const nlohmann::json& j, int depth) {
  if (j.is_object() || (j.is_array() && !isSmallVector(j))) {
    ImGuiTreeNodeFlags flags = depth < 1 ? ImGuiTreeNodeFlags_DefaultOpen : 0;
    if (j.is_array() && j.size() <= 3) flags |= ImGuiTreeNodeFlags_DefaultOpen;
    std::string label = key + (j.is_array() ? " [" + std::to_string(j.size()) + "]" : "");
    if (ImGui::TreeNodeEx(label.c_str(), flags)) {
      if (j.is_object())
        for (auto it = j.begin(); it != j.end(); ++it) jsonTree(it.key(), it.value(), depth + 1);
      else
        for (size_t i = 0; i < j.size(); ++i) jsonTree(std::to_string(i), j[i], depth + 1);
      ImGui::TreePop();
    }
    return;
  }
  std::string value;
  if (j.is_array()) {
    for (size_t i = 0; i < j.size(); ++i) value += (i ? ", " : "") + scalarText(j[i]);
    value = "[" + value + "]";
  } else {
    value = scalarText(j);
  }
  ImGui::TextDisabled("%s", key.c_str());
  ImGui::SameLine();
  ImGui::TextUnformatted(value.c_str());
}

void drawDossier(ViewerModel& m) {
  if (m.hover)
    ImGui::Text("mouse (%d, %d)", m.hover->x, m.hover->y);
  else if (m.hoverShadowTexel)
    ImGui::Text("shadow-map texel (%d, %d)", m.hoverShadowTexel->x, m.hoverShadowTexel->y);
  else
    ImGui::TextDisabled("mouse outside the image");
  if (!m.hoverText.empty()) ImGui::TextWrapped("%s", m.hoverText.c_str());
  if (m.shadowMark) {
    ImGui::TextColored(ImVec4(1, 0, 1, 1), "marked: pixels sampling shadow texel (%d, %d)", m.shadowMark->x, m.shadowMark->y);
    ImGui::SameLine();
    if (ImGui::SmallButton("clear")) m.shadowMark.reset();
  }
  ImGui::Separator();
  if (!m.probePixel) {
    ImGui::TextWrapped("Click a pixel (or use the arrow keys) for its dossier: stored values of every target, "
                       "reconstructed positions, the shadow-map texel, the point lights that reach it.");
    return;
  }
  ImGui::Text("pixel (%d, %d)", m.probePixel->x, m.probePixel->y);
  ImGui::SameLine();
  ImGui::TextDisabled("answered in %.1f ms", m.probeLatencyMs);
  if (!m.probeError.empty()) {
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", m.probeError.c_str());
    return;
  }
  if (m.dossier.is_null()) return;
  if (ImGui::Button("Copy as JSON")) m.copyJson = true;
  ImGui::BeginChild("dossier");
  for (auto it = m.dossier.begin(); it != m.dossier.end(); ++it) jsonTree(it.key(), it.value(), 0);
  ImGui::EndChild();
}

}  // namespace gb
