// The legends of the view area (view_legends.cpp): each drawn into `dl` with its ramp's left end
// at `at`, `width` pixels wide.
#pragma once
#include <imgui.h>

#include <string>
#include <vector>

#include "views/ui/viewer_model.h"

namespace gb {

// The heat ramp of views/visualize.cpp from 0 to `maxCount`, titled `unit`.
void heatLegend(ImDrawList* dl, ImVec2 at, float width, float maxCount, const char* unit);
// A grey or false-colour mapping's ramp from its black to its white point, titled `unit`.
void rampLegend(ImDrawList* dl, ImVec2 at, float width, const ViewMapping& mapping, const ResolvedRange& r,
                const std::string& unit);
// FLIP's magma from 0 to 1.
void magmaLegend(ImDrawList* dl, ImVec2 at, float width);
// An id view's classes: a swatch of each value's id colour (0: black) and its name, in a row titled `title`.
void classLegend(ImDrawList* dl, ImVec2 at, float width, const std::string& title, const std::vector<std::string>& names);
// `text` wrapped to `width` at the bottom of the view rectangle `r`.
void textLegend(ImDrawList* dl, const Rect& r, float width, const std::string& text);

}  // namespace gb
