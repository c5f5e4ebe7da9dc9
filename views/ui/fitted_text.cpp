// fitted_text.h: ImGui's CalcTextSize measures; the cut is found by bisection over characters.
#include "views/ui/fitted_text.h"

#include <imgui.h>

namespace gb {

std::string fitToWidth(const std::string& text, float width) {
  if (ImGui::CalcTextSize(text.c_str()).x <= width) return text;
  const float room = width - ImGui::CalcTextSize("...").x;
  size_t lo = 0, hi = text.size();  // the longest prefix that fits lies in [lo, hi]
  while (lo < hi) {
    const size_t mid = (lo + hi + 1) / 2;
    if (ImGui::CalcTextSize(text.c_str(), text.c_str() + mid).x <= room) lo = mid;
    else hi = mid - 1;
  }
  while (lo > 0 && (static_cast<unsigned char>(text[lo]) & 0xC0) == 0x80) --lo;  // not inside a character
  return text.substr(0, lo) + "...";
}

bool fittedText(const std::string& text) {
  const std::string shown = fitToWidth(text, ImGui::GetContentRegionAvail().x);
  ImGui::TextUnformatted(shown.c_str());
  const bool cut = shown.size() != text.size() || shown != text;
  if (cut && ImGui::IsItemHovered()) {
    ImGui::BeginTooltip();
    ImGui::PushTextWrapPos(ImGui::GetFontSize() * 60.0f);
    ImGui::TextUnformatted(text.c_str());
    ImGui::PopTextWrapPos();
    ImGui::EndTooltip();
  }
  return cut;
}

}  // namespace gb
