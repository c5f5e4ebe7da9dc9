// The viewer's panels (ImGui only): menu bar, controls (views, frame options, lights,
// animation, camera, statistics, capture), the pixel panel with the probe's dossier, status bar.
#include <imgui.h>

#include <algorithm>
#include <cstdio>

#include "views/ui/keys.h"
#include "views/ui/fitted_text.h"
#include "views/ui/viewer_model.h"

namespace gb {

void drawViewArea(ViewerModel& m, const Rect& area, ViewDrawCallback callback, std::vector<ViewDraw>& draws);
void drawDossier(ViewerModel& m);  // probe_panel.cpp
void referenceErrorSection(ViewerModel& m);  // reference_error_panel.cpp
void compareControls(ViewerModel& m);        // compare_panel.cpp
void compareTabs(ViewerModel& m);
void drawRegion(ViewerModel& m);   // region_panel.cpp
void attachMenu(ViewerModel& m);   // attach_panel.cpp (gblens attach)
void attachSection(ViewerModel& m);
std::string attachStatusLine(const ViewerModel& m);
void attachSuggestionWindow(ViewerModel& m);
double timelineHeight(const ViewerModel& m);  // timeline_panel.cpp (a sequence's frames)
void drawTimeline(ViewerModel& m, double x, double y, double w);

static constexpr double kMenuHeight = 20.0, kStatusHeight = 22.0, kControlsWidth = 310.0, kPixelWidth = 450.0;
static constexpr double kTextLine = 13.0;  // the default font's line

// A compare's status bar has room for its hover's three lines (A, B, their difference) at all times,
// so the views do not move as the mouse enters them.
static double statusHeight(const ViewerModel& m) { return kStatusHeight + (m.source == FrameSource::Compare ? 2 * kTextLine : 0.0); }

// Panels keep their width until the window gets narrow; then they give way to the views.
static double controlsWidth(const ViewerModel& m, double w) { return m.showControls ? std::min(kControlsWidth, 0.25 * w) : 0.0; }
static double pixelWidth(const ViewerModel& m, double w) {
  if (!m.showPixel) return 0.0;
  return std::min(m.source == FrameSource::Compare ? 1.5 * kPixelWidth : kPixelWidth, 0.35 * w);
}

Rect viewArea(const ViewerModel& m, double w, double h) {
  double left = controlsWidth(m, w), right = pixelWidth(m, w);
  return {left, kMenuHeight, std::max(1.0, w - left - right), std::max(1.0, h - kMenuHeight - statusHeight(m) - timelineHeight(m))};
}

static void tooltip(const char* text) {
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("%s", text);
}

// A view's entry in menus and lists: its key (if any) and name, with why it is unavailable.
static std::string viewItem(const ViewerModel& m, size_t k) {
  const ViewDef& d = m.views[k];
  std::string item = d.name + "  (" + name(d.kind) + ")";
  if (!m.unavailable[k].empty()) item += "  - " + m.unavailable[k];
  return item;
}

static bool viewCombo(const ViewerModel& m, const char* label, int& v) {
  bool changed = false;
  if (m.views.empty()) return false;
  if (ImGui::BeginCombo(label, m.views[size_t(v)].name.c_str())) {
    for (size_t k = 0; k < m.views.size(); ++k) {
      std::string item = viewItem(m, k) + (m.views[k].key.empty() ? "" : "  " + m.views[k].key);
      if (ImGui::Selectable(item.c_str(), v == int(k))) {
        v = int(k);
        changed = true;
      }
    }
    ImGui::EndCombo();
  }
  return changed;
}

// Help: the keys of this frame's views (from its layout), then the session's rows of the key table
// (views/ui/keys.h: the same table the key handler dispatches through and the README shows), as a
// two-column table whose descriptions wrap within the window (nothing runs off its edge).
static void helpMenu(const ViewerModel& m) {
  std::string keys = "Views: 1 grid";
  for (const ViewDef& d : m.views)
    if (!d.key.empty()) keys += (d.key == "0" ? ", 0 / Return " : ", " + d.key + " ") + d.name;
  const unsigned session = keySession(m);
  const float width = std::min(900.0f, ImGui::GetIO().DisplaySize.x - 40.0f);
  ImGui::PushTextWrapPos(ImGui::GetCursorPosX() + width);
  ImGui::TextUnformatted(keys.c_str());
  ImGui::PopTextWrapPos();
  ImGui::Separator();
  if (!ImGui::BeginTable("keys", 2, ImGuiTableFlags_SizingFixedFit, ImVec2(width, 0.0f))) return;
  ImGui::TableSetupColumn("input", ImGuiTableColumnFlags_WidthFixed);
  ImGui::TableSetupColumn("does", ImGuiTableColumnFlags_WidthStretch);
  for (const KeyBinding& k : keyBindings()) {
    if (!(k.sessions & session)) continue;
    ImGui::TableNextRow();
    ImGui::TableNextColumn();
    ImGui::TextUnformatted(k.keys);
    ImGui::TableNextColumn();
    ImGui::TextWrapped("%s", k.does);
  }
  ImGui::EndTable();
}

static void menuBar(ViewerModel& m) {
  if (!ImGui::BeginMainMenuBar()) return;
  if (ImGui::BeginMenu("View")) {
    if (ImGui::MenuItem("All views (grid)", "1", m.layout == LayoutMode::Grid)) m.layout = LayoutMode::Grid;
    for (size_t k = 0; k < m.views.size(); ++k) {
      const ViewDef& d = m.views[k];
      if (ImGui::MenuItem(viewItem(m, k).c_str(), d.key.c_str(), m.layout != LayoutMode::Grid && m.primary == int(k))) {
        m.primary = m.edited = int(k);
        if (m.layout == LayoutMode::Grid) m.layout = LayoutMode::Single;
      }
    }
    ImGui::Separator();
    if (ImGui::BeginMenu("Side by side with")) {
      for (size_t k = 0; k < m.views.size(); ++k)
        if (ImGui::MenuItem(viewItem(m, k).c_str(), nullptr, m.layout == LayoutMode::SideBySide && m.secondary == int(k))) {
          m.secondary = int(k);
          m.layout = LayoutMode::SideBySide;
        }
      ImGui::EndMenu();
    }
    if (ImGui::MenuItem("Single view", nullptr, m.layout == LayoutMode::Single)) m.layout = LayoutMode::Single;
    ImGui::Separator();
    ImGui::MenuItem("Texel grid when zoomed in", "G", &m.grid);
    if (ImGui::MenuItem("Fit", "Z")) m.transform = ViewTransform{};
    ImGui::MenuItem("Controls panel", nullptr, &m.showControls);
    ImGui::MenuItem("Pixel panel", nullptr, &m.showPixel);
    if (m.source == FrameSource::Live &&
        ImGui::MenuItem("Compute the reference error", nullptr, false, !m.referenceError.computing))
      m.referenceError.computeRequested = true;
    ImGui::EndMenu();
  }
  if (m.source == FrameSource::Live && ImGui::BeginMenu("Camera")) {
    if (ImGui::MenuItem("Reset", "Home")) m.resetCamera = true;
    for (size_t i = 0; i < m.cameraNames.size(); ++i)
      if (ImGui::MenuItem(m.cameraNames[i].c_str())) m.gltfCamera = int(i);
    ImGui::EndMenu();
  }
  attachMenu(m);
  if (ImGui::BeginMenu("Help")) {
    helpMenu(m);
    ImGui::EndMenu();
  }
  ImGui::EndMainMenuBar();
}

// The visualisation's own controls: exposure (HDR colour), false colour and log (depth, scalars),
// the stencil bits (named by the layout), the distance to the eye (positions).
static void visualControls(ViewerModel& m, const ViewDef& d, ViewSettings& s) {
  if (d.visual == Visual::Color) {
    ImGui::SetNextItemWidth(160);
    ImGui::SliderFloat("exposure (EV)", &s.exposure, -10.0f, 10.0f, "%+.1f");
    tooltip("colour shown = stored linear colour x 2^EV, then sRGB-encoded");
  }
  const ViewMapping mapping = viewMapping(d, s);
  if (mapping.mapping == gpu::kViewMapGrey || mapping.mapping == gpu::kViewMapDepth) {
    ImGui::Checkbox("false colour", &s.falseColor);
    tooltip("viridis (perceptually uniform) instead of grey");
    ImGui::SameLine();
    ImGui::Checkbox("log", &s.log);
    tooltip("logarithmic between black and white (both must be positive)");
  }
  if (d.visual == Visual::Position) ImGui::Checkbox("distance to the eye", &s.distance);
  if (d.visual == Visual::Stencil && d.quantity >= 0 && !m.frameLayout.quantities[size_t(d.quantity)].stencilBits.empty()) {
    const auto& bits = m.frameLayout.quantities[size_t(d.quantity)].stencilBits;
    ImGui::TextUnformatted("bits");
    for (const auto& [bitName, mask] : bits) {
      bool on = (s.stencilBits & mask) != 0;
      ImGui::SameLine();
      if (ImGui::Checkbox(bitName.c_str(), &on)) s.stencilBits = on ? s.stencilBits | mask : s.stencilBits & ~mask;
    }
    ImGui::SameLine();
    if (ImGui::SmallButton("all")) s.stencilBits = 0;
  }
}

static void viewSettings(ViewerModel& m) {
  if (m.views.empty()) return;
  ImGui::TextUnformatted("Layout");
  ImGui::SameLine();
  int layout = int(m.layout);
  ImGui::RadioButton("one", &layout, int(LayoutMode::Single));
  ImGui::SameLine();
  ImGui::RadioButton("two", &layout, int(LayoutMode::SideBySide));
  ImGui::SameLine();
  ImGui::RadioButton("grid", &layout, int(LayoutMode::Grid));
  m.layout = LayoutMode(layout);
  if (viewCombo(m, "view", m.primary)) m.edited = m.primary;
  if (m.layout == LayoutMode::SideBySide && viewCombo(m, "beside", m.secondary)) m.edited = m.secondary;
  ImGui::Separator();
  viewCombo(m, "settings of", m.edited);
  const ViewDef& d = m.views[size_t(m.edited)];
  ViewSettings& s = m.settings[size_t(m.edited)];
  if (!d.space.empty()) {  // wrapped: a map's space can be a sentence
    ImGui::PushStyleColor(ImGuiCol_Text, ImGui::GetStyle().Colors[ImGuiCol_TextDisabled]);
    ImGui::TextWrapped("%s", d.space.c_str());
    ImGui::PopStyleColor();
  }
  for (int c = 0; c < int(d.componentNames.size()) && d.components > 1; ++c) {
    bool on = s.channels & (1u << c);
    if (c) ImGui::SameLine();
    if (ImGui::Checkbox(d.componentNames[size_t(c)].c_str(), &on)) s.channels = on ? s.channels | (1u << c) : s.channels & ~(1u << c);
    tooltip(componentLabel(d, c).c_str());
  }
  visualControls(m, d, s);
  if (d.visual != Visual::Id && d.visual != Visual::Stencil) {
    ImGui::Checkbox("auto range", &s.autoRange);
    tooltip("black and white point from the data: min/max over the texels that hold a value");
    if (s.autoRange) ImGui::BeginDisabled();
    float range[2] = {s.black, s.white};
    if (ImGui::DragFloat2("black/white", range, std::max(1e-4f, (s.white - s.black) * 0.005f), 0, 0, "%.5g")) {
      s.black = range[0];
      s.white = range[1];
    }
    if (s.autoRange) {
      ImGui::EndDisabled();
      ResolvedRange r = resolveRange(d, s, &m.ranges[size_t(m.edited)]);
      if (r.fromData) {
        ImGui::Text("data: %.7g .. %.7g", r.stats.lo, r.stats.hi);
        ImGui::SameLine();
        if (ImGui::SmallButton("keep")) {  // start a manual range from the data's
          s.autoRange = false;
          s.black = r.black;
          s.white = r.white;
        }
      }
    }
  }
  if (ImGui::SmallButton("reset view settings")) s = defaultSettings(d);
  ImGui::Checkbox("NaN/Inf", &s.specials);
  ImGui::SameLine();
  ImGui::Checkbox("negative", &s.negative);
  ImGui::ColorButton("NaN", ImVec4(1, 0, 1, 1), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
  ImGui::SameLine();
  ImGui::TextUnformatted("NaN");
  ImGui::SameLine();
  ImGui::ColorButton("Inf", ImVec4(0, 1, 1, 1), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
  ImGui::SameLine();
  ImGui::TextUnformatted("Inf");
  ImGui::SameLine();
  ImGui::ColorButton("neg", ImVec4(1, 0.35f, 0, 1), ImGuiColorEditFlags_NoTooltip, ImVec2(12, 12));
  ImGui::SameLine();
  ImGui::TextUnformatted(d.negativeSuspicious ? "negative" : "negative (not flagged here)");
  ImGui::Checkbox("texel grid", &m.grid);
  ImGui::SameLine();
  ImGui::Checkbox("values in texels", &m.texelValues);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("zoomed in far enough, each texel shows its value (captures)");
  // The zoom as what it is on screen: window pixels per texel of the first view (and the fit's factor).
  if (m.texelScale >= 1.0)
    ImGui::Text("%.4g px per texel (%.3gx fit)", m.texelScale, m.transform.zoom);
  else if (m.texelScale > 0.0)
    ImGui::Text("1 px per %.3g texels (%.3gx fit)", 1.0 / m.texelScale, m.transform.zoom);
  ImGui::SameLine();
  if (ImGui::SmallButton("fit")) m.transform = ViewTransform{};
}

static void frameOptions(ViewerModel& m) {
  RenderOptions& o = m.wanted;
  int path = int(o.path);
  ImGui::RadioButton("two-pass", &path, int(Path::TwoPass));
  ImGui::SameLine();
  ImGui::RadioButton("single-pass", &path, int(Path::SinglePass));
  o.path = Path(path);
  ImGui::Checkbox("USE_EYE_DEPTH", &o.eyeDepth);
  tooltip("positions from the eye-depth target (on) or hardware depth through eyeFromClip (off)");
  // Stencil culling is the deferred method's: under tiled, clustered or forward it does nothing, and
  // the panel says so instead of offering controls without effect.
  const bool deferred = m.stats.method.empty() || m.stats.method == "deferred";
  if (!deferred) {
    ImGui::TextDisabled("LIGHT_STENCIL_CULLING: deferred only (this frame ran %s)", m.stats.method.c_str());
  } else {
    ImGui::Checkbox("LIGHT_STENCIL_CULLING", &o.stencilCulling);
  }
  if (deferred && o.stencilCulling) {
    int mask = int(o.stencilMask);
    ImGui::TextDisabled("  stencil mask");
    ImGui::SameLine();
    ImGui::RadioButton("per-light", &mask, int(StencilMask::PerLight));
    ImGui::SameLine();
    ImGui::RadioButton("shared", &mask, int(StencilMask::Shared));
    o.stencilMask = StencilMask(mask);
    if (o.stencilMask == StencilMask::PerLight) {
      int layers = int(o.stencilLayers);
      ImGui::TextDisabled("  stencil layers");
      ImGui::SameLine();
      ImGui::RadioButton("auto##layers", &layers, int(StencilLayers::Auto));
      ImGui::SameLine();
      ImGui::RadioButton("on##layers", &layers, int(StencilLayers::On));
      ImGui::SameLine();
      ImGui::RadioButton("off##layers", &layers, int(StencilLayers::Off));
      tooltip("lights whose volumes cover disjoint pixels share a stencil bit, one draw per layer (auto: on a CPU device)");
      o.stencilLayers = StencilLayers(layers);
    }
  }
  ImGui::Checkbox("fairy lights", &o.fairies);
  ImGui::SameLine();
  ImGui::Checkbox("sky", &o.sky);
  ImGui::SliderFloat("exposure", &o.exposure, 0.05f, 8.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  ImGui::SliderInt("lights", &m.lightCount, 0, 4096, "%d", ImGuiSliderFlags_Logarithmic);
  ImGui::SliderFloat("light radius", &m.lightRadiusScale, 0.1f, 4.0f, "x%.2f", ImGuiSliderFlags_Logarithmic);
  ImGui::Text("render size %ux%u", m.fullSize.x ? m.fullSize.x : m.rendered.width, m.fullSize.y ? m.fullSize.y : m.rendered.height);
  bool follow = !m.fixedSize;
  ImGui::SameLine();  // beside the size where it fits, else below it (never cut at the panel's edge)
  if (ImGui::GetContentRegionAvail().x < ImGui::GetFrameHeight() + ImGui::GetStyle().ItemInnerSpacing.x +
                                             ImGui::CalcTextSize("follow the view area").x)
    ImGui::NewLine();
  if (ImGui::Checkbox("follow the view area", &follow)) m.fixedSize = !follow;
  tooltip("off (default): the size of --size (or 1280x720), letterboxed: pixel coordinates match gblens render and capture;\n"
          "on: render at the view area's size (or a fraction of it)");
  if (!m.fixedSize) {
    ImGui::SameLine();
    ImGui::SetNextItemWidth(90);
    const char* scales[] = {"view area", "1/2 area", "1/3 area", "1/4 area"};
    int scale = m.renderScale - 1;
    if (ImGui::Combo("##scale", &scale, scales, 4)) m.renderScale = scale + 1;
    tooltip("render at the view area's size, or a fraction of it (the views zoom it up, nearest texel)");
  }
  // Responsive rendering: the index in {auto, never, 1/2, 1/3, 1/4} is the value (kReduceAuto, kReduceOff, 2..4).
  const char* reduce[] = {"auto", "never", "1/2", "1/3", "1/4"};
  int ri = std::clamp(m.reduceWhileMoving, 0, 4);
  ImGui::SetNextItemWidth(90);
  if (ImGui::Combo("reduce while moving", &ri, reduce, 5)) m.reduceWhileMoving = ri;
  tooltip("while the camera, an option or the lights change, render at a fraction of the size and refine to "
          "full when the input stops (auto: only where a full frame is slower than the input budget)");
  if (m.reducedBy > 1) ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "showing 1/%d while moving", m.reducedBy);
}

static void animation(ViewerModel& m) {
  if (ImGui::Button(m.playing ? "pause" : "play")) m.playing = !m.playing;
  ImGui::SameLine();
  if (ImGui::Button("<")) m.stepBack = true;
  tooltip("step back 1/30 s");
  ImGui::SameLine();
  if (ImGui::Button(">")) m.stepForward = true;
  tooltip("step forward 1/30 s");
  ImGui::SameLine();
  ImGui::SetNextItemWidth(80);
  ImGui::SliderFloat("speed", &m.timeSpeed, 0.0f, 4.0f, "%.2fx");
  float t = float(m.wanted.time);
  if (ImGui::SliderFloat("time", &t, 0.0f, std::max(60.0f, t), "%.3f s")) {
    m.wanted.time = t;
    m.playing = false;
  }
}

static void cameraControls(ViewerModel& m) {
  int mode = int(m.cameraMode);
  ImGui::RadioButton("orbit", &mode, int(CameraMode::Orbit));
  ImGui::SameLine();
  ImGui::RadioButton("fly", &mode, int(CameraMode::Fly));
  m.cameraMode = CameraMode(mode);
  ImGui::SameLine();
  if (ImGui::Button("reset")) m.resetCamera = true;
  ImGui::SliderFloat("move speed", &m.moveSpeed, 0.05f, 20.0f, "%.2f", ImGuiSliderFlags_Logarithmic);
  for (size_t i = 0; i < m.cameraNames.size(); ++i) {
    if (i) ImGui::SameLine();
    if (ImGui::SmallButton(m.cameraNames[i].c_str())) m.gltfCamera = int(i);
  }
}

static void statistics(ViewerModel& m) {
  const FrameStats& s = m.stats;
  ImGui::Text("frame %.2f ms, GPU %.2f ms", s.frameMs, s.gpuMs);
  ImGui::Text("present %.2f ms (views + interface)", m.presentMs);
  ImGui::Text("frames rendered %llu, presented %llu", (unsigned long long)m.framesRendered,
              (unsigned long long)m.framesPresented);
  ImGui::TextWrapped("lights %u: %u drawn (%u near plane), %u culled", s.lights, s.lightsVisible, s.lightsInside,
                     s.lightsCulled);
  if (ImGui::BeginTable("passes", 2, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
    for (const PassStat& p : s.passes) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(p.name.c_str());
      ImGui::TableNextColumn();
      if (p.skipped) {
        ImGui::TextDisabled("skipped");
        tooltip(p.reason.c_str());
      } else {
        ImGui::Text("%.3f ms", p.ms);
      }
    }
    ImGui::EndTable();
  }
  ImGui::Checkbox("measure culling efficiency", &m.cullingStats);
  tooltip("counts point-light shader runs per pixel (coverage) against the ideal (pixel, light) pairs;\n"
          "reads back coverage_masked and depth each frame");
  if (s.culling.valid)
    ImGui::TextWrapped("point-light shader runs %llu for %llu lit (pixel, light) pairs: %.3fx the ideal work",
                       (unsigned long long)s.culling.invocations, (unsigned long long)s.culling.idealPairs,
                       s.culling.workOverIdeal);
}

static void controlsPanel(ViewerModel& m, const Rect& at) {
  ImGui::SetNextWindowPos(ImVec2(float(at.x), float(at.y)));
  ImGui::SetNextWindowSize(ImVec2(float(at.w), float(at.h)));
  ImGui::Begin("Controls", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                        ImGuiWindowFlags_NoSavedSettings);
  // Nothing cut off at the panel's edge: text wraps there, and widgets leave their labels half the
  // panel ("reduce while moving" is the longest).
  ImGui::PushTextWrapPos(0.0f);
  ImGui::PushItemWidth(std::max(ImGui::GetContentRegionAvail().x - ImGui::CalcTextSize("reduce while moving").x -
                                    ImGui::GetStyle().ItemInnerSpacing.x * 2, ImGui::GetContentRegionAvail().x * 0.4f));
  if (ImGui::CollapsingHeader("View", ImGuiTreeNodeFlags_DefaultOpen)) viewSettings(m);
  if (m.source == FrameSource::Compare && ImGui::CollapsingHeader("Compare", ImGuiTreeNodeFlags_DefaultOpen))
    compareControls(m);
  if (m.source == FrameSource::Live && ImGui::CollapsingHeader("Reference error", ImGuiTreeNodeFlags_DefaultOpen))
    referenceErrorSection(m);
  if (m.attach.on) {
    attachSection(m);
    if (!m.samplesNote.empty()) ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "%s", m.samplesNote.c_str());
  } else if (m.source != FrameSource::Live) {
    if (ImGui::CollapsingHeader(m.source == FrameSource::Compare ? "Captures" : "Capture", ImGuiTreeNodeFlags_DefaultOpen)) {
      ImGui::TextWrapped("%s", m.captureInfo.c_str());
      if (!m.samplesNote.empty()) ImGui::TextColored(ImVec4(1, 0.8f, 0.4f, 1), "%s", m.samplesNote.c_str());
    }
  } else {
    if (ImGui::CollapsingHeader("Frame", ImGuiTreeNodeFlags_DefaultOpen)) frameOptions(m);
    if (ImGui::CollapsingHeader("Animation", ImGuiTreeNodeFlags_DefaultOpen)) animation(m);
    if (ImGui::CollapsingHeader("Camera")) cameraControls(m);
    if (ImGui::CollapsingHeader("Statistics", ImGuiTreeNodeFlags_DefaultOpen)) statistics(m);
  }
  // Capturing needs a renderer or an application behind the frame: none for a capture opened.
  if (m.source == FrameSource::Live || m.attach.on) {
    if (!m.captureAvailable) ImGui::BeginDisabled();
    if (ImGui::Button("Capture frame")) m.captureRequested = true;
    if (!m.captureAvailable) ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled)) ImGui::SetTooltip("%s", m.captureHint.c_str());
  }
  if (m.source == FrameSource::Live) {  // gblens's own renderer: a RenderDoc capture of it beside
    const bool renderDoc = m.captureAvailable && m.renderDocAvailable;
    ImGui::SameLine();
    if (!renderDoc) ImGui::BeginDisabled();
    if (ImGui::Button("Capture in RenderDoc")) m.renderDocRequested = true;
    if (!renderDoc) ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("%s", renderDoc ? "The same frame as a gblens capture and, beside it, a RenderDoc capture (.rdc)"
                                        : "Start gblens under RenderDoc (renderdoccmd capture gblens view ..., or qrenderdoc's "
                                          "Launch Application) to capture the frame in RenderDoc too");
  }
  if (!m.captureStatus.empty()) ImGui::TextWrapped("%s", m.captureStatus.c_str());
  ImGui::PopItemWidth();
  ImGui::PopTextWrapPos();
  ImGui::End();
}

static void pixelPanel(ViewerModel& m, const Rect& at) {
  ImGui::SetNextWindowPos(ImVec2(float(at.x), float(at.y)));
  ImGui::SetNextWindowSize(ImVec2(float(at.w), float(at.h)));
  ImGui::Begin("Pixel", nullptr, ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                                     ImGuiWindowFlags_NoSavedSettings);
  if (m.region && ImGui::CollapsingHeader("Region statistics", ImGuiTreeNodeFlags_DefaultOpen)) drawRegion(m);
  if (m.source == FrameSource::Compare)
    compareTabs(m);  // the report and the pixel's dossiers
  else
    drawDossier(m);
  ImGui::End();
}

static void statusBar(ViewerModel& m, double w, double h) {
  ImGui::SetNextWindowPos(ImVec2(0, float(h - statusHeight(m))));
  ImGui::SetNextWindowSize(ImVec2(float(w), float(statusHeight(m))));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(6, 3));
  ImGui::Begin("##status", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                                         ImGuiWindowFlags_NoBringToFrontOnFocus);
  ImGui::PopStyleVar();
  char buf[1024];
  std::string line;
  if (m.attach.on) {
    line = attachStatusLine(m);
  } else if (m.source == FrameSource::Live && m.reducedBy > 1) {
    // The frame time before the reasons: they are long, and the line is cut at the window's edge.
    std::snprintf(buf, sizeof buf, "%s | %s | %ux%u: reduced 1/%d while moving (full %ux%u when input stops) | %.1f ms | %s | %s",
                  m.sceneName.c_str(), m.deviceName.c_str(), m.rendered.width, m.rendered.height, m.reducedBy,
                  m.fullSize.x, m.fullSize.y, m.stats.frameMs, m.stats.methodReason.c_str(), m.stats.gbufferReason.c_str());
    line = buf;
  } else if (m.source == FrameSource::Live) {
    std::snprintf(buf, sizeof buf, "%s | %s | %ux%u | %.1f ms | %s | %s", m.sceneName.c_str(), m.deviceName.c_str(),
                  m.rendered.width, m.rendered.height, m.stats.frameMs, m.stats.methodReason.c_str(),
                  m.stats.gbufferReason.c_str());
    line = buf;
  } else {
    std::snprintf(buf, sizeof buf, "%s | %s | %ux%u", m.sceneName.c_str(), m.deviceName.c_str(), m.rendered.width, m.rendered.height);
    line = buf;
    if (m.timeline.on && !m.timeline.numbers.empty())  // a sequence: the frame shown
      line += " | frame " + std::to_string(m.timeline.numbers[size_t(m.timeline.shown)]) + " of " +
              std::to_string(m.timeline.numbers.front()) + ".." + std::to_string(m.timeline.numbers.back());
  }
  // The hovered values first where the line is too long for the window: they change under the
  // mouse, the rest does not (and the whole line is in the tooltip).
  if (!m.hoverText.empty()) line = m.hoverText + " | " + line;
  fittedText(line);
  ImGui::End();
}

void drawViewerUi(ViewerModel& m, ViewDrawCallback callback, std::vector<ViewDraw>& draws) {
  ImGuiIO& io = ImGui::GetIO();
  const double w = io.DisplaySize.x, h = io.DisplaySize.y;
  menuBar(m);
  Rect area = viewArea(m, w, h);
  drawViewArea(m, area, callback, draws);  // first: the panels show this frame's hover
  if (m.showControls) controlsPanel(m, {0, kMenuHeight, controlsWidth(m, w), area.h});
  if (m.showPixel) pixelPanel(m, {w - pixelWidth(m, w), kMenuHeight, pixelWidth(m, w), area.h});
  drawTimeline(m, 0.0, area.y + area.h, w);  // a sequence: the strip between the views and the status bar
  statusBar(m, w, h);
  attachSuggestionWindow(m);
}

}  // namespace gb
