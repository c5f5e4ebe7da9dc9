// What names say (see suggest_guess.h): a table of words in texture, pass and channel names.
#include "views/infer/suggest_guess.h"

#include <algorithm>
#include <cmath>
#include <map>
#include <regex>
#include <sstream>

namespace gb {

namespace {

// Words in texture, pass and channel names and the quantity each names (one table; lower case).
struct Word {
  const char* word;
  QuantityKind kind;
};
const Word kWords[] = {
    {"albedo", QuantityKind::Albedo},      {"diffuse", QuantityKind::Albedo},       {"diffcol", QuantityKind::Albedo},
    {"color", QuantityKind::Albedo},       {"colour", QuantityKind::Albedo},        {"basecolor", QuantityKind::BaseColor},
    {"base", QuantityKind::BaseColor},     {"normal", QuantityKind::Normal},        {"normals", QuantityKind::Normal},
    {"worldnormal", QuantityKind::Normal}, {"nrm", QuantityKind::Normal},           {"n", QuantityKind::Normal},
    {"depth", QuantityKind::Depth},        {"scenedepth", QuantityKind::Depth},     {"z", QuantityKind::Depth},
    {"zdepth", QuantityKind::Depth},       {"position", QuantityKind::Position},    {"pos", QuantityKind::Position},
    {"worldposition", QuantityKind::Position}, {"worldpos", QuantityKind::Position}, {"p", QuantityKind::Position},
    {"emission", QuantityKind::Emission},  {"emissive", QuantityKind::Emission},    {"emit", QuantityKind::Emission},
    {"roughness", QuantityKind::Roughness}, {"rough", QuantityKind::Roughness},     {"metallic", QuantityKind::Metallic},
    {"metalness", QuantityKind::Metallic}, {"metal", QuantityKind::Metallic},       {"specular", QuantityKind::Specular},
    {"spec", QuantityKind::Specular},      {"occlusion", QuantityKind::Occlusion},  {"ambientocclusion", QuantityKind::Occlusion},
    {"ao", QuantityKind::Occlusion},       {"ssao", QuantityKind::Occlusion},       {"shadow", QuantityKind::Shadow},
    {"motion", QuantityKind::Motion},      {"velocity", QuantityKind::Motion},      {"vector", QuantityKind::Motion},
    {"id", QuantityKind::Id},              {"indexob", QuantityKind::Id},           {"indexma", QuantityKind::Id},
    {"objectid", QuantityKind::Id},        {"materialid", QuantityKind::Id},        {"index", QuantityKind::Id},
    {"stencil", QuantityKind::Stencil},    {"combined", QuantityKind::Radiance},    {"hdr", QuantityKind::Radiance},
    {"lighting", QuantityKind::Radiance},  {"radiance", QuantityKind::Radiance},    {"beauty", QuantityKind::Radiance},
    {"finalimage", QuantityKind::Radiance}, {"final", QuantityKind::Display},       {"display", QuantityKind::Display},
    {"swapchain", QuantityKind::Display},  {"ldr", QuantityKind::Display},          {"coverage", QuantityKind::Count},
    {"count", QuantityKind::Count},        {"mist", QuantityKind::Scalar},
};

std::string lowerCase(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

// "GBuffer.AlbedoSpec" -> gbuffer, albedo, spec; "normal_shadow" -> normal, shadow.
std::vector<std::string> words(const std::string& text) {
  std::vector<std::string> out;
  std::string cur;
  auto flush = [&] {
    if (!cur.empty()) out.push_back(cur);
    cur.clear();
  };
  for (size_t i = 0; i < text.size(); ++i) {
    const unsigned char c = static_cast<unsigned char>(text[i]);
    if (!std::isalnum(c)) {
      flush();
      continue;
    }
    // camelCase: a capital after a small letter starts a word (whole words first: "BaseColor").
    if (std::isupper(c) && i > 0 && std::islower(static_cast<unsigned char>(text[i - 1]))) flush();
    cur += char(std::tolower(c));
  }
  flush();
  return out;
}


}  // namespace

// The quantities a name says, in order: the whole name first ("basecolor"), then its words.
std::vector<QuantityKind> namedKinds(const std::string& name) {
  std::vector<QuantityKind> kinds;
  auto lookup = [](const std::string& w, QuantityKind& k) {
    for (const Word& e : kWords)
      if (w == e.word) {
        k = e.kind;
        return true;
      }
    return false;
  };
  std::string joined;
  for (const std::string& w : words(name)) joined += w;
  QuantityKind k;
  const std::vector<std::string> ws = words(name);
  if (lookup(joined, k)) return {k};
  for (const std::string& w : ws)
    if (lookup(w, k) && std::find(kinds.begin(), kinds.end(), k) == kinds.end()) kinds.push_back(k);
  return kinds;
}

std::string storageFormatName(const std::string& r) {
  static const std::map<std::string, std::string> depth = {
      {"D32S8", "d32s8"}, {"D24S8", "d24s8"}, {"D32", "d32f"}, {"D32_FLOAT", "d32f"}, {"D16", "d16"}, {"D16_UNORM", "d16"},
      {"R10G10B10A2_UNORM", "rgb10a2_unorm"},
      // B8G8R8A8: the replay swaps R and B back (renderdoc_replay.py), as the layer does live.
      {"B8G8R8A8_UNORM", "rgba8_unorm"}, {"B8G8R8A8_SRGB", "rgba8_srgb"}};
  if (auto it = depth.find(r); it != depth.end()) return it->second;
  static const std::regex re("(R(\\d+))(G\\2)?(B\\2)?(A\\2)?_(UNORM|SNORM|SRGB|UINT|FLOAT)");
  std::smatch m;
  if (!std::regex_match(r, m, re)) return "";
  const std::string channels = std::string("r") + (m[3].matched ? "g" : "") + (m[4].matched ? "b" : "") + (m[5].matched ? "a" : "");
  if (m[4].matched && !m[3].matched) return "";
  const std::string type = m[6];
  const std::string suffix = type == "FLOAT" ? "f" : "_" + lowerCase(type);
  const std::string text = channels + m[2].str() + suffix;
  StorageFormat f;
  return parseStorageFormat(text, f) ? text : "";
}

std::string targetName(const std::string& text, std::set<std::string>& used) {
  std::string n;
  for (const std::string& w : words(text)) n += (n.empty() ? "" : "_") + w;
  if (n.empty() || std::isdigit(static_cast<unsigned char>(n[0]))) n = "target_" + n;
  std::string unique = n;
  for (int i = 2; used.count(unique); ++i) unique = n + "_" + std::to_string(i);
  used.insert(unique);
  return unique;
}

}  // namespace gb
