// The legends drawn at the bottom of a view (view_panel.cpp drawLabels): the heat ramp of counts
// and |A - B|, the grey or false-colour ramp of a mapping, FLIP's magma, and a map's legend in words.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <functional>
#include <string>
#include <vector>
#include <cstdio>

#include "shaders/view_colors.h"
#include "views/ui/view_legends.h"

namespace gb {

static ImU32 rgb(float r, float g, float b, float a = 1.0f) { return ImGui::ColorConvertFloat4ToU32(ImVec4(r, g, b, a)); }

// Tick labels under a ramp at five, three or two places (t in [0, 1]), as many as fit with a gap
// between neighbours: labels never run together however long the numbers are.
static void ticks(ImDrawList* dl, ImVec2 at, float width, float below, const std::function<std::string(double)>& label) {
  for (int n : {5, 3, 2}) {
    std::vector<std::string> texts;
    std::vector<float> x0s, x1s;
    for (int i = 0; i < n; ++i) {
      const double t = double(i) / (n - 1);
      texts.push_back(label(t));
      const float w = ImGui::CalcTextSize(texts.back().c_str()).x;
      const float x = at.x + float(width * t) - w * (i == 0 ? 0.0f : i == n - 1 ? 1.0f : 0.5f);
      x0s.push_back(x), x1s.push_back(x + w);
    }
    bool fits = true;
    for (int i = 1; i < n; ++i) fits &= x0s[size_t(i)] >= x1s[size_t(i - 1)] + 8.0f;
    if (!fits && n > 2) continue;
    for (int i = 0; i < n; ++i) dl->AddText(ImVec2(x0s[size_t(i)], at.y + below), rgb(1, 1, 1), texts[size_t(i)].c_str());
    return;
  }
}

// The heat map's legend: the colour ramp of views/visualize.cpp from 0 to the white point.
void heatLegend(ImDrawList* dl, ImVec2 at, float width, float maxCount, const char* unit) {
  const ImVec4 stops[5] = {{0, 0, 1, 1}, {0, 1, 1, 1}, {0, 1, 0, 1}, {1, 1, 0, 1}, {1, 0, 0, 1}};
  const float h = 10.0f;
  dl->AddRectFilled(ImVec2(at.x - 4, at.y - 4), ImVec2(at.x + width + 4, at.y + h + 18), rgb(0, 0, 0, 0.6f));
  for (int i = 0; i < 4; ++i) {
    float x0 = at.x + width * i / 4, x1 = at.x + width * (i + 1) / 4;
    ImU32 a = ImGui::ColorConvertFloat4ToU32(stops[i]), b = ImGui::ColorConvertFloat4ToU32(stops[i + 1]);
    dl->AddRectFilledMultiColor(ImVec2(x0, at.y), ImVec2(x1, at.y + h), a, b, b, a);
  }
  ticks(dl, at, width, h + 2, [&](double t) {
    char text[64];
    std::snprintf(text, sizeof text, "%.3g", maxCount * t);
    return std::string(text);
  });
  dl->AddText(ImVec2(at.x, at.y - 16), rgb(1, 1, 1), unit);  // black: none
}

// The legend of a grey or false-colour mapping: its ramp from the black to the white point (depths:
// near is bright), the values at five places (log: spaced as the mapping spaces them) and the unit.
void rampLegend(ImDrawList* dl, ImVec2 at, float width, const ViewMapping& mapping, const ResolvedRange& r,
                       const std::string& unit) {
  const float h = 10.0f;
  const bool depth = mapping.mapping == gpu::kViewMapDepth, falseColour = mapping.flags & gpu::kViewFlagFalseColor;
  const bool log = (mapping.flags & gpu::kViewFlagLog) && r.black > 0.0f && r.white > r.black;
  dl->AddRectFilled(ImVec2(at.x - 4, at.y - 18), ImVec2(at.x + width + 4, at.y + h + 18), rgb(0, 0, 0, 0.6f));
  auto colour = [&](float t) {
    glm::vec3 c = falseColour ? colors::viridis(depth ? 1.0f - t : t) : glm::vec3(depth ? 1.0f - 0.9f * t : t);
    return rgb(c.r, c.g, c.b);
  };
  const int steps = 32;
  for (int i = 0; i < steps; ++i) {
    float x0 = at.x + width * i / steps, x1 = at.x + width * (i + 1) / steps;
    dl->AddRectFilledMultiColor(ImVec2(x0, at.y), ImVec2(x1, at.y + h), colour(float(i) / steps), colour(float(i + 1) / steps),
                                colour(float(i + 1) / steps), colour(float(i) / steps));
  }
  ticks(dl, at, width, h + 2, [&](double t) {
    const double v = log ? r.black * std::pow(double(r.white) / r.black, t) : r.black + (r.white - r.black) * t;
    char text[64];
    std::snprintf(text, sizeof text, "%.4g", v);
    return std::string(text);
  });
  dl->AddText(ImVec2(at.x, at.y - 16), rgb(1, 1, 1), (unit + (log ? " (log)" : "")).c_str());
}

// FLIP's legend: the magma map (flip.h magmaColor, as the FLIP tool draws it) from 0 to 1.
void magmaLegend(ImDrawList* dl, ImVec2 at, float width) {
  const float h = 10.0f;
  const int steps = 32;
  dl->AddRectFilled(ImVec2(at.x - 4, at.y - 20), ImVec2(at.x + width + 4, at.y + h + 18), rgb(0, 0, 0, 0.6f));
  for (int i = 0; i < steps; ++i) {
    uint8_t a[3], b[3];
    magmaColor(double(i) / steps, a);
    magmaColor(double(i + 1) / steps, b);
    const ImU32 ca = IM_COL32(a[0], a[1], a[2], 255), cb = IM_COL32(b[0], b[1], b[2], 255);
    dl->AddRectFilledMultiColor(ImVec2(at.x + width * i / steps, at.y), ImVec2(at.x + width * (i + 1) / steps, at.y + h), ca,
                                cb, cb, ca);
  }
  ticks(dl, at, width, h + 2, [](double t) {
    char text[16];
    std::snprintf(text, sizeof text, "%.2g", t);
    return std::string(text);
  });
  dl->AddText(ImVec2(at.x, at.y - 16), rgb(1, 1, 1), "FLIP (A reference, B test): 0 alike .. 1");
}

// A map's legend in words (the reference error's maps: what each colour means), at the bottom of
// the view, wrapped to `width`.
void textLegend(ImDrawList* dl, const Rect& r, float width, const std::string& text) {
  const ImVec2 size = ImGui::CalcTextSize(text.c_str(), nullptr, false, width);
  const ImVec2 at(float(r.x) + 12, float(r.y + r.h) - 10 - size.y);
  dl->AddRectFilled(ImVec2(at.x - 4, at.y - 4), ImVec2(at.x + size.x + 4, at.y + size.y + 4), rgb(0, 0, 0, 0.7f));
  dl->AddText(ImGui::GetFont(), ImGui::GetFontSize(), at, rgb(1, 1, 1), text.c_str(), nullptr, width);
}

void classLegend(ImDrawList* dl, ImVec2 at, float width, const std::string& title, const std::vector<std::string>& names) {
  const float h = ImGui::GetFontSize();
  float x = at.x;
  dl->AddText(ImVec2(at.x, at.y - 16), rgb(1, 1, 1), title.c_str());
  for (size_t i = 0; i < names.size(); ++i) {
    const std::string text = std::to_string(i) + " " + names[i];
    const float w = h + 4 + ImGui::CalcTextSize(text.c_str()).x;
    if (x + w > at.x + width) break;  // no room: the hover still names the class
    const glm::vec3 c = colors::idColor(uint32_t(i));
    dl->AddRectFilled(ImVec2(x, at.y), ImVec2(x + h, at.y + h), rgb(c.r, c.g, c.b));
    dl->AddRect(ImVec2(x, at.y), ImVec2(x + h, at.y + h), rgb(0.6f, 0.6f, 0.6f));
    dl->AddText(ImVec2(x + h + 4, at.y), rgb(1, 1, 1), text.c_str());
    x += w + 14;
  }
}

}  // namespace gb
