// The compare viewer's panels (--capture A --compare B): the mode of the view pane (A/B flipped in
// place, swipe, |A - B|, FLIP, a row of three), `gblens compare`'s report as tables (a row per
// quantity, a column per figure, never wrapped), and the tabs of the report and of the probed
// pixel's two dossiers (compare_dossier.cpp).
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "views/analysis/compare.h"
#include "views/ui/compare_view.h"

namespace gb {

void flipCompareSide(ViewerModel& m) {
  if (m.compareMode != CompareMode::Alternate) {
    m.compareMode = CompareMode::Alternate;
  }
  m.compareSide = m.compareSide == FrameSide::A ? FrameSide::B : FrameSide::A;
  m.uiChanged = true;
}

// ---- the mode ---------------------------------------------------------------------------------

void compareControls(ViewerModel& m) {
  int mode = int(m.compareMode);
  ImGui::RadioButton("A / B", &mode, int(CompareMode::Alternate));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("one capture at a time in place; Space flips A and B");
  ImGui::SameLine();
  ImGui::RadioButton("swipe", &mode, int(CompareMode::Swipe));
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("A left of the handle, B right of it (drag the handle)");
  ImGui::SameLine();
  ImGui::RadioButton("|A-B|", &mode, int(CompareMode::Difference));
  ImGui::RadioButton("FLIP", &mode, int(CompareMode::Flip));
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("FLIP of colour views (LDR-FLIP; HDR-FLIP of radiance), A the reference: what a viewer "
                      "flipping between them notices, 0 .. 1");
  ImGui::SameLine();
  ImGui::RadioButton("A, B, |A-B| in a row", &mode, int(CompareMode::Row));
  if (mode != int(m.compareMode)) m.compareMode = CompareMode(mode), m.uiChanged = true;
  const bool b = m.compareSide == FrameSide::B;
  if (ImGui::Button(b ? "Flip to A  (Space)" : "Flip to B  (Space)")) flipCompareSide(m);
  if (m.compareMode == CompareMode::Alternate) {
    ImGui::SameLine();
    ImGui::TextColored(b ? ImVec4(1.0f, 0.65f, 0.3f, 1) : ImVec4(0.5f, 0.7f, 1.0f, 1), "showing %s", b ? "B" : "A");
  }
  if (m.compareMode == CompareMode::Swipe) ImGui::SliderFloat("split at", &m.splitAt, 0.0f, 1.0f, "%.2f");
  if (!m.flipStatus.empty()) ImGui::TextDisabled("%s", m.flipStatus.c_str());
}

// ---- the report -------------------------------------------------------------------------------

namespace {

std::string g4(double v) {
  char buf[32];
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}
std::string g4(const nlohmann::json& j, const char* key) {
  auto it = j.find(key);
  if (it == j.end()) return "";
  if (it->is_number_integer()) return it->dump();  // counts: every digit
  if (it->is_number()) return g4(it->get<double>());
  return it->is_string() ? it->get<std::string>() : it->dump();
}
ImVec4 verdictColour(Verdict v) {
  return v == Verdict::Pass ? ImVec4(0.5f, 0.9f, 0.5f, 1) : v == Verdict::Warn ? ImVec4(1, 0.85f, 0.3f, 1) : ImVec4(1, 0.4f, 0.4f, 1);
}
const char* verdictText(Verdict v) { return v == Verdict::Pass ? "PASS" : v == Verdict::Warn ? "WARN" : "FAIL"; }

// The figures of one metric kind: column headers and each group's values.
struct KindColumns {
  std::vector<const char*> headers;
  std::vector<std::string> (*values)(const GroupResult&);
};
KindColumns kindColumns(MetricKind k) {
  switch (k) {
    case MetricKind::Colour:
      return {{"max", "mean", "rmse", "PSNR dB"},
              [](const GroupResult& g) -> std::vector<std::string> {
                return {g4(g.figures.metrics, "max_abs"), g4(g.figures.metrics, "mean_abs"), g4(g.figures.metrics, "rmse"), g4(g.figures.metrics, "psnr_db")};
              }};
    case MetricKind::Normal:
      return {{"max deg", "mean deg", "p99 deg"},
              [](const GroupResult& g) -> std::vector<std::string> {
                return {g4(g.figures.metrics, "max_degrees"), g4(g.figures.metrics, "mean_degrees"), g4(g.figures.metrics, "p99_degrees")};
              }};
    case MetricKind::Depth:
    case MetricKind::Position:
      return {{"abs max", "abs mean", "rel max", "rel mean"},
              [](const GroupResult& g) -> std::vector<std::string> {
                return {g4(g.figures.metrics, "max_abs"), g4(g.figures.metrics, "mean_abs"), g4(g.figures.metrics, "max_rel"), g4(g.figures.metrics, "mean_rel")};
              }};
    case MetricKind::Exact:
      return {{"pixels differing"},
              [](const GroupResult& g) -> std::vector<std::string> { return {g4(g.figures.metrics, "differing_pixels")}; }};
  }
  return {};
}

constexpr ImGuiTableFlags kTableFlags = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingFixedFit |
                                        ImGuiTableFlags_ScrollX | ImGuiTableFlags_NoHostExtendY;

// Height of a table of `rows` rows (one header), with room for its horizontal scroll bar: a row is
// a line of text and the cell padding above and below it.
float tableHeight(size_t rows) {
  const ImGuiStyle& s = ImGui::GetStyle();
  return (ImGui::GetTextLineHeight() + 2.0f * s.CellPadding.y) * float(rows + 1) + s.ScrollbarSize + 3.0f;
}

void groupTable(const CompareReport& r, MetricKind kind) {
  std::vector<const GroupResult*> groups;
  for (const GroupResult& g : r.groups)
    if (g.group.kind == kind) groups.push_back(&g);
  if (groups.empty()) return;
  const KindColumns cols = kindColumns(kind);
  const bool masked = std::any_of(groups.begin(), groups.end(), [](const GroupResult* g) { return g->figures.covers == PixelSet::Unmasked; });
  const int n = 2 + int(cols.headers.size()) + 2 + (masked ? 2 : 0);
  ImGui::TextDisabled("%s", name(kind));
  if (!ImGui::BeginTable(name(kind), n, kTableFlags, ImVec2(0, tableHeight(groups.size())))) return;
  ImGui::TableSetupColumn("quantity");
  ImGui::TableSetupColumn("result");
  for (const char* h : cols.headers) ImGui::TableSetupColumn(h);
  ImGui::TableSetupColumn("% over fail");
  ImGui::TableSetupColumn("pixels");
  if (masked) {
    ImGui::TableSetupColumn("masked px");
    ImGui::TableSetupColumn("masked max");
  }
  ImGui::TableHeadersRow();
  for (const GroupResult* g : groups) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(g->group.group.c_str());
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s (target %s)", g->group.key.c_str(), g->target.c_str());
    ImGui::TableNextColumn();
    ImGui::TextColored(verdictColour(g->verdict), "%s", verdictText(g->verdict));
    for (const std::string& v : cols.values(*g)) {
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(v.c_str());
    }
    ImGui::TableNextColumn();
    ImGui::Text("%.4g", 100.0 * double(g->figures.overFail) / double(std::max<uint64_t>(g->figures.pixels, 1)));
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("fail threshold %s", g4(g->thresholds.fail).c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%llu", (unsigned long long)g->figures.pixels);
    if (masked) {
      const GroupFigures* apart = g->figuresOver(PixelSet::Masked);
      ImGui::TableNextColumn();
      ImGui::Text("%llu", (unsigned long long)(apart ? apart->pixels : 0));
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(apart ? g4(apart->maxError).c_str() : "-");
    }
  }
  ImGui::EndTable();
}

// FLIP of the colour views, as the viewer computed it (A the reference).
void flipTable(const ViewerModel& m) {
  size_t rows = 0;
  for (const auto& p : m.flipPools) rows += p.has_value();
  if (rows == 0) return;
  ImGui::TextDisabled("FLIP (A reference, B test; %.0f pixels per degree)", flipDefaultPpd());
  if (!ImGui::BeginTable("flip", 7, kTableFlags, ImVec2(0, tableHeight(rows)))) return;
  for (const char* h : {"view", "FLIP", "mean", "weighted median", "weighted Q1..Q3", "max", "pixels"}) ImGui::TableSetupColumn(h);
  ImGui::TableHeadersRow();
  for (size_t k = 0; k < m.flipPools.size(); ++k) {
    if (!m.flipPools[k]) continue;
    const FlipPool& p = *m.flipPools[k];
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(m.views[k].name.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(m.views[k].hdr ? "HDR" : "LDR");
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(g4(p.mean).c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(g4(p.weightedMedian).c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%s .. %s", g4(p.weightedQuartile1).c_str(), g4(p.weightedQuartile3).c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(g4(p.max).c_str());
    ImGui::TableNextColumn();
    ImGui::Text("%llu", (unsigned long long)p.pixels);
  }
  ImGui::EndTable();
}

// Manifest fields that differ, targets that could not be compared.
void notesTable(const CompareReport& r) {
  const size_t rows = r.differences.size() + r.mismatches.size() + r.skipped.size();
  if (rows == 0) return;
  ImGui::TextDisabled("not compared pixel by pixel");
  if (!ImGui::BeginTable("notes", 3, kTableFlags, ImVec2(0, tableHeight(rows)))) return;
  for (const char* h : {"field / target", "A", "B"}) ImGui::TableSetupColumn(h);
  ImGui::TableHeadersRow();
  for (const nlohmann::json& d : r.differences) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(d.value("name", "").c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(d["a"].dump().c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(d["b"].dump().c_str());
  }
  for (auto* list : {&r.mismatches, &r.skipped})
    for (auto& [target, why] : *list) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextColored(list == &r.mismatches ? ImVec4(1, 0.4f, 0.4f, 1) : ImVec4(0.7f, 0.7f, 0.7f, 1), "%s %s",
                         list == &r.mismatches ? "MISMATCH" : "skipped", target.c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(why.c_str());
      ImGui::TableNextColumn();
    }
  ImGui::EndTable();
}

}  // namespace

static void compareReportSection(ViewerModel& m) {
  if (!m.compareReport) {
    ImGui::TextWrapped("%s", m.compareSummary.c_str());
    return;
  }
  const CompareReport& r = *m.compareReport;
  static const char* const kResults[] = {"PASS", "WARN", "FAIL", "MISMATCH", "FILE ERROR"};
  const int code = std::clamp(r.exitCode, 0, 4);
  ImGui::TextColored(code == 0 ? ImVec4(0.5f, 0.9f, 0.5f, 1) : code == 1 ? ImVec4(1, 0.85f, 0.3f, 1) : ImVec4(1, 0.4f, 0.4f, 1),
                     "%s (gblens compare's exit %d)", kResults[code], r.exitCode);
  ImGui::SameLine();
  if (ImGui::SmallButton("Copy as text")) ImGui::SetClipboardText(m.compareSummary.c_str());
  for (MetricKind k : {MetricKind::Colour, MetricKind::Normal, MetricKind::Depth, MetricKind::Position, MetricKind::Exact})
    groupTable(r, k);
  flipTable(m);
  notesTable(r);
}

void drawDossier(ViewerModel& m);  // probe_panel.cpp: the hover and the dossier (compare: compareDossiers,
                                   // compare_dossier.cpp)

// The Pixel panel of a compare: the report, and the pixel's dossiers (brought to the front by a
// new probe).
void compareTabs(ViewerModel& m) {
  static std::optional<glm::ivec2> shown;  // the probed pixel the Pixel tab was last brought up for
  const bool newProbe = m.probePixel && m.probePixel != shown;
  if (newProbe) shown = m.probePixel;
  if (!ImGui::BeginTabBar("compare")) return;
  if (ImGui::BeginTabItem("Report")) {
    ImGui::BeginChild("report");
    compareReportSection(m);
    ImGui::EndChild();
    ImGui::EndTabItem();
  }
  if (ImGui::BeginTabItem("Pixel A vs B", nullptr, newProbe ? ImGuiTabItemFlags_SetSelected : 0)) {
    drawDossier(m);
    ImGui::EndTabItem();
  }
  ImGui::EndTabBar();
}

}  // namespace gb
