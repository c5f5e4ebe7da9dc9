// Quantity guesses for draft layouts (see suggest_guess.h): a table of names, then the texels.
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

std::string lower(std::string s) {
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

// What the texels of some channels look like at surface pixels.
struct Stats {
  size_t n = 0;
  double unitXyz = 0.0, unitXyzUnorm = 0.0;  // fraction of texels of length 1 within tolerance
  double lo = INFINITY, hi = -INFINITY;       // over the channels
  bool constant = true;
  double first = NAN;
};

Stats stats(const CpuImage& img, const SurfaceMask& s, const std::vector<uint32_t>& ch, double tol) {
  Stats st;
  size_t unit = 0, unitUnorm = 0;
  const uint32_t step = std::max(1u, img.width * img.height / 20000);
  for (uint32_t i = 0; i < img.width * img.height; i += step) {
    const uint32_t x = i % img.width, y = i / img.width;
    if (!s.surface(x, y)) continue;
    glm::dvec3 v(0.0);
    for (size_t k = 0; k < ch.size(); ++k) {
      const double c = img.value(x, y, ch[k]);
      if (k < 3) v[int(k)] = c;
      st.lo = std::min(st.lo, c), st.hi = std::max(st.hi, c);
      if (std::isnan(st.first)) st.first = c;
      st.constant = st.constant && c == st.first;
    }
    ++st.n;
    unit += std::abs(glm::length(v) - 1.0) < tol;
    unitUnorm += std::abs(glm::length(v * 2.0 - 1.0) - 1.0) < tol;
  }
  if (st.n) st.unitXyz = double(unit) / st.n, st.unitXyzUnorm = double(unitUnorm) / st.n;
  return st;
}

// The rounding of one stored channel: what "unit length" may be off by.
double tolerance(const StorageFormat& f) {
  switch (f.type) {
    case PixelType::U8:
    case PixelType::I8: return 0.03;
    case PixelType::F16: return 0.004;
    case PixelType::U16:
    case PixelType::I16: return f.packed10 ? 0.01 : 0.001;
    default: return 1e-4;
  }
}

uint32_t channelsOf(QuantityKind k, uint32_t available) {
  switch (k) {
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Position: return 3;
    case QuantityKind::Normal: return available >= 3 ? 3 : 2;
    case QuantityKind::Radiance:
    case QuantityKind::Display: return std::min(available, 4u);
    case QuantityKind::Motion: return 2;
    default: return 1;
  }
}

// A quantity's name: its kind ("normal", "albedo2"); depths by encoding ("depth" for the depth
// buffer, "eye_depth", "radial_depth").
std::string quantityName(QuantityKind k, const std::string& encoding, std::set<std::string>& used) {
  std::string base = k == QuantityKind::Depth && !encoding.empty() && encoding != "hardware" ? encoding + "_depth" : name(k);
  std::string n = base;
  for (int i = 2; used.count(n); ++i) n = base + std::to_string(i);
  used.insert(n);
  return n;
}

// The kinds the texels suggest for a target whose name says nothing, with why.
std::vector<QuantityKind> kindsFromTexels(const StorageFormat& f, const CpuImage* img, const SurfaceMask& s,
                                          bool afterGBuffer, std::string& why) {
  const uint32_t n = f.channels;
  if (f.encoding == Encoding::Uint) {
    why = "integer channels: ids";
    return {QuantityKind::Id};
  }
  if (n == 1) {
    why = f.type == PixelType::F32 || f.type == PixelType::F16 ? "one float channel: a scalar (a linear depth?)"
                                                               : "one normalised channel: occlusion (or another 0..1 scalar)";
    return {f.type == PixelType::F32 || f.type == PixelType::F16 ? QuantityKind::Scalar : QuantityKind::Occlusion};
  }
  if (n == 2) {
    why = "two channels: a 2-vector (motion, or an octahedral normal?)";
    return {QuantityKind::Vector};
  }
  if (!img) {
    why = "no texels to look at";
    return {QuantityKind::Vector};
  }
  const Stats st = stats(*img, s, {0, 1, 2}, tolerance(f));
  std::ostringstream w;
  w.precision(3);
  const bool floats = f.encoding == Encoding::Float;
  if (st.unitXyz > 0.9 && (floats || f.encoding == Encoding::Snorm)) {
    w << "xyz of unit length at " << 100 * st.unitXyz << " % of surface texels: a normal";
    why = w.str();
    return {QuantityKind::Normal};
  }
  if (st.unitXyzUnorm > 0.9 && !floats) {
    w << "2 xyz - 1 of unit length at " << 100 * st.unitXyzUnorm << " % of surface texels: a normal stored n * 0.5 + 0.5";
    why = w.str();
    return {QuantityKind::Normal};
  }
  if (floats && (st.lo < 0.0 || f.type == PixelType::F32)) {
    w << "float xyz from " << st.lo << " to " << st.hi << ", not unit length: positions";
    why = w.str();
    return {QuantityKind::Position};
  }
  if (floats) {
    w << "float colour from " << st.lo << " to " << st.hi << ": light (radiance)";
    why = w.str();
    return {QuantityKind::Radiance};
  }
  if (afterGBuffer) {
    why = "normalised colour channels written after the G-buffer: the picture shown";
    return {QuantityKind::Display};
  }
  why = "normalised colour channels, not unit vectors, written with the G-buffer: a surface colour";
  return {QuantityKind::Albedo};
}

}  // namespace

std::string storageFormatName(const std::string& r) {
  static const std::map<std::string, std::string> depth = {
      {"D32S8", "d32s8"}, {"D24S8", "d24s8"}, {"D32", "d32f"}, {"D32_FLOAT", "d32f"}, {"D16", "d16"}, {"D16_UNORM", "d16"},
      {"R10G10B10A2_UNORM", "rgb10a2_unorm"}};
  if (auto it = depth.find(r); it != depth.end()) return it->second;
  static const std::regex re("(R(\\d+))(G\\2)?(B\\2)?(A\\2)?_(UNORM|SNORM|SRGB|UINT|FLOAT)");
  std::smatch m;
  if (!std::regex_match(r, m, re)) return "";
  const std::string channels = std::string("r") + (m[3].matched ? "g" : "") + (m[4].matched ? "b" : "") + (m[5].matched ? "a" : "");
  if (m[4].matched && !m[3].matched) return "";
  const std::string type = m[6];
  const std::string suffix = type == "FLOAT" ? "f" : "_" + lower(type);
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

nlohmann::json guessQuantities(const std::string& targetText, const StorageFormat& f, const CpuImage* img,
                               const SurfaceMask& s, std::set<std::string>& used, bool afterGBuffer) {
  nlohmann::json out = nlohmann::json::array();
  auto add = [&](QuantityKind k, std::vector<uint32_t> ch, nlohmann::json fields, const std::string& why) {
    const std::string encoding = fields.is_object() ? fields.value("encoding", "") : "";
    nlohmann::json q = {{"quantity", name(k)}, {"name", quantityName(k, encoding, used)}, {"channels", ch}};
    if (fields.is_object()) q.update(fields);
    q["guess"] = why;
    out.push_back(q);
  };
  if (f.depth) {
    add(QuantityKind::Depth, {0}, {{"encoding", "hardware"}}, "a depth format: the depth buffer");
    if (f.stencil) add(QuantityKind::Stencil, {1}, {}, "the stencil of a depth/stencil format");
    return out;
  }
  std::vector<QuantityKind> kinds = namedKinds(targetText);
  std::string why = kinds.empty() ? "" : "the name \"" + targetText + "\"";
  if (kinds.empty()) kinds = kindsFromTexels(f, img, s, afterGBuffer, why);
  uint32_t next = 0;
  for (size_t i = 0; i < kinds.size() && next < f.channels; ++i) {
    const QuantityKind k = kinds[i];
    // The channels left for the kinds after this one take one each.
    const uint32_t rest = uint32_t(kinds.size() - i - 1);
    uint32_t want = std::min(channelsOf(k, f.channels - next), f.channels - next - std::min(rest, f.channels - next - 1));
    if (k == QuantityKind::Vector) want = std::min(f.channels - next, 4u);
    if (k == QuantityKind::Normal) want = want >= 3 ? 3 : 2;
    if (want == 0 || ((k == QuantityKind::Albedo || k == QuantityKind::BaseColor || k == QuantityKind::Emission ||
                       k == QuantityKind::Position) && want < 3))
      continue;
    // A one-channel quantity after others skips constant channels (padding, an unused z).
    if (want == 1 && img && i > 0)
      while (next + 1 < f.channels && stats(*img, s, {next}, 0.0).constant) ++next;
    std::string note = why, normalEncoding;
    const bool unorm = f.encoding == Encoding::Unorm || f.encoding == Encoding::Unorm10 || f.encoding == Encoding::Srgb;
    if (k == QuantityKind::Normal && img && want == 3) {  // the texels say which: xyz, n * 0.5 + 0.5, or 2 channels
      const Stats st = stats(*img, s, {next, next + 1, next + 2}, tolerance(f));
      std::ostringstream w;
      w.precision(3);
      w << note << "; xyz of unit length at " << 100 * st.unitXyz << " %, 2 xyz - 1 at " << 100 * st.unitXyzUnorm
        << " % of surface texels";
      if (std::max(st.unitXyz, st.unitXyzUnorm) < 0.5) {
        want = 2;
        w << ": neither, so octahedral in 2 channels";
      }
      note = w.str();
      const char* e = want == 2 ? (unorm ? "octahedral_unorm" : "octahedral")
                      : st.unitXyzUnorm > st.unitXyz ? "xyz_unorm" : "xyz";
      normalEncoding = e;
    }
    std::vector<uint32_t> ch;
    for (uint32_t c = 0; c < want; ++c) ch.push_back(next + c);
    next += want;
    nlohmann::json fields = nlohmann::json::object();
    if (k == QuantityKind::Normal) {
      fields["encoding"] = !normalEncoding.empty() ? normalEncoding
                           : want == 3 ? (unorm ? "xyz_unorm" : "xyz")
                                       : (unorm ? "octahedral_unorm" : "octahedral");
      fields["space"] = "view";
      note += "; space: view unless the camera search says otherwise";
    } else if (k == QuantityKind::Albedo || k == QuantityKind::BaseColor || k == QuantityKind::Emission ||
               k == QuantityKind::Radiance || k == QuantityKind::Display) {
      if (f.srgb) fields["encoding"] = "srgb";
      note += f.srgb ? "; sRGB: the format is" : "; linear: the format is not sRGB";
    } else if (k == QuantityKind::Position) {
      fields["space"] = "view";
    } else if (k == QuantityKind::Depth) {
      fields["encoding"] = "eye";
      note += "; eye depth (a float channel): check it is not hardware or radial";
    } else if (k == QuantityKind::Motion) {
      fields["units"] = "pixels";
      note += "; units and direction unknown: pixels, to the previous frame";
    }
    add(k, ch, fields, note);
  }
  // Channels no quantity took: a varying one is a scalar to look at; a constant one is padding.
  for (uint32_t c = next; c < f.channels; ++c) {
    if (img) {
      const Stats st = stats(*img, s, {c}, 0.0);
      if (st.constant) continue;
    }
    add(QuantityKind::Scalar, {c}, nlohmann::json::object(),
        "channel " + std::to_string(c) + " varies and nothing above names it");
  }
  return out;
}

}  // namespace gb
