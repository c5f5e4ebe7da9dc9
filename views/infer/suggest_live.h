// `gblens attach --suggest`: drafting a layout from a running application (the layer's report of one
// frame's passes, then the texels of the first frame streamed under the draft), the live front end
// of views/infer (suggest.h is import's).
#pragma once
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/snapshot.h"
#include "views/import/renderdoc_replay.h"
#include "views/infer/roles.h"
#include "views/live/live.h"

namespace gb {

// What the frame's structure said of each target of a live draft, for the refinement.
struct LiveTargetFacts {
  std::string label;  // the image's debug name ("" : none)
  Writer writer = Writer::GBuffer;
  bool readLater = false, presented = false, stencilStored = true;
  int pass = 0;       // the ordinal of the render pass that writes it
};

// A draft layout from the layer's report of one frame's render passes (LiveSession::suggestion): the
// G-buffer pass and targets decided by the frame's structure (roles.h), every channel as stored; what
// was found and what to check in `summary` (suggest_live.cpp); `facts`: per target, for the refinement.
nlohmann::json draftLiveLayout(const nlohmann::json& report, std::vector<std::string>& summary,
                               std::vector<LiveTargetFacts>* facts = nullptr);
// A draft with no camera: each quantity that needs one (import.h needsCamera) becomes the stored values
// (scalar or vector, same name and channels) with a note saying how to have it back; said in `summary`.
void withoutCamera(nlohmann::json& draft, std::vector<std::string>* summary);
// That draft refined with the texels of a frame streamed under it (`raw`) and the buffers bound at the
// G-buffer pass (the camera search; may be empty): what the channels hold is decided as import
// --suggest-layout decides it (infer.h), unnamed targets are named by what they hold; `frame` is `raw`
// under the refined draft. The targets and their sources stay (LiveSession::setLayout).
bool refineLiveDraft(nlohmann::json& draft, const std::vector<LiveTargetFacts>& facts, const FrameSnapshot& raw,
                     uint64_t appFrame, const std::vector<RdcBinding>& buffers, FrameSnapshot& frame,
                     std::vector<std::string>& summary, std::string& error);
// The same report for people, as `import --list` prints a capture, with the source naming each attachment.
std::string describeLivePasses(const nlohmann::json& hello, const nlohmann::json& report);

// gblens attach --suggest without a layout (live_suggest.cpp): the layer's report of one frame's
// passes, a draft from it, and the draft refined with the texels of the first frame streamed under it.
struct LiveSuggestion {
  std::string passes;                // the layer's report, for people (describeLivePasses)
  std::vector<std::string> summary;  // what was found and what to check
  nlohmann::json draft;              // the refined draft: it parses as a layout and streams as it is
  FrameSnapshot frame;               // the first frame streamed, under the refined draft
  LiveFrameInfo info;
  std::vector<std::string> reports;  // what the layer said meanwhile
};
// Starts the application under the layer asking for its passes only, drafts a layout, ends it and
// starts it again streaming under the draft (command buffers recorded before a layout was known copy
// nothing), then refines the draft with the first frame. `session`: the second run, streaming under
// the refined draft. False with why (the application ended, nothing to hold, `timeout` seconds).
bool suggestLive(const LiveOptions& o, double timeout, LiveSession& session, LiveSuggestion& out,
                 const std::function<void(const std::string&)>& progress, std::string& error);

}  // namespace gb
