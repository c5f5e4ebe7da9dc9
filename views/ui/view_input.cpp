// The mouse over one view slot (view_panel.cpp draws the slot, this answers the mouse): hover, wheel
// zoom, the swipe, probing, region selection, pan and the camera drag.
#include "views/ui/view_input.h"

#include <imgui.h>

#include <algorithm>
#include <cmath>

namespace gb {

// Ctrl + left drag: the region's first corner at the press, the rectangle to the texel under the
// mouse while it moves (both corners included, clamped to the frame), the statistics on release.
static void selectRegion(ViewerModel& m, glm::uvec2 size, glm::ivec2 texel) {
  texel = glm::clamp(texel, glm::ivec2(0), glm::ivec2(size) - 1);
  if (ImGui::IsItemClicked(ImGuiMouseButton_Left) || !m.regionAnchor) m.regionAnchor = texel;
  const glm::ivec2 lo = glm::min(*m.regionAnchor, texel), hi = glm::max(*m.regionAnchor, texel);
  m.region = RegionRect{uint32_t(lo.x), uint32_t(lo.y), uint32_t(hi.x - lo.x + 1), uint32_t(hi.y - lo.y + 1)};
  if (!ImGui::IsMouseDown(ImGuiMouseButton_Left)) {
    m.regionAnchor.reset();
    m.regionDirty = true;
  }
  m.uiChanged = true;
}

// The mouse over the slot's button: hover, wheel zoom (ctrl: dolly), the split handle, click or
// drag to probe (a shadow-map click marks a texel), ctrl drag to select a region, middle or shift
// drag to pan, right drag to turn the camera.
void handleViewMouse(ViewerModel& m, const MouseSlot& v, const Placement& pl, bool hovered, bool active) {
  ImGuiIO& io = ImGui::GetIO();
  const Rect& r = v.rect;
  const glm::uvec2 size = viewImageSize(m, v.view);
  const bool shadowMap = m.views[size_t(v.view)].sun;
  glm::dvec2 mouse(io.MousePos.x, io.MousePos.y);
  glm::dvec2 t = texelAt(pl, mouse);
  bool inside = t.x >= 0 && t.y >= 0 && t.x < size.x && t.y < size.y;
  glm::ivec2 texel(int(std::floor(t.x)), int(std::floor(t.y)));
  if (hovered) {
    m.hoverView = v.view;
    if (inside && !shadowMap) m.hover = texel;
    if (inside && shadowMap) m.hoverShadowTexel = texel;
    if (io.MouseWheel != 0.0f) {
      if (io.KeyCtrl)
        m.cameraDolly += io.MouseWheel;
      else
        zoomAbout(m.transform, r, size.x, size.y, mouse, std::pow(1.25, double(io.MouseWheel)));
      m.uiChanged = true;
    }
  }
  if (v.split && ImGui::IsItemClicked(ImGuiMouseButton_Left) && std::abs(mouse.x - (r.x + r.w * m.splitAt)) < 8.0)
    m.draggingSplit = true;
  // The swipe follows the mouse over the slot (as the review page's does); a button held pans,
  // probes or drags instead.
  if (v.split && hovered && !ImGui::IsAnyMouseDown() && !m.draggingSplit) {
    const float at = float(std::clamp((mouse.x - r.x) / std::max(r.w, 1.0), 0.0, 1.0));
    if (at != m.splitAt) m.splitAt = at, m.uiChanged = true;
  }
  if (m.draggingSplit) {
    if (active && ImGui::IsMouseDown(ImGuiMouseButton_Left))
      m.splitAt = float(std::clamp((mouse.x - r.x) / std::max(r.w, 1.0), 0.0, 1.0));
    else
      m.draggingSplit = false;
    m.uiChanged = true;
  } else if (io.KeyCtrl && !shadowMap && (ImGui::IsItemClicked(ImGuiMouseButton_Left) || m.regionAnchor)) {
    selectRegion(m, size, texel);
  } else if (ImGui::IsItemClicked(ImGuiMouseButton_Left) || (active && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f) &&
                                                       io.MouseDelta.x + io.MouseDelta.y != 0.0f && !io.KeyShift)) {
    m.edited = v.view;
    if (inside && shadowMap) {
      if (ImGui::IsItemClicked(ImGuiMouseButton_Left))
        m.shadowMark = m.shadowMark && *m.shadowMark == texel ? std::nullopt : std::optional<glm::ivec2>(texel);
    } else if (inside && (!m.probePixel || *m.probePixel != texel)) {
      m.probeRequest = texel;
    }
    m.uiChanged = true;
  }
  if (active && (ImGui::IsMouseDragging(ImGuiMouseButton_Middle, 0.0f) ||
                 (io.KeyShift && ImGui::IsMouseDragging(ImGuiMouseButton_Left, 0.0f)))) {
    panBy(m.transform, r, size.x, size.y, glm::dvec2(io.MouseDelta.x, io.MouseDelta.y));
    m.uiChanged = true;
  }
  if (active && ImGui::IsMouseDragging(ImGuiMouseButton_Right, 0.0f))
    m.cameraDrag += glm::dvec2(io.MouseDelta.x, io.MouseDelta.y);
}

}  // namespace gb
