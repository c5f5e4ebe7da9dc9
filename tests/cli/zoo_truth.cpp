// Holding a draft to the gbuffer_zoo truth (zoo_truth.h): no gblens code decides here, only the truth
// file's own words and the draft's JSON.
#include "tests/support/test_paths.h"
#include "tests/cli/zoo_truth.h"

#include <algorithm>
#include <fstream>
#include <map>
#include <set>

namespace gb::zoo {

using json = nlohmann::json;

const char* const kModes[7] = {"world_tbn", "forward", "lighting_depth", "stencil_dontcare", "linear_depth", "view_oct", "y_down"};

std::string truthPath(const std::string& mode) { return std::string(ZOO_DIR) + "/truth/" + mode + ".json"; }

json readJson(const std::string& path) {
  std::ifstream in(path);
  if (!in) return nullptr;
  return json::parse(in, nullptr, false);
}

std::string Verdict::text() const {
  std::string t = std::to_string(right) + " right, " + std::to_string(unknown) + " unknown, " + std::to_string(wrong.size()) +
                  " wrong";
  for (const std::string& w : wrong) t += "\n  " + w;
  return t;
}

namespace {

bool isDepthFormat(const std::string& vk) { return vk.find("_D16") != std::string::npos || vk.find("_D24") != std::string::npos || vk.find("_D32") != std::string::npos; }

// The fields a truth quantity states that a draft must match, with the layout's defaults.
const std::vector<std::pair<std::string, json>>& fieldsOf(const std::string& kind) {
  static const std::vector<std::pair<std::string, json>> none;
  static const std::map<std::string, std::vector<std::pair<std::string, json>>> fields = {
      {"position", {{"space", "world"}}},
      {"normal", {{"space", "view"}, {"encoding", "xyz"}, {"normalized", true}}},
      {"albedo", {{"encoding", "linear"}}},
      {"display", {{"encoding", "linear"}}},
      {"depth", {{"encoding", "eye"}, {"scale", 1.0}, {"background", nullptr}}}};
  auto it = fields.find(kind);
  return it == fields.end() ? none : it->second;
}

// What the evidence must decide (the rest may be drafted as stored values).
bool mustDecide(const std::string& kind) {
  static const std::set<std::string> decided = {"position", "normal", "depth", "albedo", "radiance", "display", "stencil"};
  return decided.count(kind) > 0;
}

std::string where(int pass, const std::string& attachment, const json& h) {
  return "pass " + std::to_string(pass) + " " + attachment + " " + h.value("quantity", "") + " " + h["channels"].dump();
}

}  // namespace

TargetOf importTargets(const json& draft) {
  return [&draft](int pass, const std::string& attachment) -> const json* {
    for (const json& t : draft["targets"])
      if (t.contains("guess") && t["guess"].is_object() && t["guess"].value("pass", -1) == pass &&
          t["guess"].value("attachment", "") == attachment)
        return &t;
    return nullptr;
  };
}

TargetOf liveTargets(const json& draft) {
  return [&draft](int pass, const std::string& attachment) -> const json* {
    for (const json& t : draft["targets"]) {
      const json live = t["source"].value("live", json::object());
      if (live.value("pass", -1) != pass) continue;
      const bool depth = live.value("depth", false);
      if (attachment == "depth" ? depth : !depth && "color " + std::to_string(live.value("color", -1)) == attachment) return &t;
    }
    return nullptr;
  };
}

Verdict compare(const json& truth, const json& /*draft, read through targetOf*/, const TargetOf& targetOf) {
  Verdict v;
  const json gbuffer = truth["gbuffer_pass"];
  for (const json& p : truth["passes"])
    for (const json& a : p["attachments"]) {
      const int pass = p["pass"];
      const bool depth = isDepthFormat(a["vk_format"]);
      const std::string attachment = depth ? "depth" : "color " + std::to_string(a["attachment"].get<int>());
      // A later pass's own depth is no quantity of the G-buffer (the draft leaves it out).
      if (depth && !gbuffer.is_null() && pass != gbuffer.get<int>()) continue;
      const json* t = targetOf(pass, attachment);
      for (const json& h : a.value("holds", json::array())) {
        const std::string kind = h["quantity"];
        if (kind == "none") continue;
        const json* q = nullptr;
        if (t)
          for (const json& d : (*t)["quantities"])
            if (d["channels"] == h["channels"] || (kind == "stencil" && d.value("quantity", "") == "stencil")) q = &d;
        const std::string at = where(pass, attachment, h);
        if (!q) {
          (mustDecide(kind) ? v.wrong.push_back(at + ": not in the draft") : (void)++v.unknown);
          continue;
        }
        const json guess = q->value("guess", json::object());
        const std::string drafted = q->value("quantity", "");
        if (drafted == "scalar" || drafted == "vector" || guess.value("quantity", "") == "unknown") {
          if (mustDecide(kind)) v.wrong.push_back(at + ": drafted as unknown (" + guess.value("evidence", "") + ")");
          else ++v.unknown;
          continue;
        }
        if (drafted != kind) {
          v.wrong.push_back(at + ": drafted as " + drafted + " (" + guess.value("evidence", "") + ")");
          continue;
        }
        const json undecided = guess.value("undecided", json::array());
        std::string differs;
        for (const auto& [field, def] : fieldsOf(kind)) {
          if (!h.contains(field) || std::find(undecided.begin(), undecided.end(), field) != undecided.end()) continue;
          const json want = h[field], got = q->contains(field) ? (*q)[field] : def;
          if (want != got && !(want.is_number() && got.is_number() && want.get<double>() == got.get<double>()))
            differs += " " + field + " " + got.dump() + " (truth " + want.dump() + ")";
        }
        if (differs.empty()) ++v.right;
        else v.wrong.push_back(at + ":" + differs);
      }
      // Nothing drafted that the truth does not hold: a decided quantity on channels the truth
      // calls padding or gives to another quantity is wrong too.
      if (!t) continue;
      for (const json& d : (*t)["quantities"]) {
        const std::string drafted = d.value("quantity", "");
        const json guess = d.value("guess", json::object());
        if (drafted == "scalar" || drafted == "vector" || guess.value("quantity", "") == "unknown") continue;
        bool held = false;
        for (const json& h : a.value("holds", json::array()))
          held = held || (h["quantity"] == drafted && (h["channels"] == d["channels"] || drafted == "stencil"));
        if (!held) v.wrong.push_back("pass " + std::to_string(pass) + " " + attachment + " " + d["channels"].dump() +
                                     ": drafted as " + drafted + ", which the truth does not hold there");
      }
    }
  return v;
}

std::string compareCamera(const json& truth, const json& draft) {
  const json& tc = truth["camera"];
  if (!draft.contains("camera")) return "the draft has no camera";
  const json& c = draft["camera"];
  std::map<std::string, int> offsets;
  for (const json& m : tc["members"]) {  // an array's first element is the matrix of this frame
    std::string name = m["name"];
    if (name.size() > 3 && name.compare(name.size() - 3, 3, "[0]") == 0) name.resize(name.size() - 3);
    offsets[name] = m["offset"];
  }
  const json& at = c.contains("renderdoc") ? c["renderdoc"] : c;
  std::string out;
  for (const char* key : {"view_from_world", "world_from_view", "clip_from_view", "clip_from_world"})
    if (at.contains(key) && (!offsets.count(key) || offsets[key] != at[key].value("offset", -1)))
      out += std::string(" ") + key + " at " + at[key].dump() + " (truth: " + (offsets.count(key) ? std::to_string(offsets[key]) : "none") + ")";
  if (c.value("up", "y") != tc.value("up", "y")) out += " up " + c.value("up", "y") + " (truth " + tc.value("up", "y") + ")";
  if (c.value("convention", "vulkan") != tc.value("convention", "vulkan"))
    out += " convention " + c.value("convention", "vulkan") + " (truth " + tc.value("convention", "vulkan") + ")";
  // A camera given as clip_from_world alone has no view of its own: its handedness is the split's.
  if (!at.contains("clip_from_world") && c.value("view_handedness", "right") != tc.value("view_handedness", "right"))
    out += " view_handedness " + c.value("view_handedness", "right");
  return out;
}

}  // namespace gb::zoo
