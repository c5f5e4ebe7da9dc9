// Values printed inside texels at high zoom, as tev and RenderDoc's texture viewer do: once every
// visible texel's lines fit inside it, each texel shows the components the view shows at the
// precision its storage has, in black on light texels and white on dark ones.
#include "views/ui/texel_values.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

#include "views/ui/view_layout.h"

namespace gb {

namespace {

// More texels than this on screen and no texel is large enough for a value anyway (a 4K window at
// 40 px per texel shows about 5,000): the lookup is bounded however the view is zoomed.
constexpr int kMaxTexels = 6000;
constexpr float kPad = 3.0f;  // pixels between the text and the texel's edges

float luminance(const glm::vec3& c) { return 0.2126f * c.x + 0.7152f * c.y + 0.0722f * c.z; }

}  // namespace

void drawTexelValues(ViewerModel& m, int view, FrameSide side, const Rect& r, const Placement& pl,
                     const ResolvedRange& range) {
  if (!m.texelValues || !m.texelValue || side == FrameSide::Difference || side == FrameSide::Flip) return;
  const ViewDef& def = m.views[size_t(view)];
  const ImFont* font = ImGui::GetFont();
  const float lineH = ImGui::GetFontSize();
  if (pl.scale < 2.0 * lineH) return;  // not even two lines: no texel can hold a value
  // The texels whose rectangle meets the slot.
  const glm::dvec2 lo = glm::floor(texelAt(pl, {r.x, r.y})), hi = glm::ceil(texelAt(pl, {r.x + r.w, r.y + r.h}));
  const glm::uvec2 size = viewImageSize(m, view);
  const int x0 = std::max(0, int(lo.x)), y0 = std::max(0, int(lo.y));
  const int x1 = std::min(int(size.x), int(hi.x)), y1 = std::min(int(size.y), int(hi.y));
  if (x1 <= x0 || y1 <= y0 || (x1 - x0) * (y1 - y0) > kMaxTexels) return;
  struct Shown {
    glm::ivec2 texel;
    TexelValue value;
  };
  std::vector<Shown> shown;
  float widest = 0.0f;
  size_t tallest = 0;
  for (int y = y0; y < y1; ++y)
    for (int x = x0; x < x1; ++x) {
      std::optional<TexelValue> v = m.texelValue(view, side, {x, y});
      if (!v || v->lines.empty()) continue;
      for (const std::string& line : v->lines) widest = std::max(widest, ImGui::CalcTextSize(line.c_str()).x);
      tallest = std::max(tallest, v->lines.size());
      shown.push_back({{x, y}, std::move(*v)});
    }
  // All or none: values in some texels only would read as values missing from the others.
  if (shown.empty() || widest + 2 * kPad > pl.scale || float(tallest) * lineH + 2 * kPad > pl.scale) return;
  const ViewSettings& s = m.settings[size_t(view)];
  const ViewMapping mapping = viewMapping(def, s);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(ImVec2(float(r.x), float(r.y)), ImVec2(float(r.x + r.w), float(r.y + r.h)), true);
  TexelValuesDrawn drawn{view, side, pl.scale, {}};
  for (const Shown& t : shown) {
    const glm::vec3 colour = mapTexel(def, s, mapping, range, t.value.value, t.value.empty);
    const ImU32 ink = luminance(colour) > 0.35f ? IM_COL32(0, 0, 0, 255) : IM_COL32(255, 255, 255, 255);
    const glm::dvec2 corner = windowAt(pl, glm::dvec2(t.texel));
    const float top = float(corner.y + (pl.scale - double(t.value.lines.size()) * lineH) * 0.5);
    for (size_t k = 0; k < t.value.lines.size(); ++k) {
      const char* line = t.value.lines[k].c_str();
      const float w = ImGui::CalcTextSize(line).x;
      dl->AddText(font, lineH, ImVec2(float(corner.x + (pl.scale - w) * 0.5), top + float(k) * lineH), ink, line);
    }
    drawn.texels.push_back({t.texel, t.value.lines});
  }
  dl->PopClipRect();
  m.texelValuesDrawn.push_back(std::move(drawn));
}

}  // namespace gb
