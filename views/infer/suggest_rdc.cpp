// A draft layout from a RenderDoc capture (see suggest.h): the frame's structure (what each pass writes
// and stores, when each texture is read, what is presented) decides the G-buffer pass and the targets
// (roles.h); their texels are read as the import will read them; what each channel group holds and
// the camera (searched in the buffers bound at the G-buffer pass's last draw) are decided by the
// evidence (infer.h).
#include <algorithm>
#include <filesystem>
#include <map>

#include "renderer/core/layout_json.h"
#include "views/import/import.h"
#include "views/import/import_renderdoc.h"
#include "views/infer/roles.h"
#include "views/infer/suggest.h"
#include "views/infer/suggest_guess.h"

namespace gb {

namespace {

const RdcTexture* findTexture(const RdcListing& l, const std::string& name) {
  for (const RdcTexture& t : l.textures)
    if (t.name == name || "#" + std::to_string(t.id) == name) return &t;
  return nullptr;
}

// How a layout names a texture: by name when no other texture has it, else by id.
std::string sourceName(const RdcListing& l, const RdcTexture& t) {
  const size_t same = size_t(std::count_if(l.textures.begin(), l.textures.end(), [&](const RdcTexture& o) { return o.name == t.name; }));
  return same == 1 && !t.name.empty() && !t.autoName ? t.name : "#" + std::to_string(t.id);
}

// A multisampled texture is holdable too: the import reads every sample (the evidence reads sample 0,
// a value the renderer stored).
bool holdable(const RdcTexture& t) { return !storageFormatName(t.format).empty() && t.depth == 1 && t.layers == 1; }

// The frame's structure as roles.h reads it: the passes with a draw, their outputs at the last draw
// with the application's store ops, and when each texture is read.
FrameFacts factsOf(const RdcListing& l, std::vector<const RdcPass*>& passes) {
  FrameFacts f;
  for (const RdcPass& p : l.passes) {
    if (!p.boundAt || (p.outputs.empty() && p.depthTarget.empty())) continue;
    PassFacts pf{p.name, p.firstEvent, p.lastEvent, {}};
    auto add = [&](const std::string& name, bool depth) {
      const RdcTexture* t = findTexture(l, name);
      if (!t) return;
      PassFacts::Output o{name, depth, true, true, holdable(*t), t->width, t->height};
      const bool stencil = t->format.find("S8") != std::string::npos;
      for (const RdcPass::Store& st : p.stores)
        if (st.texture == name) {
          o.stored = st.store.empty() || st.store == "store";
          o.stencilStored = !stencil || st.stencilStore.empty() || st.stencilStore == "store";
        }
      pf.outputs.push_back(o);
    };
    for (const std::string& name : p.outputs) add(name, false);
    if (!p.depthTarget.empty()) add(p.depthTarget, true);
    f.passes.push_back(pf);
    passes.push_back(&p);
  }
  for (const RdcTexture& t : l.textures) {
    f.reads.push_back({t.name, t.reads});
    f.readsKnown = f.readsKnown || !t.reads.empty();
    if (t.presented) f.presented.insert(t.name);
  }
  return f;
}

// Textures the size of the draft's that dispatches bind as storage images, none of the draft's: a
// G-buffer written by compute (suggest.h notDraftedLine), each named with its source. How many.
size_t noteComputeWritten(const RdcListing& l, const std::vector<const RdcTexture*>& drafted, std::vector<std::string>& summary) {
  size_t n = 0;
  for (const RdcTexture& t : l.textures) {
    if (t.computeWrites.empty() || !holdable(t) || drafted.empty() || t.width != drafted[0]->width ||
        t.height != drafted[0]->height || std::find(drafted.begin(), drafted.end(), &t) != drafted.end())
      continue;
    summary.push_back(notDraftedLine("texture " + t.name, storageFormatName(t.format),
                                     "bound for writing by the dispatch at event " + computeWriteEvents(t),
                                     {{"renderdoc", sourceName(l, t)}}));
    ++n;
  }
  return n;
}

// The pass --pass names, or the innermost one holding --event (-1: neither given).
int forcedPass(const SuggestRequest& r, const std::vector<const RdcPass*>& passes, std::string& error) {
  if (r.pass.empty() && !r.event) return -1;
  int best = -1;
  for (size_t i = 0; i < passes.size(); ++i) {
    const RdcPass& p = *passes[i];
    if (!r.pass.empty() && p.name != r.pass) continue;
    if (r.event && !(p.firstEvent <= r.event && r.event <= p.lastEvent)) continue;
    if (best < 0 || p.lastEvent - p.firstEvent < passes[size_t(best)]->lastEvent - passes[size_t(best)]->firstEvent)
      best = int(i);
  }
  if (best < 0)
    error = r.inputs[0] + (!r.pass.empty() ? ": --pass \"" + r.pass + "\": no pass of that name draws (see --list)"
                                           : ": --event " + std::to_string(r.event) + ": no pass with a draw holds it");
  return best;
}

// The draft's targets (no quantities yet) and their texels, read as the import will read them:
// after the pass that last writes each (or at --event / --pass).
bool readTargets(const SuggestRequest& r, const RdcListing& listing, uint32_t readAt,
                 const std::vector<const RdcTexture*>& textures, nlohmann::json& draft, FrameSnapshot& raw,
                 std::string& error) {
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
  for (size_t k = 0; k < texels.size() && k < in.layout.targets.size(); ++k)
    takeRenderDocTexels(in, in.layout.targets[k].name, std::move(texels[k]));
  return importFrame(in, raw, error);
}

}  // namespace

bool suggestFromRenderDoc(const SuggestRequest& r, Suggestion& out, std::string& error) {
  const std::string& rdc = r.inputs[0];
  r.progress("listing " + rdc + " (RenderDoc replays it)");
  RdcListing listing;
  if (!listRenderDocCapture(rdc, listing, error, r.replay)) return false;
  std::vector<const RdcPass*> passes;
  const FrameFacts facts = factsOf(listing, passes);
  const int forced = forcedPass(r, passes, error);
  if (!error.empty()) return false;
  const PassRoles roles = decideRoles(facts, forced);
  if (roles.gbuffer < 0 || roles.targets.empty()) {
    error = rdc + (passes.empty() ? ": no pass draws anything" : ": no draw of the capture writes a target a layout can hold");
    return false;
  }
  const RdcPass& pass = *passes[size_t(roles.gbuffer)];
  out.summary.insert(out.summary.end(), roles.notes.begin(), roles.notes.end());
  const uint32_t event = r.event ? r.event : pass.lastEvent;
  r.progress("reading the buffers bound at event " + std::to_string(pass.boundAt));
  std::map<uint32_t, RdcPass> states;
  std::string skipped;
  if (!readDrawState(rdc, {event}, true, states, skipped, error, r.replay)) return false;
  if (!skipped.empty()) {
    error = rdc + ": RenderDoc's replay crashed reading the state at event " + skipped + " (give another --event)";
    return false;
  }
  const RdcPass& bound = states[event];
  std::vector<const RdcTexture*> textures;
  for (const PassTarget& t : roles.targets)
    textures.push_back(findTexture(listing, facts.passes[t.pass].outputs[t.output].image));
  nlohmann::json draft = {{"format", "gblens-layout"}, {"version", 1},
                          {"name", "draft for " + std::filesystem::path(rdc).filename().string() +
                                       " (gblens import --suggest-layout: check every \"guess\")"},
                          {"targets", nlohmann::json::array()}};
  FrameSnapshot raw;
  const uint32_t readAt = r.event ? r.event : r.pass.empty() ? 0 : pass.lastEvent;
  if (!readTargets(r, listing, readAt, textures, draft, raw, error)) return false;
  InferInput in;
  std::vector<bool> unnamed;
  for (size_t k = 0; k < roles.targets.size(); ++k) {
    const PassTarget& role = roles.targets[k];
    InferTarget t;
    t.label = textures[k]->autoName ? "" : textures[k]->name;
    t.format = raw.layout.targets[k].format;
    t.texels = raw.images[k].present() ? &raw.images[k].image : nullptr;
    t.writer = role.writer;
    t.readLater = role.readLater;
    t.presented = role.presented;
    t.stencilStored = role.stencilStored;
    in.targets.push_back(t);
    unnamed.push_back(textures[k]->autoName);
  }
  in.buffers = bound.buffers;
  in.clipYUp = listing.api != "Vulkan" || bound.viewport[3] < 0.0;
  in.clipDepthGl = listing.api == "OpenGL";
  r.progress("searching " + std::to_string(in.buffers.size()) + " bound buffers for the camera, deciding what the " +
             std::to_string(in.targets.size()) + " targets hold");
  const InferOutput inferred = inferLayout(in);
  out.summary.insert(out.summary.end(), inferred.summary.begin(), inferred.summary.end());
  std::vector<std::string> computeWritten;
  if (noteComputeWritten(listing, textures, computeWritten) > 0 && roles.forward)
    computeMayWriteTheGBuffer(out.summary, computeWritten.size());
  out.summary.insert(out.summary.end(), computeWritten.begin(), computeWritten.end());
  applyInference(draft, inferred, unnamed);
  for (size_t k = 0; k < roles.targets.size(); ++k) {  // where each target came from, for people and tests
    const PassTarget& role = roles.targets[k];
    const PassFacts& pf = facts.passes[role.pass];
    int colour = 0;
    for (size_t o = 0; o < role.output; ++o) colour += !pf.outputs[o].depth;
    draft["targets"][k]["guess"] = {{"pass", role.pass}, {"pass_name", pf.name},
                                    {"attachment", pf.outputs[role.output].depth ? "depth" : "color " + std::to_string(colour)},
                                    {"writer", role.writer == Writer::GBuffer ? "gbuffer" : role.writer == Writer::Later ? "later" : "forward"}};
  }
  Layout check;
  if (!parseLayout(draft, "draft", check, error)) {
    error = "the draft does not parse (a bug in gblens): " + error;
    return false;
  }
  out.layout = draft;
  return true;
}

}  // namespace gb
