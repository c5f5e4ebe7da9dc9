// `gblens attach --suggest`: a draft layout from the layer's report of one frame's render passes
// (live.h draftLiveLayout). The same guesses as `import --suggest-layout` where no texels are at hand:
// the G-buffer pass is the one writing the most colour attachments (and a depth attachment), its
// attachments and the frame-sized ones later passes write are the targets, named live as the report
// names them; what the channels hold is guessed from the image's name and format (suggest_guess.h).
#include <cstdio>
#include <set>

#include "renderer/core/layout_json.h"
#include "views/capture/live.h"
#include "views/capture/suggest_guess.h"

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
                    a.value("height", 0u), a.value("store_patched", false) ? "  (not stored by the application: gblens stores it)" : "",
                    a.value("why", "").empty() ? "" : ("  * " + a.value("why", "")).c_str());
      if (usable(a)) out += "                source: " + liveSource(p, a).dump() + "\n";
    }
  }
  return out;
}

json draftLiveLayout(const json& report, std::vector<std::string>& summary) {
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
  auto add = [&](const json& pass, const json& a, bool later) {
    StorageFormat format;
    if (!parseStorageFormat(a.value("format", ""), format)) return;
    if (later && (a.value("width", 0u) != width || a.value("height", 0u) != height)) return;
    if (!width) width = a.value("width", 0u), height = a.value("height", 0u);
    const std::string image = a.value("image", "");
    if (!image.empty() && !images.insert(image).second) return;  // a later pass writing the same image again
    json quantities = guessQuantities(image, format, nullptr, SurfaceMask{}, quantityNames, later);
    const std::string base = !image.empty() ? image : !quantities.empty() ? quantities[0].value("quantity", "target") : "target";
    draft["targets"].push_back({{"name", targetName(base, targetNames)}, {"format", a.value("format", "")},
                                {"source", liveSource(pass, a)}, {"quantities", quantities}});
    if (later) summary.push_back("target " + draft["targets"].back().value("name", "") + ": written after the G-buffer pass, by " + passName(pass));
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
