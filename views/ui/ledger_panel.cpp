// The probe panel's "Why is this pixel lit" section: the light ledger (views/analysis/probe.h),
// filterable by fate and by text, sorted by contribution; hover a row for the rule in full.
#include <imgui.h>

#include <cstdio>
#include <cstring>
#include <string>

#include "views/analysis/probe.h"

namespace gb {

namespace {
bool contributes(const LedgerEntry& e) { return e.fate == "shaded" || e.fate == "lit"; }
bool culled(const LedgerEntry& e) { return e.fate == "frustum_culled" || e.fate == "sub_pixel" || e.fate == "empty"; }
}  // namespace

void ledgerSection(const PixelDossier& d) {
  const LightLedger& l = d.ledger;
  if (l.entries.empty()) return;
  char title[160];
  std::snprintf(title, sizeof title, "Why is this pixel lit: %zu lights listed###ledger", l.entries.size());
  if (!ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen)) return;
  static int show = 0;  // 0 all, 1 lighting it, 2 not lighting it, 3 culled
  static char filter[64] = "";
  ImGui::SetNextItemWidth(150.0f);
  ImGui::Combo("##fate", &show, "all\0lighting it\0not lighting it\0culled\0");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(-1.0f);
  ImGui::InputTextWithHint("##ledger filter", "filter (fate, light index, rule)", filter, sizeof filter);
  ImGui::TextDisabled("%s%s", l.rule.c_str(), l.notListed ? (", " + std::to_string(l.notListed) + " farther not listed").c_str() : "");
  // No scroll area of its own: the wheel scrolls the pixel panel, not a box inside it.
  const ImGuiTableFlags flags = ImGuiTableFlags_RowBg | ImGuiTableFlags_BordersInnerV;
  if (!ImGui::BeginTable("ledger", 4, flags)) return;
  ImGui::TableSetupColumn("light", ImGuiTableColumnFlags_WidthFixed, 60.0f);
  ImGui::TableSetupColumn("fate", ImGuiTableColumnFlags_WidthFixed, 110.0f);
  ImGui::TableSetupColumn("d / r", ImGuiTableColumnFlags_WidthFixed, 50.0f);
  ImGui::TableSetupColumn("contribution", ImGuiTableColumnFlags_WidthStretch);
  ImGui::TableHeadersRow();
  for (const LedgerEntry& e : l.entries) {
    if ((show == 1 && !contributes(e)) || (show == 2 && contributes(e)) || (show == 3 && !culled(e))) continue;
    const std::string name = e.light == "sun" ? "sun" : std::to_string(e.index);  // as the point-lights table names it
    if (filter[0] && (name + " " + e.fate + " " + e.why + " " + e.drawnAs).find(filter) == std::string::npos) continue;
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(name.c_str());
    ImGui::TableNextColumn();
    if (contributes(e))
      ImGui::TextColored(ImVec4(0.4f, 1, 0.4f, 1), "%s", e.fate.c_str());
    else
      ImGui::TextDisabled("%s", e.fate.c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s%s%s", e.why.c_str(), e.drawnAs.empty() ? "" : "\ndrawn as: ", e.drawnAs.c_str());
    ImGui::TableNextColumn();
    if (e.light == "point")
      ImGui::Text("%.3g", e.distance / e.radius);
    else
      ImGui::TextDisabled("-");
    ImGui::TableNextColumn();
    ImGui::Text("%.4g %.4g %.4g", e.contribution.r, e.contribution.g, e.contribution.b);
  }
  ImGui::EndTable();
}

}  // namespace gb
