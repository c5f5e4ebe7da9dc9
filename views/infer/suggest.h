// Drafting a layout for an unfamiliar G-buffer: `gblens import APP.rdc --suggest-layout` (the pass
// that writes the G-buffer decided by the frame's structure, its targets and storage formats, what
// each channel group holds decided by evidence, the camera found by search in the bound buffers) and
// `gblens import FILES.exr --suggest-layout` (targets from channel names, the camera from a sidecar
// beside them). Every quantity carries a "guess" object (views/infer/guess.h); the draft parses as a
// layout and imports as it is.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/snapshot.h"
#include "views/import/renderdoc_replay.h"
#include "views/infer/infer.h"

namespace gb {

struct SuggestRequest {
  std::vector<std::string> inputs;  // one RenderDoc capture, or image files
  uint32_t event = 0;               // RenderDoc: the G-buffer pass ends at this event (0: found)
  std::string pass;                 // RenderDoc: ... or this pass
  RdcReplayOptions replay;
  std::function<void(const std::string&)> progress = [](const std::string&) {};
};

struct Suggestion {
  nlohmann::json layout;             // the draft
  std::vector<std::string> summary;  // for the terminal: what was found and what to check
};

bool suggestLayout(const SuggestRequest& request, Suggestion& out, std::string& error);

// Shared by both sources (suggest.cpp).
bool suggestFromRenderDoc(const SuggestRequest& request, Suggestion& out, std::string& error);
bool suggestFromImages(const SuggestRequest& request, Suggestion& out, std::string& error);
// `raw`'s texels under the draft's layout (parsed; false with its message when it does not parse).
bool draftFrame(const nlohmann::json& draft, const FrameSnapshot& raw, FrameSnapshot& frame, std::string& error);
// The inference's quantities and camera into the draft's targets (in order); a target whose name the
// source made up (`unnamed`) is named by the first quantity it holds.
void applyInference(nlohmann::json& draft, const InferOutput& inferred, const std::vector<bool>& unnamed);

// A G-buffer written by compute is not drafted (a storage image may be read or written, and nothing
// in the frame's structure says which, nor what it holds): the summary line that names such an image
// (`what`: "storage image NAME", `where`: "bound by compute after #0") with the source that picks
// it; and, when the render passes write no G-buffer, the roles' "no G-buffer" note saying that
// compute may write it (`images` of the frame's size). The same words for captures and live frames.
std::string notDraftedLine(const std::string& what, const std::string& format, const std::string& where,
                           const nlohmann::json& source);
void computeMayWriteTheGBuffer(std::vector<std::string>& summary, size_t images);

}  // namespace gb
