// Draft layouts (see suggest.h): which source drafts, and what both share once the evidence has
// decided (the quantities and camera into the draft).
#include "views/infer/suggest.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <sstream>

#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "views/infer/suggest_guess.h"

namespace gb {

namespace {

bool isRenderDocCapture(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".rdc";
}

}  // namespace

bool suggestLayout(const SuggestRequest& r, Suggestion& out, std::string& error) {
  if (r.inputs.empty()) {
    error = "--suggest-layout: give a RenderDoc capture (.rdc) or image files";
    return false;
  }
  if (r.inputs.size() == 1 && isRenderDocCapture(r.inputs[0])) return suggestFromRenderDoc(r, out, error);
  if ((r.event || !r.pass.empty())) {
    error = std::string(r.event ? "--event" : "--pass") + ": applies to a RenderDoc capture (.rdc)";
    return false;
  }
  return suggestFromImages(r, out, error);
}

bool draftFrame(const nlohmann::json& draft, const FrameSnapshot& raw, FrameSnapshot& frame, std::string& error) {
  Layout l;
  if (!parseLayout(draft, "draft", l, error)) return false;
  frame = FrameSnapshot{};
  frame.setLayout(l);
  frame.images = raw.images;
  frame.absences = raw.absences;
  frame.camera = raw.camera;
  return true;
}

std::string notDraftedLine(const std::string& what, const std::string& format, const std::string& where,
                           const nlohmann::json& source) {
  return "not drafted: " + what + " (" + format + ") " + where +
         ": what a dispatch writes is not decided from the frame's structure; to see it, add a target with \"format\": \"" +
         format + "\", \"source\": " + source.dump();
}

void computeMayWriteTheGBuffer(std::vector<std::string>& summary, size_t images) {
  for (std::string& line : summary)
    if (line.rfind("no G-buffer:", 0) == 0)
      line = "no render pass writes a G-buffer" + line.substr(std::string("no G-buffer").size()) +
             "; or compute writes it: dispatches bind " + std::to_string(images) + " storage images of the frame's size (below)";
}

void applyInference(nlohmann::json& draft, const InferOutput& inferred, const std::vector<bool>& unnamed) {
  nlohmann::json& targets = draft["targets"];
  std::set<std::string> names;
  for (size_t t = 0; t < targets.size() && t < inferred.quantities.size(); ++t) {
    targets[t]["quantities"] = inferred.quantities[t];
    const nlohmann::json& qs = targets[t]["quantities"];
    std::string base = targets[t].value("name", "target");
    if (t < unnamed.size() && unnamed[t] && !qs.empty()) base = qs[0].value("quantity", "target");
    targets[t]["name"] = targetName(base, names);
  }
  if (!inferred.camera.is_null()) draft["camera"] = inferred.camera;
}

}  // namespace gb
