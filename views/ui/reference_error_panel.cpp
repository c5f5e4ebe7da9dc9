// The "Reference error" window: the maps `gblens error -o` writes (views/analysis/error.h
// errorMaps), computed for the live frame on request while the viewer stays responsive; the map
// is drawn through the view pipeline from the app's reference renderer (FrameSide::Reference).
#include <imgui.h>

#include <algorithm>

#include "views/analysis/decompose.h"
#include "views/analysis/error.h"
#include "views/ui/view_params.h"
#include "views/ui/viewer_model.h"

namespace gb {

static void queueMap(ViewerModel& m, ViewDrawCallback callback, std::vector<ViewDraw>& draws) {
  const auto& e = m.referenceError;
  const ImVec2 avail = ImGui::GetContentRegionAvail(), at = ImGui::GetCursorScreenPos();
  if (avail.x < 8 || avail.y < 8 || e.width == 0) return;
  const double scale = std::min(avail.x / double(e.width), avail.y / double(e.height));
  const ImGuiIO& io = ImGui::GetIO();
  Placement fb{at.x * io.DisplayFramebufferScale.x, at.y * io.DisplayFramebufferScale.y, scale * io.DisplayFramebufferScale.x};
  // Error maps are sRGB colour images held as `final`; decomposition terms linear colour in `hdr`
  // drawn from 0 to their largest value; the light count as a heat map in `coverage_full`.
  ViewDef def;
  def.name = "reference";
  def.visual = e.mapping;
  def.components = e.mapping == Visual::Count ? 1 : 3;
  def.integer = e.mapping == Visual::Count;
  def.channels = e.mapping == Visual::Count ? 0x1 : 0x7;
  ResolvedRange range;
  if (e.mapping != Visual::Color || !e.srgbMap) range.black = 0.0f, range.white = std::max(e.white, 1e-30f);
  ViewGpuSource src;
  src.decoded = false;
  ViewDraw vd;
  vd.referenceTarget = e.mapping == Visual::Count ? Target::CoverageFull : e.srgbMap ? Target::Final : Target::Hdr;
  vd.side = FrameSide::Reference;
  vd.params = viewParams(def, defaultSettings(def), src, range, fb, false, std::nullopt, {1, 1});
  const float w = float(e.width * scale), h = float(e.height * scale);
  vd.rect = {fb.originX, fb.originY, w * io.DisplayFramebufferScale.x, h * io.DisplayFramebufferScale.y};
  draws.push_back(vd);
  ImDrawList* dl = ImGui::GetWindowDrawList();
  dl->PushClipRect(at, ImVec2(at.x + w, at.y + h), true);
  dl->AddCallback(callback, reinterpret_cast<void*>(intptr_t(draws.size() - 1)));
  dl->AddCallback(ImDrawCallback_ResetRenderState, nullptr);
  dl->PopClipRect();
  ImGui::Dummy(ImVec2(w, h));
}

void referenceErrorWindow(ViewerModel& m, ViewDrawCallback callback, std::vector<ViewDraw>& draws) {
  auto& e = m.referenceError;
  if (!e.open) return;
  ImGui::SetNextWindowSize(ImVec2(560, 420), ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Reference error", &e.open)) {
    ImGui::End();
    return;
  }
  if (m.source != FrameSource::Live) {
    ImGui::TextWrapped("The reference needs the scene: live frames only (gblens error SCENE -o DIR for others).");
    ImGui::End();
    return;
  }
  const std::vector<ErrorMapDef>& maps = errorMaps();
  auto label = [&](size_t i) {
    return i < maps.size() ? std::string("error: ") + maps[i].name
                           : std::string("decomposition: ") + name(LightingTerm(i - maps.size()));
  };
  ImGui::SetNextItemWidth(220);
  if (ImGui::BeginCombo("map", label(size_t(e.map)).c_str())) {
    for (size_t i = 0; i < maps.size() + kLightingTermCount; ++i)
      if (ImGui::Selectable(label(i).c_str(), int(i) == e.map)) e.map = int(i), e.mapChanged = true;
    ImGui::EndCombo();
  }
  ImGui::SameLine();
  if (e.computing) {
    ImGui::Text("computing the reference... %.1f s", e.seconds);
  } else if (ImGui::Button(e.ready ? "Recompute for this frame" : "Compute for this frame")) {
    e.computeRequested = true;
  }
  if (!e.error.empty()) ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", e.error.c_str());
  if (!e.ready) {
    ImGui::TextWrapped("The maps of gblens error -o for the frame on screen (fairy sprites off, primitive_id on, as "
                       "gblens error renders it), against the double-precision ray-traced reference, and the lighting "
                       "decomposition of gblens decompose. It takes seconds on a CPU device; the viewer stays usable "
                       "meanwhile.");
    ImGui::End();
    return;
  }
  if (e.stale) ImGui::TextColored(ImVec4(1, 0.7f, 0.3f, 1), "stale: the frame changed since (recompute)");
  if (size_t(e.map) < maps.size())
    ImGui::TextWrapped("%s", maps[size_t(e.map)].legend);
  else if (!e.decomposeNote.empty())
    ImGui::TextWrapped("%s", e.decomposeNote.c_str());
  else
    ImGui::TextWrapped("%s from the G-buffer with shading.h in double (gblens decompose), drawn 0 .. %.4g",
                       name(LightingTerm(size_t(e.map) - maps.size())), e.white);
  ImGui::TextDisabled("%s (%.1f s)", e.summary.c_str(), e.seconds);
  queueMap(m, callback, draws);
  ImGui::End();
}

}  // namespace gb
