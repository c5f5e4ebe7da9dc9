// The compare viewer's choices without ImGui (views/ui/compare_panel.cpp draws them): flipping A
// and B in place, and the two dossiers of one pixel as rows of one table, A beside B, the rows whose
// values differ marked.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "views/ui/viewer_model.h"

namespace gb {

// Space / the Flip button: shows the other capture in place (same view, zoom and pan); from any
// other mode, A or B in place again, starting with the other side than the one last shown.
void flipCompareSide(ViewerModel& m);

// One value of the dossier: its section (the dossier JSON's top-level key), the path below it
// ("ledger.entries[sun].contribution": array elements named by their name, target, light, index or
// quantity where they have one, else numbered), and each side's value as JSON text ("" where that
// side has no such field). Short number arrays (vectors, colours) are one value.
struct DossierRow {
  std::string section, field, a, b;
  bool differs = false;
};
// Every value of either dossier, in A's order (B's extra fields after them).
std::vector<DossierRow> dossierRows(const nlohmann::json& a, const nlohmann::json& b);

}  // namespace gb
