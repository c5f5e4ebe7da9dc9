// `gblens attach --suggest`: a draft layout from the layer's report of one frame's render passes
// (suggest_live.h draftLiveLayout): the frame's structure decides the G-buffer pass and the targets
// (roles.h), named live as the report names them, every channel first as stored; the first frame
// streamed under it decides what the channels hold, as `import --suggest-layout` decides (infer.h).
#include <cstdio>
#include <map>
#include <set>

#include "renderer/core/layout_json.h"
#include "views/import/import.h"
#include "views/live/live.h"
#include "views/infer/suggest_live.h"
#include "views/infer/suggest.h"
#include "views/infer/roles.h"
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

// The live source that picks a storage image a dispatch binds: its debug name, else where it is
// bound (in the innermost debug label open at the dispatch, when there is one).
json storageSource(const json& e) {
  const std::string name = !e.value("image", "").empty() ? e.value("image", "") : e.value("view", "");
  if (!name.empty()) return {{"live", {{"name", name}}}};
  json pick = {{"storage", {{"set", e.value("set", 0)}, {"binding", e.value("binding", 0)}}}};
  const json labels = e.value("labels", json::array());
  if (!labels.empty()) pick["pass"] = labels.back();
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
    for (const json& e : p.value("storage_after", json::array())) {
      const std::string image = e.value("image", ""), fmt = e.value("format", "");
      out += format("       %-8s %-20s %-32s %-14s %ux%u  (bound by a compute dispatch after it, set %u binding %u)%s\n",
                    "storage", image.empty() ? "(unnamed)" : image.c_str(), e.value("vk_format", "").c_str(),
                    fmt.empty() ? "-" : fmt.c_str(), e.value("width", 0u), e.value("height", 0u), e.value("set", 0u),
                    e.value("binding", 0u), e.value("why", "").empty() ? "" : ("  * " + e.value("why", "")).c_str());
      if (!fmt.empty() && e.value("why", "").empty()) out += "                source: " + storageSource(e).dump() + "\n";
    }
  }
  return out;
}

namespace {

// An attachment's image as the frame's structure names it: the layer's id, else its debug name.
std::string imageKey(const json& pass, const json& a) {
  if (a.contains("image_id")) return "#" + std::to_string(a.value("image_id", 0));
  if (!a.value("image", "").empty()) return a.value("image", "");
  return "pass " + std::to_string(pass.value("ordinal", 0)) + " " + a.value("role", "");
}

// The layer's report as roles.h reads it: passes in recording order (pass k spans 2k; what reads an
// image during pass k reads at 2k, between passes k and k + 1 at 2k + 1).
// A list member of a report by reference (value() would copy it: the attachments are kept by address).
const json& listOf(const json& j, const char* key) {
  static const json empty = json::array();
  return j.contains(key) && j[key].is_array() ? j[key] : empty;
}

FrameFacts factsOf(const json& report, std::vector<const json*>& attachments) {
  FrameFacts f;
  std::map<std::string, std::vector<uint32_t>> reads;
  for (const json& p : listOf(report, "passes")) {
    const uint32_t at = 2u * uint32_t(p.value("ordinal", 0));
    PassFacts pf{passName(p), at, at, {}};
    for (const json& a : listOf(p, "attachments")) {
      const std::string role = a.value("role", "");
      if (role == "other") continue;
      PassFacts::Output o{imageKey(p, a), role == "depth", true, true, usable(a), a.value("width", 0u), a.value("height", 0u)};
      if (a.contains("store") && a["store"].is_string()) o.stored = a["store"] == "store";
      if (a.contains("stencil_store") && a["stencil_store"].is_string()) o.stencilStored = a["stencil_store"] == "store";
      if (a.value("presented", false)) f.presented.insert(o.image);
      pf.outputs.push_back(o);
      attachments.push_back(&a);
    }
    for (const char* key : {"reads", "reads_after"})
      if (p.contains(key)) {
        f.readsKnown = true;
        for (const json& id : p[key]) reads["#" + std::to_string(id.get<int>())].push_back(at + (key[5] ? 1 : 0));
      }
    f.passes.push_back(pf);
  }
  for (const json& id : report.value("presented", json::array())) f.presented.insert("#" + std::to_string(id.get<int>()));
  for (auto& [image, events] : reads) f.reads.push_back({image, events});
  return f;
}

// The first draft's quantities: every channel as stored (the streamed texels decide the rest).
json storedQuantity(const char* kind, const char* name, json channels) {
  json q = json::object();
  q["quantity"] = kind;
  q["name"] = name;
  q["channels"] = std::move(channels);
  return q;
}

json storedQuantities(const StorageFormat& f) {
  json q = json::array();
  if (f.depth) {
    q.push_back(storedQuantity("scalar", "depth", json::array({0})));
    if (f.stencil) q.push_back(storedQuantity("scalar", "stencil", json::array({1})));
    return q;
  }
  json channels = json::array();
  for (uint32_t c = 0; c < f.channels; ++c) channels.push_back(c);
  q.push_back(storedQuantity(f.channels == 1 ? "scalar" : "vector", f.channels == 1 ? "scalar" : "vector", channels));
  return q;
}

// Storage images that compute dispatches bind, the size of the draft's targets, none of them: a
// G-buffer written by compute (a visibility buffer's resolve, compute deferred) is not drafted (a
// storage image may be read or written; nothing in the frame's structure says which, nor what it
// holds), so the summary names each with the source that picks it, for the user to add. How many.
size_t noteStorageImages(const json& report, const json& draft, std::vector<std::string>& summary) {
  std::set<std::string> sources;
  for (const json& t : draft["targets"]) sources.insert(t["source"].dump());
  uint32_t width = 0, height = 0;
  for (const json& p : listOf(report, "passes"))
    for (const json& a : listOf(p, "attachments"))
      if (!width && sources.count(liveSource(p, a).dump())) width = a.value("width", 0u), height = a.value("height", 0u);
  std::set<int> seen;
  for (const json& p : listOf(report, "passes"))
    for (const json& e : listOf(p, "storage_after")) {
      const json source = storageSource(e);
      if (e.value("width", 0u) != width || e.value("height", 0u) != height || e.value("format", "").empty() ||
          !e.value("why", "").empty() || e.value("samples", 1u) != 1u || sources.count(source.dump()) ||
          !seen.insert(e.value("image_id", 0)).second)
        continue;
      const std::string image = e.value("image", "");
      summary.push_back(notDraftedLine("storage image " + (image.empty() ? "(unnamed)" : image), e.value("format", ""),
                                       "bound by compute after " + passName(p), source));
    }
  return seen.size();
}

}  // namespace

json draftLiveLayout(const json& report, std::vector<std::string>& summary, std::vector<LiveTargetFacts>* facts) {
  json draft = {{"format", "gblens-layout"}, {"version", 1},
                {"name", "draft (gblens attach --suggest: check every \"guess\")"}, {"targets", json::array()}};
  std::vector<const json*> attachments;
  const FrameFacts frame = factsOf(report, attachments);
  const PassRoles roles = decideRoles(frame);
  if (facts) facts->clear();
  if (roles.gbuffer < 0 || roles.targets.empty()) {
    summary.push_back("no render pass writes an attachment a layout can hold");
    return draft;
  }
  summary.insert(summary.end(), roles.notes.begin(), roles.notes.end());
  const json& passes = listOf(report, "passes");
  std::set<std::string> targetNames, quantityNames;
  for (const PassTarget& r : roles.targets) {
    // The report's attachment of this output: passes and their non-"other" attachments in order.
    size_t index = 0;
    for (size_t p = 0; p < r.pass; ++p) index += frame.passes[p].outputs.size();
    const json& a = *attachments[index + r.output];
    const json& pass = passes[r.pass];
    StorageFormat format;
    if (!parseStorageFormat(a.value("format", ""), format)) continue;
    json quantities = storedQuantities(format);
    for (json& q : quantities) {  // unique names across targets
      std::string n = q["name"].get<std::string>(), base = n;
      for (int i = 2; quantityNames.count(n); ++i) n = base + std::to_string(i);
      quantityNames.insert(n);
      q["name"] = n;
    }
    const std::string image = a.value("image", "");
    draft["targets"].push_back({{"name", targetName(!image.empty() ? image : format.depth ? "depth" : "target", targetNames)},
                                {"format", a.value("format", "")}, {"source", liveSource(pass, a)}, {"quantities", quantities}});
    if (facts)
      facts->push_back({image, r.writer, r.readLater, r.presented, r.stencilStored, pass.value("ordinal", 0)});
    if (r.writer == Writer::Later)
      summary.push_back("target " + draft["targets"].back().value("name", "") + ": written after the G-buffer pass, by " +
                        passName(pass));
  }
  std::vector<std::string> storage;
  if (noteStorageImages(report, draft, storage) > 0 && roles.forward)  // a visibility buffer's frame looks forward
    computeMayWriteTheGBuffer(summary, storage.size());
  summary.insert(summary.end(), storage.begin(), storage.end());
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
        const std::string note = "shown as stored: a " + was + " quantity needs the camera (give \"camera\", then \"quantity\": \"" +
                                 was + "\")";
        json guess = j.contains("guess") && j["guess"].is_object() ? j["guess"] : json::object();
        if (j.contains("guess") && j["guess"].is_string()) guess["evidence"] = j["guess"];
        guess["quantity"] = "unknown";
        guess["evidence"] = guess.value("evidence", "") + "; " + note;
        json stored = {{"quantity", q.channels.size() == 1 ? "scalar" : "vector"}, {"name", q.name}, {"channels", j["channels"]},
                       {"guess", guess}};
        j = stored;
        if (summary) summary->push_back(q.name + ": shown as stored values (a " + was + " quantity needs the layout's camera)");
      }
  }
}

// What the texels say, decided by the evidence as import --suggest-layout decides a capture's
// (infer.h): the targets and their sources stay; an unnamed image's target is named by what it holds.
bool refineLiveDraft(json& draft, const std::vector<LiveTargetFacts>& facts, const FrameSnapshot& raw, uint64_t appFrame,
                     const std::vector<RdcBinding>& buffers, FrameSnapshot& frame, std::vector<std::string>& summary,
                     std::string& error) {
  json& targets = draft["targets"];
  if (targets.size() != raw.layout.targets.size() || facts.size() != targets.size()) {
    error = "the streamed frame holds " + std::to_string(raw.layout.targets.size()) + " targets, the draft " +
            std::to_string(targets.size());
    return false;
  }
  InferInput in;
  std::vector<bool> unnamed;
  size_t looked = 0;
  for (size_t t = 0; t < targets.size(); ++t) {
    InferTarget target;
    target.label = facts[t].label;
    target.format = raw.layout.targets[t].format;
    target.texels = raw.images[t].present() ? &raw.images[t].image : nullptr;
    looked += target.texels != nullptr;
    target.writer = facts[t].writer;
    target.readLater = facts[t].readLater;
    target.presented = facts[t].presented;
    target.stencilStored = facts[t].stencilStored;
    if (facts[t].writer != Writer::Later) in.livePass = facts[t].pass;
    in.targets.push_back(target);
    unnamed.push_back(facts[t].label.empty());
  }
  in.buffers = buffers;
  in.bufferSource = "live";
  in.clipYKnown = false;  // the layer does not report the viewport's sign
  const InferOutput inferred = inferLayout(in);
  const std::vector<std::string> was = [&] {
    std::vector<std::string> n;
    for (const json& t : targets) n.push_back(t.value("name", "target"));
    return n;
  }();
  applyInference(draft, inferred, unnamed);
  for (size_t t = 0; t < targets.size(); ++t)  // what was said of a target under its first name
    for (std::string& line : summary)
      if (line.rfind("target " + was[t] + ":", 0) == 0)
        line = "target " + targets[t]["name"].get<std::string>() + line.substr(7 + was[t].size());
  summary.insert(summary.end(), inferred.summary.begin(), inferred.summary.end());
  summary.push_back("the channels decided from the texels of application frame " + std::to_string(appFrame) + " (" +
                    std::to_string(looked) + " of " + std::to_string(targets.size()) + " targets streamed)");
  draft["name"] = "draft (gblens attach --suggest, from the texels of one frame: check every \"guess\")";
  return draftFrame(draft, raw, frame, error);
}

}  // namespace gb
