// The timeline strip of a sequence (gblens view SEQ; ImGui only): step back / forward, play / pause at
// the sequence's rate, a slider over its frames, the frame's number and time, the frame cache (on an
// attached stream's kept frames, attach --history K: Freeze / Live for the stream, the kept frames'
// count and memory, at most K frames; app/viewer/live_timeline.cpp); below
// them the temporal views' row: the motion check's verdict of the pair ending at the frame shown and
// the Flicker button. It edits ViewerModel::timeline; the app (app/viewer/sequence.cpp,
// temporal_views.cpp) shows the frame asked for and computes the maps.
#include <imgui.h>

#include <algorithm>
#include <cstdio>
#include <string>

#include "views/analysis/view_table.h"
#include "views/ui/viewer_model.h"

namespace gb {

// The strip's rows: the frames, and the temporal views' row where there is a verdict or a button.
static bool temporalRow(const ViewerModel::TimelineUi& t) { return !t.motionLine.empty() || !t.flickerOf.empty() || !t.flickerLine.empty(); }
double timelineHeight(const ViewerModel& m) { return m.timeline.on ? (temporalRow(m.timeline) ? 56.0 : 30.0) : 0.0; }

bool cycleMotionViews(ViewerModel& m) {
  const int error = findView(m.views, "Motion error"), classes = findView(m.views, "Motion class");
  if (error < 0 || m.views[size_t(error)].quantity >= 0) return false;
  const bool again = m.layout != LayoutMode::Grid && m.primary == error && classes >= 0;
  m.primary = m.edited = again ? classes : error;
  if (m.layout == LayoutMode::Grid) m.layout = LayoutMode::Single;
  m.uiChanged = true;
  return true;
}

// The second row: the motion verdict (coloured by what it says; the detected convention and the pixel
// counts in its tooltip) and the Flicker button with what the last flicker found.
static void drawTemporalRow(ViewerModel& m) {
  ViewerModel::TimelineUi& t = m.timeline;
  if (!t.motionLine.empty()) {
    const bool agrees = t.motionLine.find("agrees") != std::string::npos;
    const bool undecided = t.motionComputing || t.motionLine.find("undecided") != std::string::npos ||
                           t.motionLine.find("no previous") != std::string::npos;
    const ImVec4 colour = agrees ? ImVec4(0.55f, 0.9f, 0.55f, 1) : undecided ? ImVec4(0.75f, 0.75f, 0.75f, 1) : ImVec4(1, 0.6f, 0.3f, 1);
    const size_t cut = t.motionLine.find(" | ");
    ImGui::TextColored(colour, "%s", t.motionLine.substr(0, cut).c_str());
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("%s\n\ngblens motion on the pair ending at the frame shown (V: the Motion error view, again: Motion class)",
                        t.motionLine.c_str());
    ImGui::SameLine(0.0f, 24.0f);
  }
  if (!t.flickerOf.empty() || t.flickerComputing) {
    const std::string label = t.flickerComputing ? "Flicker: computing..." : "Flicker of " + t.flickerOf;
    ImGui::BeginDisabled(t.flickerComputing);
    if (ImGui::SmallButton(label.c_str())) t.flickerRequested = true, m.uiChanged = true;
    ImGui::EndDisabled();
    if (ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
      ImGui::SetTooltip("F: the view's temporal standard deviation and largest frame-to-frame step over the whole sequence,\n"
                        "each frame carried to the frame shown by reprojection (gblens flicker); views Flicker stddev, Flicker max step");
    ImGui::SameLine();
  }
  if (!t.flickerLine.empty()) ImGui::TextDisabled("%s", t.flickerLine.c_str());
}

void stepTimeline(ViewerModel& m, int delta) {
  ViewerModel::TimelineUi& t = m.timeline;
  if (!t.on || t.numbers.empty()) return;
  const int from = t.requested >= 0 ? t.requested : t.shown;  // presses that arrive together all count
  t.requested = std::clamp(from + delta, 0, int(t.numbers.size()) - 1);
  t.playing = false;
  m.uiChanged = true;
}

// What the strip says of the frame shown: its number, place, time and the rate played at.
static std::string frameText(const ViewerModel::TimelineUi& t) {
  char buf[256];
  const size_t i = size_t(t.shown);
  const int n = std::snprintf(buf, sizeof buf, "%sframe %lld (%zu of %zu)", t.history ? "application " : "", (long long)t.numbers[i],
                              i + 1, t.numbers.size());
  std::string text(buf, size_t(std::max(n, 0)));
  if (t.times[i]) {
    std::snprintf(buf, sizeof buf, "  t %.4g s", *t.times[i]);
    text += buf;
  }
  return text;
}

// Play / pause a sequence; on an attached stream's kept frames, freeze the stream or back to it.
static void playButton(ViewerModel& m) {
  ViewerModel::TimelineUi& t = m.timeline;
  const ImVec2 size(ImGui::CalcTextSize("Freeze").x + 12.0f, 0.0f);
  if (t.history) {
    if (ImGui::Button(m.playing ? "Freeze" : "Live", size)) m.playing = !m.playing, m.uiChanged = true;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip(m.playing ? "freeze the stream: step through its kept frames (Space)" : "back to the stream's newest frame (Space)");
    return;
  }
  if (ImGui::Button(t.playing ? "Pause" : "Play ", size)) t.playing = !t.playing;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("play / pause at the sequence's rate (Space)");
}

// Right of the slider: the rate and the cache (kept frames: their count and memory, the bound), or
// why a frame could not be shown.
static std::string rightText(const ViewerModel& m) {
  const ViewerModel::TimelineUi& t = m.timeline;
  char right[256];
  if (!t.status.empty())
    std::snprintf(right, sizeof right, "%s", t.status.c_str());
  else if (t.history)
    std::snprintf(right, sizeof right, "%s | %zu of at most %zu frames kept, %.1f MB", m.playing ? "live" : "frozen", t.cached,
                  t.cacheLimit, double(t.historyBytes) / 1e6);
  else
    std::snprintf(right, sizeof right, "%.3g fps%s | %zu of at most %zu frames in memory", t.fps,
                  t.fpsFromTimes ? " (the frames' times)" : " (no times: 30 fps)", t.cached, t.cacheLimit);
  return right;
}

void drawTimeline(ViewerModel& m, double x, double y, double w) {
  ViewerModel::TimelineUi& t = m.timeline;
  if (!t.on || t.numbers.empty()) return;
  ImGui::SetNextWindowPos(ImVec2(float(x), float(y)));
  ImGui::SetNextWindowSize(ImVec2(float(w), float(timelineHeight(m))));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowPadding, ImVec2(6, 4));
  ImGui::Begin("##timeline", nullptr, ImGuiWindowFlags_NoDecoration | ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoSavedSettings |
                                           ImGuiWindowFlags_NoBringToFrontOnFocus);
  ImGui::PopStyleVar();
  const int last = int(t.numbers.size()) - 1;
  if (ImGui::Button("|<")) t.requested = 0, t.playing = false;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the first frame");
  ImGui::SameLine();
  if (ImGui::ArrowButton("##back", ImGuiDir_Left)) stepTimeline(m, -1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the previous frame (,)");
  ImGui::SameLine();
  playButton(m);
  ImGui::SameLine();
  if (ImGui::ArrowButton("##forward", ImGuiDir_Right)) stepTimeline(m, +1);
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the next frame (.)");
  ImGui::SameLine();
  if (ImGui::Button(">|")) t.requested = last, t.playing = false;
  if (ImGui::IsItemHovered()) ImGui::SetTooltip("the last frame");
  ImGui::SameLine();
  // Right of the slider: the rate and the cache, or why a frame could not be shown.
  const std::string right = rightText(m);
  const float rightWidth = std::min(ImGui::CalcTextSize(right.c_str()).x, float(w) * 0.45f);
  ImGui::SetNextItemWidth(std::max(80.0f, ImGui::GetContentRegionAvail().x - rightWidth - ImGui::GetStyle().ItemSpacing.x));
  int index = t.requested >= 0 ? t.requested : t.shown;
  std::string label = frameText(t);
  std::string format;  // the slider prints the text as is ('%' doubled)
  for (char c : label) format += c == '%' ? std::string("%%") : std::string(1, c);
  if (ImGui::SliderInt("##frame", &index, 0, last, format.c_str(), ImGuiSliderFlags_AlwaysClamp)) {
    t.requested = index;
    t.playing = false;
  }
  ImGui::SameLine();
  if (!t.status.empty())
    ImGui::TextColored(ImVec4(1, 0.5f, 0.4f, 1), "%s", right.c_str());
  else
    ImGui::TextDisabled("%s", right.c_str());
  if (ImGui::IsItemHovered() && t.status.empty() && t.history)
    ImGui::SetTooltip("gblens attach --history %zu: the stream's last %zu decoded frames are kept (the oldest goes);\n"
                      "frozen, the strip steps through them (the probe follows its point), Live returns to the newest",
                      t.cacheLimit, t.cacheLimit);
  else if (ImGui::IsItemHovered() && t.status.empty())
    ImGui::SetTooltip("frames are loaded when first shown and kept in a cache of at most %zu (the least recently used goes)",
                      t.cacheLimit);
  if (temporalRow(t)) drawTemporalRow(m);
  if (t.requested >= 0 || t.playing) m.uiChanged = true;
  ImGui::End();
}

}  // namespace gb
