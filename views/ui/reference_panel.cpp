// The Pixel panel's reference section: the ray-traced double-precision reference at the probed
// pixel beside the G-buffer's values (views/analysis/probe_reference.h), on request.
#include <imgui.h>

#include "views/ui/viewer_model.h"

namespace gb {

void referenceSection(ViewerModel& m) {
  if (!ImGui::CollapsingHeader("Reference (ray traced, double)", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (ImGui::Checkbox("compare this pixel with the reference", &m.probeReference) && m.probePixel)
    m.probeRequest = m.probePixel;  // probe again, with (or without) it
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("Casts the pixel-centre ray through the scene in double (Embree), shades it with the scene's\n"
                      "lights, and measures the G-buffer against it as `gblens error` does (gblens probe --reference).");
  if (!m.probeReference) return;
  if (!m.reference) {
    ImGui::TextDisabled("%s", m.referenceNote.empty() ? "probe a pixel" : m.referenceNote.c_str());
    return;
  }
  const ReferencePixel& r = *m.reference;
  const reference::Surface& s = r.surface;
  if (!s.hit) {
    ImGui::Text("no surface (sky)");
  } else {
    ImGui::Text("normal    %.7f %.7f %.7f", s.normal.x, s.normal.y, s.normal.z);
    ImGui::Text("eye depth %.9g", s.eyeDepth);
    ImGui::Text("world     %.7g %.7g %.7g", s.world.x, s.world.y, s.world.z);
    ImGui::Text("albedo    %.5f %.5f %.5f  specular %.4g", s.albedo.x, s.albedo.y, s.albedo.z, s.specular);
    ImGui::Text("sun       %s   primitive_id %u", s.sunVisible < 0 ? "not evaluated" : s.sunVisible ? "reached" : "blocked",
                s.primitiveId);
    ImGui::Text("hdr       %.6g %.6g %.6g", r.hdr.x, r.hdr.y, r.hdr.z);
  }
  if (r.compared) {
    ImGui::TextUnformatted("G-buffer against the reference:");
    ImGui::Text("  normal %.3g deg, eye depth %.3g relative", r.normalDeg, r.eyeDepthRelative);
    ImGui::Text("  position %.3g relative, hdr %.3g relative", r.positionRelative, r.hdrRelative);
    ImGui::Text("  shadow ");
    ImGui::SameLine(0, 0);
    if (r.shadowDiffers)
      ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "differs");
    else
      ImGui::TextUnformatted("agrees");
  }
  if (!r.note.empty()) ImGui::TextWrapped("%s", r.note.c_str());
  ImGui::TextDisabled("reference %.1f ms", m.referenceMs);
}

}  // namespace gb
