// A draft layout from image files (see suggest.h): each EXR layer (Blender's "ViewLayer.Normal.X",
// Unreal's "WorldNormal.R", OIIO's "N.x", a file's plain R G B A and Z) becomes a target of the
// format its channel type is; the camera is a sidecar beside the files, checked against stored
// positions when there are any.
#include <OpenImageIO/imageio.h>

#include <algorithm>
#include <filesystem>
#include <map>

#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "views/import/import.h"
#include "views/infer/suggest.h"
#include "views/infer/suggest_guess.h"

namespace gb {

namespace fs = std::filesystem;

namespace {

struct Group {
  std::string file, part, layer;  // the layer: the channel names' prefix ("" : none)
  std::vector<std::string> channels;
  std::vector<OIIO::TypeDesc> types;
};

// Component order within a layer: R G B A, X Y Z W, U V.
int componentOrder(const std::string& c) {
  static const char* order[] = {"r", "g", "b", "a", "x", "y", "z", "w", "u", "v"};
  std::string l = c;
  std::transform(l.begin(), l.end(), l.begin(), [](unsigned char ch) { return char(std::tolower(ch)); });
  for (int i = 0; i < 10; ++i)
    if (l == order[i]) return i < 4 ? i : i < 8 ? i - 4 : i - 8;
  return 10;
}

bool readGroups(const std::string& file, std::vector<Group>& out, std::string& error) {
  auto in = OIIO::ImageInput::open(file);
  if (!in) {
    error = file + ": cannot read the image (" + OIIO::geterror() + ")";
    return false;
  }
  int parts = 0;
  while (in->seek_subimage(parts, 0)) ++parts;
  for (int part = 0; part < parts && in->seek_subimage(part, 0); ++part) {
    const OIIO::ImageSpec& spec = in->spec();
    std::map<std::string, Group> layers;
    std::vector<std::string> order;
    for (int c = 0; c < spec.nchannels; ++c) {
      const std::string& n = spec.channelnames[size_t(c)];
      const size_t dot = n.rfind('.');
      std::string layer = dot == std::string::npos ? "" : n.substr(0, dot);
      const std::string component = dot == std::string::npos ? n : n.substr(dot + 1);
      if (layer.empty() && componentOrder(component) > 3) layer = component;  // a lone Z or depth: its own target
      if (!layers.count(layer)) order.push_back(layer);
      Group& g = layers[layer];
      g.file = file, g.layer = layer;
      g.part = parts > 1 ? std::to_string(part) : "";
      g.channels.push_back(n);
      g.types.push_back(spec.channelformat(c));
    }
    for (const std::string& layer : order) {
      Group g = layers[layer];
      std::vector<size_t> idx(g.channels.size());
      for (size_t i = 0; i < idx.size(); ++i) idx[i] = i;
      auto comp = [&](size_t i) { return componentOrder(g.channels[i].substr(g.channels[i].rfind('.') + 1)); };
      std::stable_sort(idx.begin(), idx.end(), [&](size_t a, size_t b) { return comp(a) < comp(b); });
      Group sorted = g;
      for (size_t i = 0; i < idx.size(); ++i) sorted.channels[i] = g.channels[idx[i]], sorted.types[i] = g.types[idx[i]];
      out.push_back(sorted);
    }
  }
  return true;
}

// The storage format a group's channels are held in exactly ("" : mixed types, or none a layout has).
std::string groupFormat(const Group& g) {
  static const char* counts[] = {"", "r", "rg", "rgb", "rgba"};
  if (g.channels.empty() || g.channels.size() > 4) return "";
  for (const OIIO::TypeDesc& t : g.types)
    if (t != g.types[0]) return "";
  const std::string c = counts[g.channels.size()];
  const OIIO::TypeDesc t = g.types[0];
  if (t == OIIO::TypeDesc::HALF) return c + "16f";
  if (t == OIIO::TypeDesc::FLOAT) return c + "32f";
  if (t == OIIO::TypeDesc::UINT32) return c + "32_uint";
  if (t == OIIO::TypeDesc::UINT16) return c + "16_unorm";
  if (t == OIIO::TypeDesc::UINT8) return c + "8_unorm";
  return "";
}

}  // namespace

bool suggestFromImages(const SuggestRequest& r, Suggestion& out, std::string& error) {
  std::vector<Group> groups;
  for (const std::string& file : r.inputs) {
    r.progress("reading the channels of " + file);
    if (!readGroups(file, groups, error)) return false;
  }
  std::set<std::string> targetNames;
  nlohmann::json targets = nlohmann::json::array();
  std::vector<std::string> labels;
  for (const Group& g : groups) {
    const std::string format = groupFormat(g);
    const std::string label = g.layer.empty() ? fs::path(g.file).stem().string() : g.layer.substr(g.layer.rfind('.') + 1);
    if (format.empty()) {
      out.summary.push_back("left out " + (g.layer.empty() ? g.file : g.layer) + ": channel types a layout format cannot hold together");
      continue;
    }
    nlohmann::json source = {{"channels", g.channels}};
    if (r.inputs.size() > 1) source["file"] = fs::path(g.file).filename().string();
    if (!g.part.empty()) source["part"] = g.part;
    targets.push_back({{"name", targetName(label, targetNames)}, {"format", format}, {"source", source},
                       {"quantities", nlohmann::json::array()}});
    labels.push_back(label);
  }
  if (targets.empty()) {
    error = r.inputs[0] + ": no channels a layout can hold";
    return false;
  }
  nlohmann::json draft = {{"format", "gblens-layout"}, {"version", 1},
                          {"name", "draft for " + fs::path(r.inputs[0]).filename().string() +
                                       " (gblens import --suggest-layout: check every \"guess\")"},
                          {"targets", targets}};
  ImportInput in;
  in.files = r.inputs;
  if (!parseLayout(draft, "draft", in.layout, error)) return false;
  r.progress("reading the pixels of " + std::to_string(labels.size()) + " layers");
  FrameSnapshot raw;
  if (!importFrame(in, raw, error)) return false;

  InferInput infer;
  for (size_t t = 0; t < labels.size(); ++t) {
    InferTarget target;
    target.label = labels[t];
    target.format = in.layout.targets[t].format;
    target.texels = raw.images[t].present() ? &raw.images[t].image : nullptr;
    // Files say nothing of passes: a layer named for light or the picture is lit colour.
    for (QuantityKind k : namedKinds(labels[t]))
      if (k == QuantityKind::Radiance || k == QuantityKind::Display) target.writer = Writer::Later;
    infer.targets.push_back(target);
  }
  // The camera: a sidecar beside the files (Blender's script writes camera.json there).
  std::string sidecar;
  for (const std::string& f : r.inputs)
    if (std::error_code ec; sidecar.empty() && fs::is_regular_file(fs::path(f).parent_path() / "camera.json", ec))
      sidecar = (fs::path(f).parent_path() / "camera.json").string();
  if (sidecar.empty()) {
    out.summary.push_back("camera: no camera.json beside the files");
  } else {
    ImportInput withCamera = in;
    withCamera.cameraFile = sidecar;
    FrameSnapshot imported;
    if (!importFrame(withCamera, imported, error)) return false;
    infer.given = imported.layout.camera;
    infer.givenConverted = imported.camera;
    infer.givenNote = "the sidecar beside the files (" + sidecar + "; its own fields say its conventions)";
  }
  const InferOutput inferred = inferLayout(infer);
  out.summary.insert(out.summary.end(), inferred.summary.begin(), inferred.summary.end());
  applyInference(draft, inferred, std::vector<bool>(labels.size(), false));
  Layout check;
  if (!parseLayout(draft, "draft", check, error)) {
    error = "the draft does not parse (a bug in gblens): " + error;
    return false;
  }
  out.layout = draft;
  return true;
}

}  // namespace gb
