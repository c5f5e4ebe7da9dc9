// The mouse over one view slot of the view area (views/ui/view_input.cpp).
#pragma once
#include "views/ui/view_layout.h"
#include "views/ui/viewer_model.h"

namespace gb {

// The slot the mouse is over: its view, rectangle and whether it is a swipe (A | B).
struct MouseSlot {
  int view = 0;
  Rect rect;
  bool split = false;
};

// Hover, wheel zoom (ctrl: dolly), the swipe following the mouse or its handle dragged, click or drag
// to probe (a shadow-map click marks a texel), ctrl drag to select a region, middle or shift drag to
// pan, right drag to turn the camera; `hovered` and `active` as ImGui says of the slot's button.
void handleViewMouse(ViewerModel& m, const MouseSlot& v, const Placement& pl, bool hovered, bool active);

}  // namespace gb
