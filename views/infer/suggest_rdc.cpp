// A draft layout from a RenderDoc capture (see suggest.h): the G-buffer pass is the one whose last
// draw writes the most colour targets (and a depth target); its targets, and the frame-sized ones
// later passes write, are read as the import would read them; the camera is searched for in the
// buffers bound at that draw.
#include <algorithm>
#include <filesystem>
#include <map>

#include "renderer/core/layout_json.h"
#include "views/import/import.h"
#include "views/infer/suggest.h"

namespace gb {

namespace {

const RdcTexture* findTexture(const RdcListing& l, const std::string& name) {
  for (const RdcTexture& t : l.textures)
    if (t.name == name || "#" + std::to_string(t.id) == name) return &t;
  return nullptr;
}

// What a texture's name says about it: nothing when RenderDoc made the name up ("2D Color
// Attachment 127" is no albedo).
std::string said(const RdcTexture& t) { return t.autoName ? "" : t.name; }

// How a layout names a texture: by name when no other texture has it, else by id.
std::string sourceName(const RdcListing& l, const RdcTexture& t) {
  const size_t same = size_t(std::count_if(l.textures.begin(), l.textures.end(), [&](const RdcTexture& o) { return o.name == t.name; }));
  return same == 1 && !t.name.empty() && !t.autoName ? t.name : "#" + std::to_string(t.id);
}

// The G-buffer pass: --pass, the pass ending at --event, or the one whose last draw writes the most
// colour targets with a depth target (the innermost of passes ending with the same draw).
const RdcPass* gbufferPass(const RdcListing& l, const SuggestRequest& r, std::string& error) {
  const RdcPass* best = nullptr;
  auto better = [](const RdcPass& p, const RdcPass* b) {
    if (!b) return true;
    const size_t sp = p.outputs.size() * 2 + !p.depthTarget.empty(), sb = b->outputs.size() * 2 + !b->depthTarget.empty();
    if (sp != sb) return sp > sb;
    return p.lastEvent - p.firstEvent < b->lastEvent - b->firstEvent;
  };
  for (const RdcPass& p : l.passes) {
    if (!r.pass.empty() && p.name != r.pass) continue;
    if (r.event && !(p.firstEvent <= r.event && r.event <= p.lastEvent)) continue;
    if (p.boundAt && (r.event ? !best || p.lastEvent - p.firstEvent < best->lastEvent - best->firstEvent : better(p, best)))
      best = &p;
  }
  if (!best)
    error = r.inputs[0] + (!r.pass.empty() ? ": --pass \"" + r.pass + "\": no pass of that name draws (see --list)"
                           : r.event       ? ": --event " + std::to_string(r.event) + ": no pass with a draw holds it"
                                           : ": no pass draws anything");
  else if (best->outputs.empty() && best->depthTarget.empty())
    error = r.inputs[0] + ": no draw of the capture writes a colour or depth target";
  return error.empty() ? best : nullptr;
}

// The textures to draft: the G-buffer draw's targets, then frame-sized ones later passes write.
std::vector<const RdcTexture*> draftTextures(const RdcListing& l, const RdcPass& gbuffer, uint32_t after,
                                             std::vector<std::string>& summary) {
  std::vector<const RdcTexture*> out;
  auto add = [&](const std::string& name, const std::string& why) {
    const RdcTexture* t = findTexture(l, name);
    if (!t || std::find(out.begin(), out.end(), t) != out.end()) return;
    if (storageFormatName(t->format).empty() || t->samples > 1 || t->depth > 1 || t->layers > 1) {
      summary.push_back("left out " + t->name + " (" + t->format + "): a format or shape a layout cannot hold");
      return;
    }
    if (!out.empty() && (t->width != out[0]->width || t->height != out[0]->height) && why.empty()) return;
    out.push_back(t);
    if (!why.empty()) summary.push_back("target " + t->name + ": " + why);
  };
  for (const std::string& name : gbuffer.outputs) add(name, "");
  if (!gbuffer.depthTarget.empty()) add(gbuffer.depthTarget, "");
  if (out.empty()) return out;
  for (const RdcPass& p : l.passes)
    if (p.firstEvent > after)
      for (const std::string& name : p.writes) {
        const RdcTexture* t = findTexture(l, name);
        if (t && t->width == out[0]->width && t->height == out[0]->height)
          add(name, "written after the G-buffer pass, by " + p.name);
      }
  return out;
}

}  // namespace

namespace {

// The draft's targets (no quantities yet) and their texels, read as the import will read them:
// after the pass that last writes each (or at --event / --pass).
bool readTargets(const SuggestRequest& r, const RdcListing& listing, const RdcPass& pass,
                 const std::vector<const RdcTexture*>& textures, nlohmann::json& draft, FrameSnapshot& raw,
                 std::string& error) {
  const uint32_t readAt = r.event ? r.event : r.pass.empty() ? 0 : pass.lastEvent;
  std::set<std::string> targetNames;
  std::vector<std::string> sources;
  for (const RdcTexture* t : textures) {
    sources.push_back(sourceName(listing, *t));
    draft["targets"].push_back({{"name", targetName(t->name, targetNames)}, {"format", storageFormatName(t->format)},
                                {"source", {{"renderdoc", sources.back()}}}, {"quantities", nlohmann::json::array()}});
  }
  r.progress("reading the texels of " + std::to_string(textures.size()) + " targets");
  std::vector<RdcTexels> texels;
  if (!readRenderDocTexels(r.inputs[0], readAt, sources, texels, error, r.replay)) return false;
  ImportInput in;
  if (!parseLayout(draft, "draft", in.layout, error)) return false;
  for (size_t k = 0; k < texels.size() && k < in.layout.targets.size(); ++k) {
    const std::string& target = in.layout.targets[k].name;
    in.renderdocSizes[target] = {texels[k].texture.width, texels[k].texture.height};
    in.renderdocTexels[target] = std::move(texels[k].bytes);
  }
  return importFrame(in, raw, error);
}

// What the channels hold: depth targets first (they say where surfaces are), then the rest; unnamed
// textures' targets named by what they hold ("position", "normal"). `frame` gets the drafted layout.
bool guessTargets(nlohmann::json& draft, const std::vector<const RdcTexture*>& textures, const RdcPass& pass,
                  const FrameSnapshot& raw, FrameSnapshot& frame, SurfaceMask& surface, std::string& error) {
  std::set<std::string> quantityNames;
  for (bool depthPass : {true, false}) {
    for (uint32_t t = 0; t < textures.size(); ++t) {
      const StorageFormat& f = raw.layout.targets[t].format;
      if (f.depth != depthPass) continue;
      const bool later = std::find(pass.outputs.begin(), pass.outputs.end(), textures[t]->name) == pass.outputs.end();
      draft["targets"][t]["quantities"] =
          guessQuantities(said(*textures[t]), f, &raw.images[t].image, surface, quantityNames, later);
    }
    if (!draftFrame(draft, raw, frame, error)) return false;
    if (depthPass) surface = surfaceOf(frame);
  }
  std::set<std::string> renamed;
  for (size_t t = 0; t < textures.size(); ++t) {
    const nlohmann::json& qs = draft["targets"][t]["quantities"];
    const std::string base = textures[t]->autoName && !qs.empty() ? qs[0]["quantity"].get<std::string>() : textures[t]->name;
    draft["targets"][t]["name"] = targetName(base, renamed);
  }
  return draftFrame(draft, raw, frame, error);
}

}  // namespace

bool suggestFromRenderDoc(const SuggestRequest& r, Suggestion& out, std::string& error) {
  const std::string& rdc = r.inputs[0];
  r.progress("listing " + rdc + " (RenderDoc replays it)");
  RdcListing listing;
  if (!listRenderDocCapture(rdc, listing, error, r.replay)) return false;
  const RdcPass* pass = gbufferPass(listing, r, error);
  if (!pass) return false;
  const uint32_t event = r.event ? r.event : pass->lastEvent;
  out.summary.push_back("G-buffer pass: " + pass->name + " (events " + std::to_string(pass->firstEvent) + ".." +
                        std::to_string(pass->lastEvent) + "; its last draw, event " + std::to_string(pass->boundAt) +
                        ", writes " + std::to_string(pass->outputs.size()) + " colour target(s)" +
                        (pass->depthTarget.empty() ? "" : " and a depth target") + ")");
  r.progress("reading the buffers bound at event " + std::to_string(pass->boundAt));
  std::map<uint32_t, RdcPass> states;
  std::string skipped;
  if (!readDrawState(rdc, {event}, true, states, skipped, error, r.replay)) return false;
  if (!skipped.empty()) {
    error = rdc + ": RenderDoc's replay crashed reading the state at event " + skipped + " (give another --event)";
    return false;
  }
  const RdcPass& bound = states[event];
  const std::vector<const RdcTexture*> textures = draftTextures(listing, *pass, pass->lastEvent, out.summary);
  if (textures.empty()) {
    error = rdc + ": the G-buffer pass's targets have no format a layout can hold";
    return false;
  }
  nlohmann::json draft = {{"format", "gblens-layout"}, {"version", 1},
                          {"name", "draft for " + std::filesystem::path(rdc).filename().string() +
                                       " (gblens import --suggest-layout: check every \"guess\")"},
                          {"targets", nlohmann::json::array()}};
  FrameSnapshot raw, frame;
  SurfaceMask surface;
  if (!readTargets(r, listing, *pass, textures, draft, raw, error) ||
      !guessTargets(draft, textures, *pass, raw, frame, surface, error))
    return false;
  CameraEvidence evidence = evidenceOf(frame, surface);
  evidence.clipYUp = listing.api != "Vulkan" || bound.viewport[3] < 0.0;
  evidence.clipDepthGl = listing.api == "OpenGL";
  r.progress("searching " + std::to_string(bound.buffers.size()) + " bound buffers for the camera");
  const FoundCamera found = searchCamera(bound.buffers, evidence);
  out.summary.insert(out.summary.end(), found.summary.begin(), found.summary.end());
  if (found.found) {
    refineWithCamera(draft, frame, surface, found.layout, found.converted, found.positionsChecked, found.positionSpace,
                     out.summary);
    draft["camera"] = found.camera;
  }
  Layout check;
  if (!parseLayout(draft, "draft", check, error)) return false;  // a draft that does not parse is a bug here
  out.layout = draft;
  return true;
}

}  // namespace gb
