// The pixel panel: the value under the mouse and the probe's dossier (views/probe.h: the same
// dossier `gblens probe` prints) laid out for reading: colour, G-buffer, positions both ways,
// the shadow-map footprint, the point lights with their contributions, the raw stored values.
#include <imgui.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "renderer/core/layout_json.h"
#include "views/ui/viewer_model.h"

namespace gb {

void ledgerSection(const PixelDossier& d);  // ledger_panel.cpp

// Tables fill the panel: label columns fit their text, value columns share the rest (no clipped text).
static const ImGuiTableFlags kTable = ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp;

// A two-column table whose first column fits its labels and whose second takes the rest.
static bool labelTable(const char* id) {
  if (!ImGui::BeginTable(id, 2, kTable)) return false;
  ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthFixed);
  ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthStretch);
  return true;
}

static std::string f9(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.9g", v);
  return b;
}
static std::string v3(const glm::dvec3& v) { return f9(v.x) + ", " + f9(v.y) + ", " + f9(v.z); }
// Compact numbers for the lights table (the JSON and the stored-values table keep every digit).
static std::string g5(double v) {
  char b[40];
  std::snprintf(b, sizeof b, "%.5g", v);
  return b;
}
static std::string c3(const glm::dvec3& v) { return g5(v.x) + ", " + g5(v.y) + ", " + g5(v.z); }

// A value the user can copy: right-click it.
static void copyable(const char* id, const std::string& value) {
  if (ImGui::BeginPopupContextItem(id)) {
    if (ImGui::MenuItem("Copy value")) ImGui::SetClipboardText(value.c_str());
    ImGui::EndPopup();
  }
}

static void row(const char* label, const std::string& value) {
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextDisabled("%s", label);
  ImGui::TableNextColumn();
  ImGui::TextWrapped("%s", value.c_str());
  copyable(label, value);
}

// A colour swatch of a linear colour (ImGui colours are sRGB-encoded bytes).
static void swatch(const char* id, glm::dvec3 linear) {
  auto enc = [](double v) {
    v = std::clamp(v, 0.0, 1.0);
    return float(v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055);
  };
  ImGui::ColorButton(id, ImVec4(enc(linear.x), enc(linear.y), enc(linear.z), 1.0f), ImGuiColorEditFlags_NoTooltip,
                     ImVec2(14, 14));
  ImGui::SameLine();
}

static void colourSection(const PixelDossier& d) {
  if (!ImGui::CollapsingHeader("Colour", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (d.hasFinal) {
    swatch("final", glm::dvec3(d.finalColor));
    ImGui::Text("final    %s", v3(glm::dvec3(d.finalColor)).c_str());
    if (d.hasHdr) ImGui::TextDisabled("  toneMap(hdr) %s", v3(d.finalExpected).c_str());
  }
  if (d.hasHdr) {
    ImGui::Text("hdr      %s", v3(glm::dvec3(d.hdr)).c_str());
    ImGui::TextDisabled("  expected %s", v3(d.hdrExpected).c_str());
    ImGui::TextDisabled("  residual %s", v3(glm::dvec3(d.hdr) - d.hdrExpected).c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("stored hdr - (directional + point lights), in double from the stored G-buffer;\n"
                        "fairy sprites are not included");
  }
}

static void gbufferSection(const PixelDossier& d) {
  if (!ImGui::CollapsingHeader("G-buffer", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (!d.geometry) ImGui::TextColored(ImVec4(0.6f, 0.8f, 1, 1), "no geometry here (sky)");
  if (!labelTable("gbuffer")) return;
  // What the lighting reads; "-" where the frame's layout has no such quantity (imported frames:
  // the layout quantities above say what they hold).
  row("albedo", d.hasAlbedo ? v3(d.albedo) : "-");
  if (d.hasAlbedo) {
    ImGui::SameLine();
    swatch("albedo", d.albedo);
  }
  row("specular", d.hasAlbedo ? f9(d.specular) : "-");
  row("normal", d.hasNormal ? v3(d.normal) : "-");
  row("|stored| - 1", d.hasNormal ? f9(d.normalLengthError) : "-");
  row("shadow", d.hasNormal ? f9(d.shadow) : "-");
  row("eye depth", d.hasEyeDepth ? f9(d.eyeDepth) : "-");
  row("hardware depth", d.hasHardwareDepth ? f9(d.hardwareDepth) : "-");
  if (d.hasHardwareDepth)
    row("stencil", std::to_string(d.stencil) + ((d.stencil & 0x80) ? " (geometry bit set" : " (geometry bit clear") +
                       ", low bits " + std::to_string(d.stencil & 0x7F) + ")");
  ImGui::EndTable();
}

static void positionSection(const PixelDossier& d) {
  if (!ImGui::CollapsingHeader("Position", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::TextDisabled("the lighting used %s", d.positionSource.c_str());
  if (ImGui::BeginTable("position", 3, kTable)) {
    ImGui::TableSetupColumn("");
    ImGui::TableSetupColumn("from eye depth");
    ImGui::TableSetupColumn("from hardware depth");
    ImGui::TableHeadersRow();
    for (int world = 0; world < 2; ++world) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextDisabled(world ? "world" : "eye");
      for (const ProbePosition* p : {&d.fromEyeDepth, &d.fromHardwareDepth}) {
        ImGui::TableNextColumn();
        if (!p->valid) {
          ImGui::TextDisabled("-");
          continue;
        }
        glm::dvec3 v = world ? p->world : p->eye;
        ImGui::Text("%s\n%s\n%s", f9(v.x).c_str(), f9(v.y).c_str(), f9(v.z).c_str());
      }
    }
    ImGui::EndTable();
  }
  ImGui::Text("difference %s scene units", f9(d.positionDifference).c_str());
  ImGui::Text("eye depth %s ulps, hardware depth %s ulps", f9(d.eyeDepthUlps).c_str(), f9(d.hardwareDepthUlps).c_str());
}

static void shadowSection(const PixelDossier& d) {
  const ProbeShadow& s = d.shadowMap;
  if (!ImGui::CollapsingHeader("Shadow map", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::TextWrapped("%s", s.note.c_str());
  if (!s.valid) return;
  ImGui::Text("receiver depth %s at texel (%s, %s)", f9(s.receiverDepth).c_str(), f9(s.texel.x).c_str(), f9(s.texel.y).c_str());
  ImGui::TextDisabled("bias constant %g, slope %g, clamp %g", s.biasConstant, s.biasSlope, s.biasClamp);
  if (ImGui::BeginTable("shadow", 4, kTable)) {
    for (const char* h : {"texel", "stored depth", "weight", "compare"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (int k = 0; k < 4; ++k) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("%d, %d", s.x0 + (k & 1), s.y0 + (k >> 1));
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(s.outside[k] ? "border (1)" : f9(s.stored[k]).c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(f9(s.weight[k]).c_str());
      ImGui::TableNextColumn();
      if (s.lit[k])
        ImGui::TextColored(ImVec4(1, 0.9f, 0.5f, 1), "lit");
      else
        ImGui::TextColored(ImVec4(0.5f, 0.6f, 1, 1), "shadowed");
    }
    ImGui::EndTable();
  }
  ImGui::Text("filtered %s, stored shadow %s", f9(s.filtered).c_str(), f9(s.storedShadow).c_str());
  ImGui::TextDisabled("nearest texel margin %s (stored - receiver)", f9(s.nearestMargin).c_str());
}

static void lightsSection(const PixelDossier& d) {
  char title[160];
  auto count = [](int64_t v) { return v < 0 ? std::string("n/a") : std::to_string(v); };
  std::snprintf(title, sizeof title, "Point lights: %zu reach the ray, %u shaded###lights", d.lights.size(), d.shadedLights);
  if (!ImGui::CollapsingHeader(title, ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::TextDisabled("coverage_full %s, coverage_masked %s; * near-plane class", count(d.coverageFull).c_str(),
                      count(d.coverageMasked).c_str());
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("the counts the coverage targets stored at this pixel: volumes covering it, and\n"
                      "point-light shader runs; they should equal the lights listed and the lights shaded");
  // The ledger's words for each light's fate (one vocabulary with "Why is this pixel lit").
  auto fateOf = [&](uint32_t index) -> std::string {
    for (const LedgerEntry& e : d.ledger.entries)
      if (e.light == "point" && e.index == index) return e.fate;
    return "";
  };
  if (ImGui::BeginTable("lights", 5, kTable)) {
    for (const char* h : {"light", "d / r", "atten.", "fate", "contribution"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (const ProbeLight& l : d.lights) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      const bool nearPlane = l.lightClass != "stencil";
      ImGui::Text("%u%s", l.index, nearPlane ? "*" : "");
      if (ImGui::IsItemHovered())
        ImGui::SetTooltip("light %u (%s class): eye position %s, radius %s\nthe ray meets its volume at eye depth %s .. %s",
                          l.index, l.lightClass.c_str(), v3(l.eyePosition).c_str(), f9(l.radius).c_str(),
                          f9(l.enter).c_str(), f9(l.exit).c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(g5(l.distance / l.radius).c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(g5(l.attenuation).c_str());
      ImGui::TableNextColumn();
      std::string fate = fateOf(l.index);
      if (fate.empty()) fate = l.stencilPass ? "shaded" : "not shaded";
      if (fate == "shaded")
        ImGui::TextColored(ImVec4(0.4f, 1, 0.4f, 1), "%s", fate.c_str());
      else
        ImGui::TextDisabled("%s", fate.c_str());
      ImGui::TableNextColumn();
      swatch(("c" + std::to_string(l.index)).c_str(), l.color);
      ImGui::TextUnformatted(c3(l.contribution).c_str());
    }
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted("total");
    for (int c = 0; c < 3; ++c) ImGui::TableNextColumn();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(c3(d.pointLightTotal).c_str());
    ImGui::EndTable();
  }
  ImGui::Text("directional + ambient %s", v3(d.directional).c_str());
}

// A multisampled target: each sample's decoded values and bits, then their spread per channel.
static void samplesRows(const ProbeTarget& t) {
  for (size_t k = 0; k < t.samples.size(); ++k) {
    std::string values, bits;
    for (const ProbeChannel& c : t.samples[k]) {
      values += (values.empty() ? "" : ", ") + g5(c.value);
      char b[16];
      std::snprintf(b, sizeof(b), "%s%x", bits.empty() ? "" : " ", c.bits);
      bits += b;
    }
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::Text("  sample %zu", k);
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(values.c_str());
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(bits.c_str());
  }
  if (t.spread.empty()) return;
  std::string spread;
  for (double v : t.spread) spread += (spread.empty() ? "" : ", ") + g5(v);
  ImGui::TableNextRow();
  ImGui::TableNextColumn();
  ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "  spread");
  ImGui::TableNextColumn();
  ImGui::TextUnformatted(spread.c_str());
  ImGui::TableNextColumn();
}

static void storedSection(const PixelDossier& d) {
  // Open from the start where a target is multisampled: its samples are what the probe is for there.
  const bool multi = std::any_of(d.targets.begin(), d.targets.end(), [](const ProbeTarget& t) { return !t.samples.empty(); });
  if (!ImGui::CollapsingHeader("Stored values", multi ? ImGuiTreeNodeFlags_DefaultOpen : 0)) return;
  if (!ImGui::BeginTable("stored", 3, kTable)) return;
  for (const char* h : {"channel", "value", "bits"}) ImGui::TableSetupColumn(h);
  ImGui::TableHeadersRow();
  for (const ProbeTarget& t : d.targets) {
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextColored(ImVec4(0.6f, 0.8f, 1, 1), "%s", t.target.c_str());
    ImGui::TableNextColumn();
    ImGui::TextDisabled("%s", t.present ? (t.type + " " + t.encoding).c_str() : t.absent.c_str());
    ImGui::TableNextColumn();
    for (const ProbeChannel& c : t.channels) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::Text("  %s", c.name.c_str());
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(f9(c.value).c_str());
      ImGui::TableNextColumn();
      ImGui::Text("0x%08x", c.bits);
    }
    samplesRows(t);
  }
  ImGui::EndTable();
}

// Every quantity of the frame's layout, decoded as its views show it (values in its own space and
// units), and every position the layout allows with its distance to a stored one.
static void quantitiesSection(const PixelDossier& d) {
  if (!ImGui::CollapsingHeader("Quantities (the layout's)", ImGuiTreeNodeFlags_DefaultOpen)) return;
  if (labelTable("quantities")) {
    for (const ProbeQuantity& q : d.quantities) {
      std::string v;
      for (double x : q.values) v += (v.empty() ? "" : ", ") + g5(x);
      std::string text = !q.present ? "-" : v.empty() ? q.note : q.space + "  " + v + (q.note.empty() ? "" : "  (" + q.note + ")");
      if (q.eyeDepth && q.kind == "depth" && q.encoding != "eye") text += "  eye depth " + g5(*q.eyeDepth);
      row(q.name.c_str(), text);
      if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s.%s: %s, %s", q.target.c_str(), q.name.c_str(), q.kind.c_str(), q.encoding.c_str());
      for (size_t k = 0; k < q.sampleValues.size(); ++k) {  // a multisampled target: each sample decoded
        std::string sv;
        for (double x : q.sampleValues[k]) sv += (sv.empty() ? "" : ", ") + g5(x);
        row(("  sample " + std::to_string(k)).c_str(), sv.empty() ? q.sampleNotes[k] : sv + (q.sampleNotes[k].empty() ? "" : "  (" + q.sampleNotes[k] + ")"));
      }
    }
    ImGui::EndTable();
  }
  for (const ProbeReconstruction& r : d.reconstructions) {
    if (!r.valid) continue;
    ImGui::TextWrapped("%s (%s): eye %s | %s %s", r.quantity.c_str(), r.method.c_str(), c3(r.eye).c_str(),
                       r.worldSpace.c_str(), c3(r.world).c_str());
    if (r.hasStored)
      ImGui::TextWrapped("  to the stored position: %s units, %s %s ulps", g5(r.toStored).c_str(), g5(r.toStoredUlps).c_str(),
                         r.ulpOf.c_str());
  }
  if (!d.lightingNote.empty()) ImGui::TextWrapped("lighting: %s", d.lightingNote.c_str());
}

static void dossierSections(const PixelDossier& d) {
  if (!d.missing.empty()) {
    std::string missing;
    for (const std::string& s : d.missing) missing += (missing.empty() ? "" : ", ") + s;
    ImGui::TextColored(ImVec4(1, 0.6f, 0.3f, 1), "missing: %s", missing.c_str());
  }
  // Another renderer's G-buffer: its own quantities; gblens's frame also its lighting's view of it.
  if (d.native) colourSection(d);
  quantitiesSection(d);
  if (d.native) {
    gbufferSection(d);
    positionSection(d);
    shadowSection(d);
  }
  if (d.native || d.lightingNote.empty()) {
    ledgerSection(d);
    lightsSection(d);
  }
  storedSection(d);
}

void referenceSection(ViewerModel& m);  // reference_panel.cpp
void trackSection(ViewerModel& m);      // track_panel.cpp: a sequence's probe across its frames
void compareDossiers(ViewerModel& m);   // compare_panel.cpp

// The clicked shadow-map texel: how many pixels read it, where (zoom to them), or why none do.
static void shadowMarkLine(ViewerModel& m) {
  const ImVec4 magenta(1, 0, 1, 1);
  const glm::ivec2 t = *m.shadowMark;
  char line[256];
  if (!m.shadowMarks) {
    std::snprintf(line, sizeof line, "marked: pixels reading shadow texel (%d, %d): %s", t.x, t.y,
                  m.shadowMarkNote.empty() ? "counting" : m.shadowMarkNote.c_str());
  } else if (m.shadowMarks->pixels > 0) {
    const RegionRect& b = *m.shadowMarks->box;
    std::snprintf(line, sizeof line, "marked: %lld pixels read shadow texel (%d, %d), within %u,%u %ux%u",
                  (long long)m.shadowMarks->pixels, t.x, t.y, b.x, b.y, b.width, b.height);
  } else {
    std::snprintf(line, sizeof line, "marked: 0 pixels read shadow texel (%d, %d): %s", t.x, t.y, m.shadowMarkNote.c_str());
  }
  // Wrapped to the panel, the buttons below: nothing cut off at the panel's edge.
  ImGui::PushStyleColor(ImGuiCol_Text, magenta);
  ImGui::TextWrapped("%s", line);
  ImGui::PopStyleColor();
  if (m.shadowMarks && m.shadowMarks->pixels > 0) {
    if (ImGui::SmallButton("zoom to marks (M)")) zoomToShadowMarks(m);
    ImGui::SameLine();
  }
  if (ImGui::SmallButton("clear mark")) m.shadowMark.reset();
}

void drawDossier(ViewerModel& m) {
  // The readout under the mouse keeps a fixed height, so what follows (the dossier, its buttons)
  // does not move as the mouse goes from pixel to pixel.
  // A compare's readout holds A's line, B's and their difference, each wrapped to two lines.
  const float lines = m.source == FrameSource::Compare ? 7.5f : 4.5f;
  ImGui::BeginChild("hover", ImVec2(0, ImGui::GetTextLineHeightWithSpacing() * lines), false, ImGuiWindowFlags_NoScrollbar);
  if (m.hover)
    ImGui::Text("mouse (%d, %d)", m.hover->x, m.hover->y);
  else if (m.hoverShadowTexel)
    ImGui::Text("shadow-map texel (%d, %d)", m.hoverShadowTexel->x, m.hoverShadowTexel->y);
  else
    ImGui::TextDisabled("mouse outside the image");
  if (!m.hoverText.empty()) ImGui::TextWrapped("%s", m.hoverText.c_str());
  ImGui::EndChild();
  if (m.shadowMark) shadowMarkLine(m);
  ImGui::Separator();
  if (!m.probePixel || !m.dossier) {
    // Another renderer's frame has only its layout's quantities: no shadow map or lights to promise.
    if (gblensLayout(m.frameLayout))
      ImGui::TextWrapped("Click a pixel (or use the arrow keys) for its dossier: stored values of every target, "
                         "reconstructed positions, the shadow-map texels, the point lights that reach it.");
    else
      ImGui::TextWrapped("Click a pixel (or use the arrow keys) for its dossier: the stored texels of every target, "
                         "each quantity of the layout decoded, positions reconstructed from depth.");
    return;
  }
  const PixelDossier& d = *m.dossier;
  ImGui::Text("pixel (%d, %d) of %ux%u", m.probePixel->x, m.probePixel->y, d.width, d.height);
  ImGui::SameLine();
  if (ImGui::SmallButton("Copy as JSON")) m.copyJson = true;
  if (m.copiedBytes && ImGui::GetTime() - m.copiedAt < 3.0) {  // the confirmation, for a few seconds
    ImGui::SameLine();
    ImGui::TextColored(ImVec4(0.4f, 1, 0.4f, 1), "copied (%zu bytes)", m.copiedBytes);
    m.uiChanged = true;  // keep drawing until it goes
  }
  ImGui::TextDisabled("dossier ready %.1f ms after the click", m.probeLatencyMs);
  if (!m.probeNote.empty()) ImGui::TextColored(ImVec4(1, 0.75f, 0.3f, 1), "%s", m.probeNote.c_str());
  if (!m.probeError.empty()) {
    ImGui::TextColored(ImVec4(1, 0.4f, 0.4f, 1), "%s", m.probeError.c_str());
    return;
  }
  if (!m.dossierB) {
    trackSection(m);
    ImGui::BeginChild("dossier");
    if (gblensLayout(m.frameLayout)) referenceSection(m);  // another renderer's frame has no scene to trace
    dossierSections(d);
    ImGui::EndChild();
    return;
  }
  compareDossiers(m);  // compare: one table, A beside B, the values that differ marked
}

}  // namespace gb
