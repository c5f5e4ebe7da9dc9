// `gblens attach --suggest`: a draft layout from the layer's report of one frame's render passes
// (live.h draftLiveLayout). The same guesses as `import --suggest-layout` where no texels are at hand:
// the G-buffer pass is the one writing the most colour attachments (and a depth attachment), its
// attachments and the frame-sized ones later passes write are the targets, named live as the report
// names them; what the channels hold is guessed from the image's name and format (suggest_guess.h).
#include <cstdio>
#include <set>

#include "renderer/core/layout_json.h"
#include "views/import/import.h"
#include "views/live/live.h"
#include "views/infer/suggest_live.h"
#include "views/infer/suggest.h"
#include "views/infer/suggest_guess.h"

namespace gb {

namespace {

using nlohmann::json;

bool usable(const json& a) {
  return !a.value("format", "").empty() && a.value("why", "").empty() && a.value("role", "") != "other";
}

// The live source that picks an attachment: its image's debug name, else its index in its pass.
json liveSource(const json& pass, const json& a) {
  const std::string image = a.value("image", ""), role = a.value("role", "");
  if (!image.empty()) return {{"live", {{"name", image}}}};
  json pick = {{"pass", pass.value("ordinal", 0)}};
  if (role == "depth")
    pick["depth"] = true;
  else
    pick["color"] = std::stoi(role.substr(6));  // "color N"
  return {{"live", pick}};
}

// A pass's debug labels and render pass name ("" : none).
std::string passLabels(const json& p) {
  std::string name;
  for (const json& l : p.value("labels", json::array())) name += (name.empty() ? "" : " > ") + l.get<std::string>();
  if (!p.value("render_pass", "").empty()) name += (name.empty() ? "" : "  ") + ("render pass \"" + p.value("render_pass", "") + "\"");
  return name;
}

std::string passName(const json& p) {
  const std::string labels = passLabels(p);
  return "#" + std::to_string(p.value("ordinal", 0)) + (labels.empty() ? "" : " " + labels);
}

// Which of an attachment's aspects the application does not store (its own store ops, per aspect:
// a stored depth with a DONT_CARE stencil is only "stencil"), and whether gblens stores them.
std::string notStored(const json& a) {
  auto off = [&](const char* key) { return a.contains(key) && a[key].is_string() && a[key] != "store"; };
  const bool depthStencil = a.value("role", "") == "depth" && a.contains("stencil_store") && a["stencil_store"].is_string() &&
                            a.contains("store") && a["store"].is_string();
  const bool main = off("store"), stencil = off("stencil_store");
  if (!main && !stencil) return a.value("store_patched", false) ? "  (not stored by the application: gblens stores it)" : "";
  const std::string which = !depthStencil ? "" : main && stencil ? "depth and stencil " : main ? "depth " : "stencil ";
  return "  (" + which + "not stored by the application" + (a.value("store_patched", false) ? ": gblens stores it)" : ")");
}

// printf into a std::string.
template <class... A>
std::string format(const char* f, A... a) {
  char text[512];
  std::snprintf(text, sizeof text, f, a...);
  return text;
}

}  // namespace

std::string describeLivePasses(const json& hello, const json& report) {
  std::string out = format("application  %s (%s)\n", hello.value("application", "").c_str(), hello.value("device", "").c_str());
  out += format("frame        %llu\n", (unsigned long long)report.value("frame", 0ull));
  const json passes = report.value("passes", json::array());
  out += format("passes       %zu (ordinal in its command buffer, labels or render pass name; attachments)\n", passes.size());
  for (const json& p : passes) {
    const std::string names = passLabels(p);
    out += format("  #%-3d %s%s\n", p.value("ordinal", 0), p.value("dynamic", false) ? "(dynamic rendering) " : "", names.c_str());
    for (const json& a : p.value("attachments", json::array())) {
      const std::string role = a.value("role", ""), image = a.value("image", ""), fmt = a.value("format", "");
      out += format("       %-8s %-20s %-32s %-14s %ux%u%s%s\n", role.c_str(), image.empty() ? "(unnamed)" : image.c_str(),
                    a.value("vk_format", "").c_str(), fmt.empty() ? "-" : fmt.c_str(), a.value("width", 0u),
                    a.value("height", 0u), notStored(a).c_str(),
                    a.value("why", "").empty() ? "" : ("  * " + a.value("why", "")).c_str());
      if (usable(a)) out += "                source: " + liveSource(p, a).dump() + "\n";
    }
  }
  return out;
}

json draftLiveLayout(const json& report, std::vector<std::string>& summary, std::vector<bool>* later) {
  const json passes = report.value("passes", json::array());
  int best = -1, bestScore = -1;
  for (size_t i = 0; i < passes.size(); ++i) {
    int colours = 0, depth = 0;
    for (const json& a : passes[i].value("attachments", json::array())) {
      if (!usable(a)) continue;
      if (a.value("role", "") == "depth")
        depth = 1;
      else
        ++colours;
    }
    const int score = colours * 2 + depth;
    if (score > bestScore) best = int(i), bestScore = score;
  }
  json draft = {{"format", "gblens-layout"}, {"version", 1},
                {"name", "draft (gblens attach --suggest: check every \"guess\")"}, {"targets", json::array()}};
  if (best < 0 || bestScore <= 0) {
    summary.push_back("no render pass writes an attachment a layout can hold");
    return draft;
  }
  const json& gbuffer = passes[size_t(best)];
  summary.push_back("G-buffer pass: " + passName(gbuffer) + " (the most colour attachments)");
  std::set<std::string> targetNames, quantityNames, images;
  uint32_t width = 0, height = 0;
  std::vector<bool> ignored, &laterTargets = later ? *later : ignored;
  laterTargets.clear();
  auto add = [&](const json& pass, const json& a, bool afterGBuffer) {
    StorageFormat format;
    if (!parseStorageFormat(a.value("format", ""), format)) return;
    if (afterGBuffer && (a.value("width", 0u) != width || a.value("height", 0u) != height)) return;
    if (!width) width = a.value("width", 0u), height = a.value("height", 0u);
    const std::string image = a.value("image", "");
    if (!image.empty() && !images.insert(image).second) return;  // a later pass writing the same image again
    json quantities = guessQuantities(image, format, nullptr, SurfaceMask{}, quantityNames, afterGBuffer);
    const std::string base = !image.empty() ? image : !quantities.empty() ? quantities[0].value("quantity", "target") : "target";
    draft["targets"].push_back({{"name", targetName(base, targetNames)}, {"format", a.value("format", "")},
                                {"source", liveSource(pass, a)}, {"quantities", quantities}});
    laterTargets.push_back(afterGBuffer);
    if (afterGBuffer) summary.push_back("target " + draft["targets"].back().value("name", "") + ": written after the G-buffer pass, by " + passName(pass));
  };
  for (const json& a : gbuffer.value("attachments", json::array()))
    if (usable(a)) add(gbuffer, a, false);
  for (size_t i = size_t(best) + 1; i < passes.size(); ++i)
    for (const json& a : passes[i].value("attachments", json::array()))
      if (usable(a) && a.value("role", "") != "depth") add(passes[i], a, true);
  summary.push_back("no camera: name the buffer that holds it (camera.renderdoc) or give matrices (docs/layout-format.md)");
  return draft;
}

}  // namespace gb

namespace gb {

void withoutCamera(json& draft, std::vector<std::string>* summary) {
  if (draft.contains("camera")) return;
  Layout l;
  std::string error;
  if (!parseLayout(draft, "draft", l, error)) return;
  for (const Quantity& q : l.quantities) {
    if (!needsCamera(q)) continue;
    for (json& t : draft["targets"])
      for (json& j : t["quantities"]) {
        if (j.value("name", "") != q.name) continue;
        const std::string was = j.value("quantity", "");
        json stored = {{"quantity", q.channels.size() == 1 ? "scalar" : "vector"}, {"name", q.name}, {"channels", j["channels"]},
                       {"guess", j.value("guess", "") + "; shown as stored: a " + was +
                                     " quantity needs the camera (give \"camera\", then \"quantity\": \"" + was + "\")"}};
        j = stored;
        if (summary) summary->push_back(q.name + ": shown as stored values (a " + was + " quantity needs the layout's camera)");
      }
  }
}

// What the texels say, as import --suggest-layout reads them: depth targets first (they say where the
// surfaces are), then the rest; an unnamed image's target is named by what it holds.
bool refineLiveDraft(json& draft, const std::vector<bool>& later, const FrameSnapshot& raw, uint64_t appFrame,
                     FrameSnapshot& frame, std::vector<std::string>& summary, std::string& error) {
  json& targets = draft["targets"];
  if (targets.size() != raw.layout.targets.size() || later.size() != targets.size()) {
    error = "the streamed frame holds " + std::to_string(raw.layout.targets.size()) + " targets, the draft " +
            std::to_string(targets.size());
    return false;
  }
  SurfaceMask surface;
  std::set<std::string> quantityNames;
  size_t looked = 0;
  for (bool depthPass : {true, false}) {
    for (size_t t = 0; t < targets.size(); ++t) {
      const StorageFormat& f = raw.layout.targets[t].format;
      if (f.depth != depthPass) continue;
      const CpuImage* texels = raw.images[t].present() ? &raw.images[t].image : nullptr;
      looked += texels != nullptr;
      const json source = targets[t]["source"]["live"];
      targets[t]["quantities"] = guessQuantities(source.value("name", ""), f, texels, surface, quantityNames, later[t]);
    }
    if (!draftFrame(draft, raw, frame, error)) return false;
    if (depthPass) surface = surfaceOf(frame);
  }
  std::set<std::string> renamed;
  for (json& t : targets) {
    const json& qs = t["quantities"];
    const std::string image = t["source"]["live"].value("name", ""), was = t.value("name", "target");
    t["name"] = targetName(image.empty() && !qs.empty() ? qs[0].value("quantity", "target") : was, renamed);
    for (std::string& line : summary)  // what was said of it under its first name
      if (line.rfind("target " + was + ":", 0) == 0) line = "target " + t["name"].get<std::string>() + line.substr(7 + was.size());
  }
  withoutCamera(draft, &summary);
  summary.push_back("the channels guessed from the texels of application frame " + std::to_string(appFrame) + " (" +
                    std::to_string(looked) + " of " + std::to_string(targets.size()) + " targets streamed)");
  draft["name"] = "draft (gblens attach --suggest, from the texels of one frame: check every \"guess\")";
  return draftFrame(draft, raw, frame, error);
}

}  // namespace gb
