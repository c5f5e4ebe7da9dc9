// Drafting a layout for an unfamiliar G-buffer: `gblens import APP.rdc --suggest-layout` (the pass
// that writes the G-buffer, its targets and storage formats, a guessed quantity per channel, the
// camera found by search in the bound buffers) and `gblens import FILES.exr --suggest-layout`
// (targets from channel names, the camera from a sidecar beside them). Every guess carries a
// "guess" note in the draft; the draft parses as a layout and imports as it is.
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/snapshot.h"
#include "views/import/renderdoc_replay.h"
#include "views/infer/suggest_camera.h"
#include "views/infer/suggest_guess.h"

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
// The surface pixels by a depth quantity of a frame (hardware: not the clear value; eye: finite,
// positive and not the background); every pixel when the layout has none.
SurfaceMask surfaceOf(const FrameSnapshot& frame);
// Samples of stored positions and hardware depth at surface pixels of a drafted frame.
CameraEvidence evidenceOf(const FrameSnapshot& frame, const SurfaceMask& surface);
// With the camera known: positions' space, a position's 4th channel that is a linear depth (eye
// depth / scale), normals' space; the draft's quantities are rewritten with notes.
void refineWithCamera(nlohmann::json& draft, const FrameSnapshot& frame, const SurfaceMask& surface,
                      const LayoutCamera& camera, const Camera& converted, bool positionsChecked, Space positionSpace,
                      std::vector<std::string>& summary);

}  // namespace gb
