// The viewer's parts for an attached application (gblens attach, ImGui only): the "Application" menu
// (pause, capture, detach), the controls panel's section (what is attached, the frame shown, the
// layer's reports), the status bar's line and, with --suggest, the layer's passes and the drafted layout.
#include <imgui.h>

#include <algorithm>

#include "views/ui/viewer_model.h"

namespace gb {

void attachMenu(ViewerModel& m) {
  if (!m.attach.on || !ImGui::BeginMenu("Application")) return;
  if (ImGui::MenuItem(m.playing ? "Pause (freeze this frame)" : "Resume", "Space", false, !m.attach.detachRequested))
    m.playing = !m.playing;
  if (ImGui::MenuItem("Capture frame", "C")) m.captureRequested = true;
  if (ImGui::MenuItem("Detach (the application runs on)", nullptr, false, !m.attach.detachRequested)) m.attach.detachRequested = true;
  ImGui::EndMenu();
}

void attachSection(ViewerModel& m) {
  if (!ImGui::CollapsingHeader("Application", ImGuiTreeNodeFlags_DefaultOpen)) return;
  ImGui::TextWrapped("%s", m.attach.application.c_str());
  ImGui::TextWrapped("%s", m.attach.frame.c_str());
  ImGui::TextWrapped("%s", m.attach.status.c_str());
  if (!m.attach.detachRequested) {
    if (ImGui::Button(m.playing ? "pause" : "resume")) m.playing = !m.playing;
    if (ImGui::IsItemHovered())
      ImGui::SetTooltip("Space. Paused, the frame shown stays and nothing is taken from the application: it runs on, "
                        "its layer drops the frames");
    ImGui::SameLine();
    if (ImGui::Button("detach")) m.attach.detachRequested = true;
    if (ImGui::IsItemHovered()) ImGui::SetTooltip("The layer goes idle for good; the last frame stays; the application runs on");
  }
  for (const std::string& r : m.attach.reports) ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "%s", r.c_str());
}

std::string attachStatusLine(const ViewerModel& m) {
  return m.attach.status + (m.captureStatus.empty() ? "" : " | " + m.captureStatus) + " | " + m.sceneName;
}

// --suggest: the layer's report of one frame's passes and the layout drafted from it.
void attachSuggestionWindow(ViewerModel& m) {
  if (!m.attach.on || m.attach.passes.empty()) return;
  // Over the lower right (the Pixel panel's empty part until a click), not over the grid it explains.
  const ImVec2 screen = ImGui::GetIO().DisplaySize;
  const ImVec2 size(std::min(560.0f, screen.x * 0.45f), screen.y * 0.5f);
  ImGui::SetNextWindowPos(ImVec2(screen.x - size.x - 8.0f, screen.y - size.y - 28.0f), ImGuiCond_FirstUseEver);
  ImGui::SetNextWindowSize(size, ImGuiCond_FirstUseEver);
  if (!ImGui::Begin("Suggested layout (gblens attach --suggest)")) return ImGui::End();
  ImGui::TextUnformatted("What the layer saw in one frame:");
  // The report is a table of fixed columns: scrolled sideways, not wrapped.
  const float lines = float(std::count(m.attach.passes.begin(), m.attach.passes.end(), '\n') + 1);
  ImGui::BeginChild("report", ImVec2(0.0f, std::min(lines, 14.0f) * ImGui::GetTextLineHeightWithSpacing() + 16.0f), false,
                    ImGuiWindowFlags_HorizontalScrollbar);
  ImGui::TextUnformatted(m.attach.passes.c_str());
  ImGui::EndChild();
  // What was found and left out, wrapped: a line's end (a live source to add) must be readable.
  for (const std::string& line : m.attach.summary) ImGui::TextWrapped("%s", line.c_str());
  ImGui::Separator();
  ImGui::TextUnformatted(m.attach.draftStreamed
                             ? "The stream is decoded with this draft (every \"guess\" to be checked; save it, edit, attach with --layout):"
                             : "A draft layout (every \"guess\" to be checked; save it and attach with --layout):");
  // What each channel group was decided to hold, and on what evidence (unknown: shown as stored).
  if (!m.attach.verdicts.empty() &&
      ImGui::BeginTable("verdicts", 5, ImGuiTableFlags_Borders | ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
    for (const char* h : {"target", "channels", "holds", "confidence", "evidence"}) ImGui::TableSetupColumn(h);
    ImGui::TableHeadersRow();
    for (const ViewerModel::AttachUi::Verdict& v : m.attach.verdicts) {
      ImGui::TableNextRow();
      const std::string* cells[] = {&v.target, &v.channels, &v.quantity, &v.confidence, &v.evidence};
      for (int c = 0; c < 5; ++c) {
        ImGui::TableSetColumnIndex(c);
        if (c == 2 && v.quantity == "unknown") ImGui::TextColored(ImVec4(1.0f, 0.8f, 0.3f, 1.0f), "unknown");
        else ImGui::TextWrapped("%s", cells[c]->c_str());
      }
    }
    ImGui::EndTable();
  }
  if (ImGui::SmallButton("save the draft (ctrl+S)")) m.attach.saveDraftRequested = true;
  ImGui::SameLine();
  if (ImGui::SmallButton("copy the draft")) ImGui::SetClipboardText(m.attach.draft.c_str());
  if (!m.attach.draftStatus.empty()) ImGui::TextUnformatted(m.attach.draftStatus.c_str());
  ImGui::InputTextMultiline("##draft", m.attach.draft.data(), m.attach.draft.size() + 1, ImVec2(-1, -1),
                            ImGuiInputTextFlags_ReadOnly);
  ImGui::End();
}

}  // namespace gb
