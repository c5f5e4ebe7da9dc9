// The two dossiers of one probed pixel of a compare as one table (views/ui/compare_view.h
// dossierRows): A beside B, fields paired by name, the values that differ marked and shown A over B.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <map>

#include "views/ui/compare_view.h"

namespace gb {
// ---- the dossiers as rows ---------------------------------------------------------------------

namespace {

// An array element's name: the first of these keys it holds.
std::string elementName(const nlohmann::json& e, size_t index) {
  if (e.is_object())
    for (const char* key : {"name", "target", "index", "light", "quantity", "method"})
      if (auto it = e.find(key); it != e.end()) return it->is_string() ? it->get<std::string>() : it->dump();
  return std::to_string(index);
}

bool shortNumberArray(const nlohmann::json& j) {
  if (!j.is_array() || j.size() > 4) return false;
  for (const nlohmann::json& e : j)
    if (!e.is_number()) return false;
  return true;
}

// A value as people read it: numbers to `digits` significant digits (0: every digit that tells it
// apart, JSON's shortest form), integers whole, short number arrays as one list, strings unquoted.
std::string valueText(const nlohmann::json& j, int digits) {
  if (j.is_number_float() && digits > 0) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.*g", digits, j.get<double>());
    return buf;
  }
  if (j.is_string()) return j.get<std::string>();
  if (j.is_array()) {
    std::string out = "[";
    for (size_t i = 0; i < j.size(); ++i) out += (i ? ", " : "") + valueText(j[i], digits);
    return out + "]";
  }
  return j.dump();
}

// path -> value, in the order met.
using Flat = std::vector<std::pair<std::string, nlohmann::json>>;

void flatten(const nlohmann::json& j, const std::string& path, Flat& out) {
  if (j.is_object() && !j.empty()) {
    for (auto it = j.begin(); it != j.end(); ++it) flatten(it.value(), path.empty() ? it.key() : path + "." + it.key(), out);
  } else if (j.is_array() && !j.empty() && !shortNumberArray(j)) {
    std::map<std::string, int> seen;  // two elements of one name: the second is name#2
    for (size_t i = 0; i < j.size(); ++i) {
      std::string name = elementName(j[i], i);
      if (int n = ++seen[name]; n > 1) name += "#" + std::to_string(n);
      flatten(j[i], path + "[" + name + "]", out);
    }
  } else {
    out.push_back({path, j});
  }
}

}  // namespace

// `text` in lines of at most `width` pixels, broken only at spaces: ImGui's own wrapping also breaks
// after '.', cutting numbers in two. A word wider than `width` stays whole.
static std::string fitLines(const std::string& text, float width) {
  std::string out, line;
  for (size_t i = 0; i < text.size();) {
    const size_t space = text.find(' ', i);
    const size_t end = space == std::string::npos ? text.size() : space + 1;
    const std::string word = text.substr(i, end - i);
    i = end;
    if (!line.empty() && ImGui::CalcTextSize((line + word).c_str()).x > width) {
      while (!line.empty() && line.back() == ' ') line.pop_back();
      out += line + "\n";
      line.clear();
    }
    line += word;
  }
  return out + line;
}

std::vector<DossierRow> dossierRows(const nlohmann::json& a, const nlohmann::json& b) {
  struct Entry {
    size_t section;  // order of the section's first appearance
    std::string field;
    const nlohmann::json *a = nullptr, *b = nullptr;
  };
  std::vector<std::string> sections;
  std::vector<Entry> entries;
  std::map<std::string, size_t> at;  // section + path -> entry
  std::vector<Flat> flats;           // keeps the flattened values alive
  flats.reserve(2 * (a.size() + b.size()));
  auto add = [&](const nlohmann::json& side, bool isA) {
    if (!side.is_object()) return;
    for (auto it = side.begin(); it != side.end(); ++it) {
      size_t section = std::find(sections.begin(), sections.end(), it.key()) - sections.begin();
      if (section == sections.size()) sections.push_back(it.key());
      flats.emplace_back();
      flatten(it.value(), "", flats.back());
      for (auto& [field, value] : flats.back()) {
        auto found = at.emplace(it.key() + "\n" + field, entries.size()).first;
        if (found->second == entries.size()) entries.push_back({section, field});
        (isA ? entries[found->second].a : entries[found->second].b) = &value;
      }
    }
  };
  add(a, true);
  add(b, false);
  // B's extra fields join their section (A's order, then B's).
  std::stable_sort(entries.begin(), entries.end(), [](const Entry& x, const Entry& y) { return x.section < y.section; });
  std::vector<DossierRow> rows;
  for (const Entry& e : entries) {
    DossierRow r{sections[e.section], e.field, e.a ? valueText(*e.a, 7) : "", e.b ? valueText(*e.b, 7) : ""};
    r.differs = !e.a || !e.b || *e.a != *e.b;
    if (r.differs && r.a == r.b) r.a = valueText(*e.a, 0), r.b = valueText(*e.b, 0);  // beyond 7 digits
    rows.push_back(std::move(r));
  }
  return rows;
}

// ---- the dossiers -----------------------------------------------------------------------------

void compareDossiers(ViewerModel& m) {
  if (!m.dossierJson.contains("a") || !m.dossierJson.contains("b")) return;
  const std::vector<DossierRow> rows = dossierRows(m.dossierJson["a"], m.dossierJson["b"]);
  size_t differing = 0;
  for (const DossierRow& r : rows) differing += r.differs;
  ImGui::Text("A and B at this pixel: %zu of %zu values differ", differing, rows.size());
  ImGui::SameLine();
  ImGui::Checkbox("only those", &m.dossierDifferencesOnly);
  const ImVec4 differs(1.0f, 0.7f, 0.25f, 1.0f);
  ImGui::BeginChild("dossiers");
  for (size_t i = 0; i < rows.size();) {
    // One section: a tree node saying how many of its values differ, open where any does.
    size_t end = i, sectionDiffers = 0;
    while (end < rows.size() && rows[end].section == rows[i].section) sectionDiffers += rows[end++].differs;
    if (m.dossierDifferencesOnly && sectionDiffers == 0) {
      i = end;
      continue;
    }
    char title[160];
    std::snprintf(title, sizeof title, "%s  (%zu of %zu differ)###%s", rows[i].section.c_str(), sectionDiffers, end - i,
                  rows[i].section.c_str());
    if (sectionDiffers) ImGui::PushStyleColor(ImGuiCol_Text, differs);
    const bool open = ImGui::TreeNodeEx(title, sectionDiffers ? ImGuiTreeNodeFlags_DefaultOpen : 0);
    if (sectionDiffers) ImGui::PopStyleColor();
    if (open) {
      // Two columns, so that a narrow panel shows every value: a value both share once, one that
      // differs as an A line over a B line, marked. Long field paths and values wrap in their
      // column (the field column at most 45 % of the panel) instead of pushing the values out.
      float fieldWidth = 0.0f;
      for (size_t k = i; k < end; ++k) fieldWidth = std::max(fieldWidth, ImGui::CalcTextSize(rows[k].field.c_str()).x);
      fieldWidth = std::min(fieldWidth, 0.45f * ImGui::GetContentRegionAvail().x);
      if (ImGui::BeginTable(rows[i].section.c_str(), 2, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg)) {
        ImGui::TableSetupColumn("field", ImGuiTableColumnFlags_WidthFixed, fieldWidth);
        ImGui::TableSetupColumn("A = B, or A over B", ImGuiTableColumnFlags_WidthStretch);
        ImGui::TableHeadersRow();
        for (size_t k = i; k < end; ++k) {
          const DossierRow& r = rows[k];
          if (m.dossierDifferencesOnly && !r.differs) continue;
          ImGui::TableNextRow();
          ImGui::TableNextColumn();
          ImGui::PushTextWrapPos(0.0f);  // field paths wrap at the column's edge
          if (!r.differs) {
            ImGui::TextUnformatted(r.field.c_str());
            ImGui::TableNextColumn();
            ImGui::TextUnformatted(fitLines(r.a, ImGui::GetContentRegionAvail().x).c_str());
          } else {
            ImGui::TableSetBgColor(ImGuiTableBgTarget_RowBg1, ImGui::GetColorU32(ImVec4(0.45f, 0.25f, 0.05f, 0.6f)));
            ImGui::TextColored(differs, "%s", r.field.c_str());
            ImGui::TableNextColumn();
            const float width = ImGui::GetContentRegionAvail().x;
            ImGui::TextColored(ImVec4(0.6f, 0.8f, 1.0f, 1), "%s", fitLines("A " + (r.a.empty() ? "(none)" : r.a), width).c_str());
            ImGui::TextColored(ImVec4(1.0f, 0.75f, 0.45f, 1), "%s", fitLines("B " + (r.b.empty() ? "(none)" : r.b), width).c_str());
          }
          ImGui::PopTextWrapPos();
        }
        ImGui::EndTable();
      }
      ImGui::TreePop();
    }
    i = end;
  }
  ImGui::EndChild();
}

}  // namespace gb
