// Reading layout files: parameter resolution, then validation of every field with a message that
// names the file, the target or quantity and the field (docs/layout-format.md).
#include "renderer/core/layout_json.h"

#include "renderer/core/camera.h"

#include <cmath>
#include <fstream>
#include <set>
#include <sstream>
#include <tuple>

#include "renderer/core/file_name.h"
#include "renderer/core/json_read.h"

namespace gb {

using json = nlohmann::json;

namespace {

// Scales, depths and light values beyond this are not a renderer's: refused, so that nothing an
// import computes from them overflows to Inf (and is written as JSON null).
constexpr double kMaxLayoutNumber = 1e30;

// Where in the file a value is, for messages: "my.json: targets[1] \"gbuf\": quantities[0] \"N\"".
struct Where {
  std::string text;
  Where at(const std::string& part) const { return {text + ": " + part}; }
  std::string field(const std::string& f) const { return text + ": " + f; }
};

struct Reader {
  std::string& error;
  bool fail(const Where& w, const std::string& field, const std::string& message) {
    if (error.empty()) error = w.field(field) + ": " + message;
    return false;
  }
  bool string(const json& j, const Where& w, const char* key, std::string& out, bool required) {
    auto it = j.find(key);
    if (it == j.end()) return !required || fail(w, key, "missing");
    if (!it->is_string()) return fail(w, key, "expected a string, got " + jsonBrief(*it));
    out = it->get<std::string>();
    return true;
  }
  bool number(const json& j, const Where& w, const char* key, double& out) {
    auto it = j.find(key);
    if (it == j.end()) return true;
    if (!jsonNumber(*it, out) || std::abs(out) > kMaxLayoutNumber)
      return fail(w, key, "expected a number (magnitude at most 1e30), got " + jsonBrief(*it));
    return true;
  }
  bool boolean(const json& j, const Where& w, const char* key, bool& out) {
    auto it = j.find(key);
    if (it == j.end()) return true;
    if (!it->is_boolean()) return fail(w, key, "expected true or false, got " + jsonBrief(*it));
    out = it->get<bool>();
    return true;
  }
  bool size(const json& j, const Where& w, const char* key, uint32_t& width, uint32_t& height) {
    auto it = j.find(key);
    if (it == j.end()) return true;
    int64_t wh[2] = {0, 0};
    if (!it->is_array() || it->size() != 2 || !jsonInteger((*it)[0], 1, 65536, wh[0]) ||
        !jsonInteger((*it)[1], 1, 65536, wh[1]))
      return fail(w, key, "expected [width, height] (1..65536), got " + jsonBrief(*it));
    width = uint32_t(wh[0]);
    height = uint32_t(wh[1]);
    return true;
  }
  bool vec3(const json& j, const Where& w, const char* key, glm::dvec3& out) {
    auto it = j.find(key);
    if (it == j.end()) return true;
    if (!it->is_array() || it->size() != 3) return fail(w, key, "expected 3 numbers, got " + jsonBrief(*it));
    for (int i = 0; i < 3; ++i)
      if (!jsonNumber((*it)[i], out[i]) || std::abs(out[i]) > kMaxLayoutNumber)
        return fail(w, key, "expected 3 numbers (magnitude at most 1e30), got " + jsonBrief(*it));
    return true;
  }
  // One of `choices`; `index` receives its position.
  bool choice(const json& j, const Where& w, const char* key, std::initializer_list<const char*> choices, int& index) {
    std::string v;
    if (!string(j, w, key, v, false)) return false;
    if (v.empty()) return true;
    int i = 0;
    std::string list;
    for (const char* c : choices) {
      if (v == c) {
        index = i;
        return true;
      }
      list += std::string(i++ ? ", " : "") + c;
    }
    return fail(w, key, "\"" + v + "\" is not one of " + list);
  }
  bool unknownKeys(const json& j, const Where& w, std::initializer_list<const char*> known) {
    for (auto& item : j.items()) {
      const std::string& k = item.key();  // (a named variable: clang-14 cannot capture a structured binding)
      if (std::none_of(known.begin(), known.end(), [&](const char* n) { return k == n; }))
        return fail(w, k, "unknown field");
    }
    return true;
  }
};

bool validName(const std::string& s) {
  if (s.empty() || s.size() > kMaxNameBytes) return false;
  for (char c : s)
    if (!(std::islower(static_cast<unsigned char>(c)) || std::isdigit(static_cast<unsigned char>(c)) || c == '_'))
      return false;
  return true;
}

// Channels a quantity of this kind and encoding takes (0: 2 to 4).
uint32_t channelsFor(const Quantity& q) {
  switch (q.kind) {
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Position: return 3;
    case QuantityKind::Radiance:
    case QuantityKind::Display:
    case QuantityKind::Vector: return 0;
    case QuantityKind::Normal:
      return q.normal == NormalEncoding::Xyz || q.normal == NormalEncoding::XyzUnorm ? 3
             : q.normal == NormalEncoding::Octahedral12                            ? 3
                                                                                    : 2;
    case QuantityKind::Motion: return 2;
    default: return 1;
  }
}

bool readQuantityFields(Reader& r, const json& j, const Where& w, Quantity& q) {
  int i = -1;
  switch (q.kind) {
    case QuantityKind::Normal: {
      if (!r.choice(j, w, "encoding", {"xyz", "xyz_unorm", "octahedral", "octahedral_unorm", "spheremap", "lambert"}, i))
        return false;
      static const NormalEncoding e[] = {NormalEncoding::Xyz,        NormalEncoding::XyzUnorm,
                                         NormalEncoding::Octahedral, NormalEncoding::OctahedralUnorm,
                                         NormalEncoding::Spheremap,  NormalEncoding::Lambert};
      if (i >= 0) q.normal = e[i];
      double bits = 0.0;
      if (!r.number(j, w, "bits", bits)) return false;
      if (bits != 0.0 && bits != 8.0 && bits != 12.0 && bits != 16.0)
        return r.fail(w, "bits", "expected 8, 12 or 16");
      if (bits == 12.0) {
        if (q.normal != NormalEncoding::Octahedral && q.normal != NormalEncoding::OctahedralUnorm)
          return r.fail(w, "bits", "12 applies to octahedral encodings only");
        q.normal = NormalEncoding::Octahedral12;
      }
      int s = -1;
      if (!r.choice(j, w, "space", {"view", "world"}, s) || !r.boolean(j, w, "normalized", q.normalized)) return false;
      if (s >= 0) q.space = Space(s);
      return r.unknownKeys(j, w, {"quantity", "name", "channels", "encoding", "bits", "space", "normalized", "when"});
    }
    case QuantityKind::Depth: {
      if (!r.choice(j, w, "encoding", {"hardware", "eye", "radial"}, i)) return false;
      if (i < 0) return r.fail(w, "encoding", "missing (hardware, eye or radial)");
      q.depth = DepthEncoding(i);
      double bg = NAN;
      int of = -1;
      if (!r.number(j, w, "background", bg) || !r.choice(j, w, "of", {"camera", "sun"}, of) ||
          !r.number(j, w, "scale", q.scale) || !r.number(j, w, "bias", q.bias))
        return false;
      if (!std::isnan(bg)) q.background = bg;
      q.ofSun = of == 1;
      // Eye and radial distances may be stored as fractions (eye depth / far): distance = stored * scale + bias.
      if ((j.contains("scale") || j.contains("bias")) && (q.depth == DepthEncoding::Hardware || q.ofSun))
        return r.fail(w, j.contains("scale") ? "scale" : "bias",
                      "applies to eye and radial camera depths (hardware depth is decoded by the projection)");
      if (!(q.scale > 0.0)) return r.fail(w, "scale", "expected a positive number");
      return r.unknownKeys(j, w, {"quantity", "name", "channels", "encoding", "background", "of", "scale", "bias", "when"});
    }
    case QuantityKind::Position: {
      int s = -1;
      if (!r.choice(j, w, "space", {"view", "world", "camera_relative"}, s)) return false;
      q.space = s < 0 ? Space::World : Space(s);
      return r.unknownKeys(j, w, {"quantity", "name", "channels", "space", "when"});
    }
    case QuantityKind::Motion: {
      int u = -1, d = -1, yAxis = -1, jitter = -1;
      if (!r.choice(j, w, "units", {"pixels", "ndc", "uv"}, u) || !r.choice(j, w, "direction", {"to_previous", "to_next"}, d) ||
          !r.choice(j, w, "y", {"down", "up"}, yAxis) || !r.choice(j, w, "jitter", {"excluded", "included"}, jitter))
        return false;
      if (u >= 0) q.units = MotionUnits(u);
      q.toPrevious = d != 1;
      q.motionYUp = yAxis == 1;
      q.jitterIncluded = jitter == 1;
      return r.unknownKeys(j, w, {"quantity", "name", "channels", "units", "direction", "y", "jitter", "when"});
    }
    case QuantityKind::Id:
      if (auto it = j.find("names"); it != j.end()) {
        if (!it->is_object()) return r.fail(w, "names", "expected {\"value\": \"name\", ...}");
        for (auto& [k, v] : it->items()) {
          char* end = nullptr;
          unsigned long long id = std::strtoull(k.c_str(), &end, 10);
          if (k.empty() || *end || !v.is_string() || !std::isdigit(static_cast<unsigned char>(k[0])) || id > 0xFFFFFFFFull)
            return r.fail(w, "names", "expected {\"value\": \"name\", ...} with values 0..4294967295");
          q.idNames[uint32_t(id)] = v.get<std::string>();
        }
      }
      return r.unknownKeys(j, w, {"quantity", "name", "channels", "names", "when"});
    case QuantityKind::Stencil:
      if (auto it = j.find("bits"); it != j.end()) {
        if (!it->is_object()) return r.fail(w, "bits", "expected {\"name\": mask, ...}");
        for (auto& [k, v] : it->items()) {
          int64_t mask = 0;
          if (!jsonInteger(v, 1, 255, mask)) return r.fail(w, "bits", "\"" + k + "\": expected a mask 1..255");
          q.stencilBits[k] = uint32_t(mask);
        }
      }
      return r.unknownKeys(j, w, {"quantity", "name", "channels", "bits", "when"});
    case QuantityKind::Albedo:
    case QuantityKind::BaseColor:
    case QuantityKind::Emission:
    case QuantityKind::Radiance:
    case QuantityKind::Display:
      if (!r.choice(j, w, "encoding", {"linear", "srgb"}, i)) return false;
      if (i >= 0) q.color = ColorEncoding(i);
      return r.unknownKeys(j, w, {"quantity", "name", "channels", "encoding", "when"});
    default:
      if (!r.number(j, w, "scale", q.scale) || !r.number(j, w, "bias", q.bias) ||
          !r.string(j, w, "unit", q.unit, false))
        return false;
      return r.unknownKeys(j, w, {"quantity", "name", "channels", "scale", "bias", "unit", "when"});
  }
}

// A draft layout's "guess" notes (import --suggest-layout): kept for people, never interpreted.
bool takeGuess(Reader& r, json& j, const Where& w, json& guess) {
  auto it = j.find("guess");
  if (it == j.end()) return true;
  if (!it->is_string() && !it->is_object()) return r.fail(w, "guess", "expected a text or an object");
  guess = *it;
  j.erase(it);
  return true;
}

// A `gblens check` policy: {"denormal": "warn", ...} (views/analysis/check.h names the classes).
bool readCheck(Reader& r, const json& j, const Where& w, std::map<std::string, std::string>& out) {
  auto it = j.find("check");
  if (it == j.end()) return true;
  static const std::set<std::string> classes = {"nan", "inf", "denormal", "out_of_range", "position", "normal", "motion", "history"};
  static const std::set<std::string> levels = {"fault", "warn", "ignore"};
  if (!it->is_object()) return r.fail(w, "check", "expected {\"CLASS\": \"fault|warn|ignore\", ...}");
  for (auto& [k, v] : it->items()) {
    if (!classes.count(k)) return r.fail(w, "check", "\"" + k + "\": expected nan, inf, denormal, out_of_range, position, normal, motion or history");
    if (!v.is_string() || !levels.count(v.get<std::string>()))
      return r.fail(w, "check", "\"" + k + "\": expected \"fault\", \"warn\" or \"ignore\", got " + v.dump());
    out[k] = v.get<std::string>();
  }
  return true;
}

// "history_of": NAME, "history_space": "previous" | "current" (any kind): read and erased, so that
// every kind takes them; NAME is checked against the whole layout once every target is read.
bool readHistory(Reader& r, json& j, const Where& w, Quantity& q) {
  int space = -1;
  if (!r.string(j, w, "history_of", q.historyOf, false) || !r.choice(j, w, "history_space", {"previous", "current"}, space))
    return false;
  if (j.contains("history_of") && q.historyOf.empty()) return r.fail(w, "history_of", "expected the name of a quantity of the layout");
  if (space >= 0 && q.historyOf.empty()) return r.fail(w, "history_space", "applies to a history (give \"history_of\")");
  q.historyCurrent = space == 1;
  j.erase("history_of");
  j.erase("history_space");
  return true;
}

// Every history_of names another quantity of the layout with as many components.
bool checkHistories(Reader& r, const json& targets, const Where& w, const Layout& l) {
  size_t at = 0;
  for (size_t t = 0; t < targets.size(); ++t) {
    const json& qs = targets[t]["quantities"];
    for (size_t i = 0; i < qs.size() && at < l.quantities.size(); ++i, ++at) {
      const Quantity& q = l.quantities[at];
      if (q.historyOf.empty()) continue;
      const Where wq = w.at("targets[" + std::to_string(t) + "]").at("\"" + l.targets[t].name + "\"")
                           .at("quantities[" + std::to_string(i) + "] \"" + q.name + "\"");
      const Quantity* x = l.findByName(q.historyOf);
      if (!x) {
        std::string names;
        for (const Quantity& o : l.quantities)
          if (&o != &q) names += (names.empty() ? "" : ", ") + o.name;
        return r.fail(wq, "history_of", "\"" + q.historyOf + "\" is not a quantity of the layout (" + names + ")");
      }
      if (x == &q) return r.fail(wq, "history_of", "a quantity cannot be its own history");
      if (x->channels.size() != q.channels.size())
        return r.fail(wq, "history_of", "\"" + x->name + "\" has " + std::to_string(x->channels.size()) + " components, \"" +
                                            q.name + "\" " + std::to_string(q.channels.size()));
    }
  }
  return true;
}

bool readQuantity(Reader& r, const json& jIn, const Where& w, Layout& l, uint32_t target, Quantity& q) {
  if (!jIn.is_object()) return r.fail(w, "quantity", "expected an object");
  if (!readCheck(r, jIn, w, q.check)) return false;
  json j = jIn;
  j.erase("check");  // read above; every kind may have it
  if (!takeGuess(r, j, w, q.guess) || !readHistory(r, j, w, q)) return false;
  std::string kind;
  if (!r.string(j, w, "quantity", kind, true)) return false;
  if (!parseQuantityKind(kind, q.kind)) return r.fail(w, "quantity", "unknown kind \"" + kind + "\"");
  if (!r.string(j, w, "name", q.name, false)) return false;
  if (q.name.empty()) q.name = kind;
  if (std::string why; !safeFileName(q.name, why)) return r.fail(w, "name", jsonBrief(q.name) + ": " + why);
  q.target = target;
  if (!readQuantityFields(r, j, w, q)) return false;
  const LayoutTarget& t = l.targets[target];
  auto it = j.find("channels");
  if (it == j.end() || !it->is_array() || it->empty()) return r.fail(w, "channels", "expected a list of channels");
  for (const json& c : *it) {
    int64_t index = 0;
    if (jsonInteger(c, 0, INT64_MAX, index)) {
      if (index >= int64_t(t.format.channels))
        return r.fail(w, "channels", "channel " + std::to_string(index) + " is beyond the " +
                                         std::to_string(t.format.channels) + " channels of format " + t.format.name);
      q.channels.push_back(uint32_t(index));
    } else if (c.is_string() && !t.channels.empty()) {
      auto pos = std::find(t.channels.begin(), t.channels.end(), c.get<std::string>());
      if (pos == t.channels.end()) return r.fail(w, "channels", "the target has no channel " + c.dump());
      q.channels.push_back(uint32_t(pos - t.channels.begin()));
    } else {
      return r.fail(w, "channels", "expected channel indices (or names given in the target's \"channels\"), got " + jsonBrief(c));
    }
    if (q.channels.back() >= t.format.channels)
      return r.fail(w, "channels", "channel " + std::to_string(q.channels.back()) + " is beyond the " +
                                       std::to_string(t.format.channels) + " channels of format " + t.format.name);
  }
  const uint32_t want = channelsFor(q), have = uint32_t(q.channels.size());
  if (want ? have != want : (have < 2 || have > 4)) {
    std::string what = q.kind == QuantityKind::Normal ? std::string("encoding \"") + name(q.normal) + "\"" : "quantity " + kind;
    return r.fail(w, "channels", what + " needs " + (want ? std::to_string(want) : std::string("2 to 4")) +
                                     " channels, has " + std::to_string(have));
  }
  const bool integral = q.kind == QuantityKind::Id || q.kind == QuantityKind::Stencil || q.kind == QuantityKind::Count;
  if (q.kind == QuantityKind::Normal && q.normal == NormalEncoding::Octahedral12 &&
      !(t.format.type == PixelType::U8 && t.format.encoding == Encoding::Unorm))
    return r.fail(w, "bits", "12+12-bit octahedral normals are packed in 8-bit unorm channels; the format is " + t.format.name);
  if (q.kind == QuantityKind::Depth && q.depth == DepthEncoding::Hardware && t.format.encoding == Encoding::Uint)
    return r.fail(w, "encoding", "hardware depth cannot be held by the integer format " + t.format.name);
  if (integral && t.format.encoding == Encoding::Snorm)
    return r.fail(w, "quantity", std::string(name(q.kind)) + " is an integer; the format " + t.format.name + " holds fractions");
  for (const Quantity& other : l.quantities)
    if (nameKey(other.name) == nameKey(q.name))
      return r.fail(w, "name", "\"" + q.name + "\" names another quantity too (\"" + other.name + "\": case, _ and - do not tell names apart)");
  return true;
}

// {"live": "NAME"} or {"live": {"pass": LABEL | N, "name" | "color" | "depth" | "format" | "attachment": ...,
// "subpass": S (with color or depth)}} or {"live": {"pass": LABEL, "storage": {"set": S, "binding": B}}}.
bool readStoragePick(Reader& r, const json& j, const Where& wl, TargetSource::LivePick& p) {
  auto it = j.find("storage");
  if (it == j.end()) return true;
  const Where ws = wl.at("storage");
  if (!it->is_object()) return r.fail(wl, "storage", "expected {\"set\": S, \"binding\": B} (a compute dispatch's storage image)");
  int64_t set = -1, binding = -1;
  if (!it->contains("set") || !jsonInteger((*it)["set"], 0, 31, set)) return r.fail(ws, "set", "expected a set number 0..31");
  if (!it->contains("binding") || !jsonInteger((*it)["binding"], 0, 1 << 16, binding))
    return r.fail(ws, "binding", "expected a binding number 0..65536");
  if (p.passIndex >= 0)
    return r.fail(wl, "pass", "with \"storage\": a debug label open at the dispatch (a dispatch has no render pass ordinal)");
  p.storageSet = int(set);
  p.storageBinding = int(binding);
  return r.unknownKeys(*it, ws, {"set", "binding"});
}

bool readLiveSource(Reader& r, const json& j, const Where& w, TargetSource& s) {
  s.kind = TargetSource::Kind::Live;
  TargetSource::LivePick& p = s.live;
  if (j.is_string()) {
    p.name = j.get<std::string>();
    return !p.name.empty() || r.fail(w, "live", "expected an attachment's debug name");
  }
  Where wl = w.at("live");
  if (!j.is_object()) return r.fail(w, "live", "expected a debug name or {\"pass\": ..., \"name\" | \"color\" | \"depth\" | \"format\": ...}");
  if (auto it = j.find("pass"); it != j.end()) {
    if (it->is_number_integer() && it->get<int64_t>() >= 0 && it->get<int64_t>() < 1 << 20)
      p.passIndex = int(it->get<int64_t>());
    else if (it->is_string() && !it->get<std::string>().empty())
      p.pass = it->get<std::string>();
    else
      return r.fail(wl, "pass", "expected a label (text) or the render pass's ordinal in its command buffer (0, 1, ...)");
  }
  double color = -1.0, subpass = -1.0, attachment = -1.0;
  if (!r.string(j, wl, "name", p.name, false) || !r.number(j, wl, "color", color) || !r.boolean(j, wl, "depth", p.depth) ||
      !r.string(j, wl, "format", p.format, false) || !r.number(j, wl, "subpass", subpass) ||
      !r.number(j, wl, "attachment", attachment))
    return false;
  if (j.contains("color") && (color < 0.0 || color > 7.0 || color != std::floor(color)))
    return r.fail(wl, "color", "expected a colour attachment index 0..7");
  if (j.contains("subpass") && (subpass < 0.0 || subpass > 63.0 || subpass != std::floor(subpass)))
    return r.fail(wl, "subpass", "expected a subpass index 0..63");
  if (j.contains("attachment") && (attachment < 0.0 || attachment > 63.0 || attachment != std::floor(attachment)))
    return r.fail(wl, "attachment", "expected the render pass's attachment index 0..63");
  p.color = int(color);
  p.subpass = int(subpass);
  p.attachment = int(attachment);
  if (p.subpass >= 0 && p.color < 0 && !p.depth)
    return r.fail(wl, "subpass", "goes with \"color\": N or \"depth\": true (that subpass's attachment)");
  StorageFormat f;
  if (!p.format.empty() && !parseStorageFormat(p.format, f))
    return r.fail(wl, "format", "unknown storage format \"" + p.format + "\"");
  if (!readStoragePick(r, j, wl, p)) return false;
  const int picks = int(!p.name.empty()) + int(p.color >= 0) + int(p.depth) + int(!p.format.empty()) + int(p.attachment >= 0) +
                    int(p.storageSet >= 0);
  if (picks != 1)
    return r.fail(wl, "name", "give exactly one of \"name\", \"color\", \"depth\": true, \"format\", \"attachment\" and \"storage\"");
  return r.unknownKeys(j, wl, {"pass", "name", "color", "depth", "format", "subpass", "attachment", "storage"});
}

bool readSource(Reader& r, const json& j, const Where& w, TargetSource& s) {
  if (!j.is_object()) return r.fail(w, "source", "expected an object");
  Where ws = w.at("source");
  if (auto it = j.find("live"); it != j.end()) {
    if (j.size() != 1) return r.fail(ws, "live", "a live source has no other fields");
    return readLiveSource(r, *it, ws, s);
  }
  bool raw = false;
  int64_t offset = 0, part = 0;
  if (!r.string(j, ws, "file", s.path, false) || !r.boolean(j, ws, "raw", raw) ||
      !r.string(j, ws, "renderdoc", s.resource, false))
    return false;
  // A byte offset into a file: at most 2^48 (256 TiB), never wrapped.
  if (auto it = j.find("offset"); it != j.end() && !jsonInteger(*it, 0, int64_t(1) << 48, offset))
    return r.fail(ws, "offset", "expected a byte count 0..2^48, got " + jsonBrief(*it));
  // Bytes from one row's start to the next in a raw dump (rows padded to an alignment): at most 2^32.
  int64_t stride = 0;
  if (auto it = j.find("row_stride"); it != j.end() && (!jsonInteger(*it, 1, int64_t(1) << 32, stride) || !raw))
    return r.fail(ws, "row_stride", raw ? "expected a byte count 1..2^32, got " + jsonBrief(*it) : "applies to a raw dump");
  s.rowStride = uint64_t(stride);
  if (auto it = j.find("part"); it != j.end()) {
    if (it->is_string())
      s.part = it->get<std::string>();
    else if (jsonInteger(*it, 0, 65535, part))
      s.part = std::to_string(part);
    else
      return r.fail(ws, "part", "expected a part name or index 0..65535, got " + jsonBrief(*it));
  }
  if (auto it = j.find("channels"); it != j.end()) {
    if (!it->is_array()) return r.fail(ws, "channels", "expected the file's channel names");
    for (const json& c : *it) {
      if (!c.is_string()) return r.fail(ws, "channels", "expected the file's channel names");
      s.channels.push_back(c.get<std::string>());
    }
  }
  // Neither: the file given on the command line (a shipped layout does not know the user's file name).
  if (!s.path.empty() && !s.resource.empty()) return r.fail(ws, "file", "give one of \"file\" and \"renderdoc\", not both");
  s.kind = !s.resource.empty() ? TargetSource::Kind::RenderDoc : raw ? TargetSource::Kind::Raw : TargetSource::Kind::File;
  s.offset = uint64_t(offset);
  return r.unknownKeys(j, ws, {"file", "raw", "offset", "row_stride", "part", "channels", "renderdoc"});
}

bool readTarget(Reader& r, const json& given, const Where& w, Layout& l) {
  if (!given.is_object()) return r.fail(w, "", "expected an object");
  json j = given;
  LayoutTarget t;
  if (!r.string(j, w, "name", t.name, true)) return false;
  if (!validName(t.name)) return r.fail(w, "name", jsonBrief(t.name) + ": use a-z, 0-9 and _ (at most 100)");
  if (l.findTarget(t.name) >= 0) return r.fail(w, "name", "\"" + t.name + "\" names another target too");
  Where wt = w.at("\"" + t.name + "\"");
  if (!takeGuess(r, j, wt, t.guess)) return false;
  // "format": one storage format, or a list the source's files may hold it in (the file's channel type picks).
  std::vector<std::string> formats;
  if (auto it = j.find("format"); it != j.end() && it->is_array() && !it->empty()) {
    for (const json& f : *it)
      if (f.is_string()) formats.push_back(f.get<std::string>());
    if (formats.size() != it->size()) return r.fail(wt, "format", "expected storage format names, got " + it->dump());
  } else {
    formats.emplace_back();
    if (!r.string(j, wt, "format", formats[0], true)) return false;
  }
  const std::string& format = formats[0];
  for (const std::string& f : formats) {
    StorageFormat parsed;
    if (!parseStorageFormat(f, parsed))
      return r.fail(wt, "format", "unknown storage format \"" + f + "\" (e.g. rgba8_unorm, rg16_snorm, r32f, d32s8)");
    if (formats.size() > 1 && (parsed.depth || parsed.packed10))
      return r.fail(wt, "format", "a list of formats is for image files: " + f + " is a packed GPU format");
    if (!t.formatChoices.empty() && parsed.channels != t.formatChoices[0].channels)
      return r.fail(wt, "format", "the formats of a list must have one channel count: " + f + " has " +
                                      std::to_string(parsed.channels) + ", " + formats[0] + " " +
                                      std::to_string(t.formatChoices[0].channels));
    t.formatChoices.push_back(parsed);
  }
  t.format = t.formatChoices[0];
  if (formats.size() == 1) t.formatChoices.clear();
  if (!r.size(j, wt, "size", t.width, t.height)) return false;
  if (auto it = j.find("channels"); it != j.end()) {
    if (!it->is_array() || it->size() != t.format.channels)
      return r.fail(wt, "channels", "expected " + std::to_string(t.format.channels) + " channel names for format " + format);
    for (const json& c : *it) {
      std::string why;
      if (!c.is_string()) return r.fail(wt, "channels", "expected names");
      if (!safeFileName(c.get<std::string>(), why)) return r.fail(wt, "channels", jsonBrief(c) + ": " + why);
      if (std::find(t.channels.begin(), t.channels.end(), c.get<std::string>()) != t.channels.end())
        return r.fail(wt, "channels", jsonBrief(c) + " named twice");  // one EXR channel would hold both
      t.channels.push_back(c.get<std::string>());
    }
  }
  if (auto it = j.find("source"); it != j.end() && !readSource(r, *it, wt, t.source)) return false;
  if (!r.unknownKeys(j, wt, {"name", "format", "size", "channels", "source", "quantities", "when"})) return false;
  l.targets.push_back(t);
  const uint32_t index = uint32_t(l.targets.size() - 1);
  auto qs = j.find("quantities");
  if (qs == j.end() || !qs->is_array()) return r.fail(wt, "quantities", "expected a list of quantities");
  for (size_t i = 0; i < qs->size(); ++i) {
    Quantity q;
    std::string label = (*qs)[i].is_object() && (*qs)[i].contains("name") ? " " + (*qs)[i]["name"].dump() : "";
    if (!readQuantity(r, (*qs)[i], wt.at("quantities[" + std::to_string(i) + "]" + label), l, index, q)) return false;
    l.quantities.push_back(q);
  }
  // Default channel names: <quantity>.<component> (pbrt's "Albedo.R"), "C<n>" for unused channels.
  LayoutTarget& lt = l.targets[index];
  if (lt.channels.empty()) {
    lt.channels.resize(lt.format.channels);
    for (uint32_t c = 0; c < lt.format.channels; ++c) lt.channels[c] = "C" + std::to_string(c);
    for (const Quantity* q : l.quantitiesOf(index)) {
      static const char* xyzw[] = {"X", "Y", "Z", "W"};
      static const char* rgba[] = {"R", "G", "B", "A"};
      const bool colour = q->kind == QuantityKind::Albedo || q->kind == QuantityKind::BaseColor ||
                          q->kind == QuantityKind::Emission || q->kind == QuantityKind::Radiance ||
                          q->kind == QuantityKind::Display;
      for (size_t k = 0; k < q->channels.size(); ++k)
        lt.channels[q->channels[k]] = q->channels.size() == 1 ? q->name : q->name + "." + (colour ? rgba : xyzw)[k];
      // A manifest writes these names back and they must read again (tests/fuzz found a 99-byte name).
      if (const std::string& c = lt.channels[q->channels[0]]; c.size() > kMaxNameBytes)
        return r.fail(wt, "quantities", jsonBrief(q->name) + ": its channels would be named " + jsonBrief(c) + ", over " +
                                            std::to_string(kMaxNameBytes) + " bytes: shorten it or name the target's \"channels\"");
    }
  }
  return true;
}

bool readMatrix(Reader& r, const json& j, const Where& w, const char* key, bool rowMajor, glm::dmat4& m) {
  auto it = j.find(key);
  if (it == j.end()) return r.fail(w, key, "missing");
  if (!it->is_array() || it->size() != 16) return r.fail(w, key, "expected 16 numbers");
  for (int i = 0; i < 16; ++i) {
    double v = 0.0;
    if (!jsonNumber((*it)[i], v)) return r.fail(w, key, "expected 16 numbers");
    if (rowMajor)
      m[i % 4][i / 4] = v;
    else
      m[i / 4][i % 4] = v;
  }
  const double det = glm::determinant(m);
  if (!std::isfinite(det) || std::abs(det) < 1e-300) return r.fail(w, key, "the matrix is singular");
  return true;
}

// camera.live (gblens attach): {"pass": P, "set": S, "binding": B, "index": I} or {"pass": P,
// "push_constants": true}, the matrices' offsets beside it as {"offset": BYTES} from the bound range's start.
bool readLiveCamera(Reader& r, const json& j, const json& live, const Where& wc, bool rowMajor, LayoutCamera& c) {
  if (c.renderdoc || !c.sidecar.empty())
    return r.fail(wc, "live", "give one of \"live\", \"renderdoc\" and \"sidecar\"");
  if (!live.is_object())
    return r.fail(wc, "live", "expected {\"pass\": ..., \"set\": S, \"binding\": B} or {\"pass\": ..., \"push_constants\": true}");
  Where wl = wc.at("live");
  LayoutCamera::LiveBinding b;
  auto pass = live.find("pass");
  if (pass != live.end() && pass->is_number_integer() && pass->get<int64_t>() >= 0 && pass->get<int64_t>() < 1 << 20)
    b.passIndex = int(pass->get<int64_t>());
  else if (pass != live.end() && pass->is_string() && !pass->get<std::string>().empty())
    b.pass = pass->get<std::string>();
  else
    return r.fail(wl, "pass", "expected a label (text) or the render pass's ordinal in its command buffer (0, 1, ...)");
  if (!r.boolean(live, wl, "push_constants", b.pushConstants)) return false;
  for (auto [key, out, required] : {std::tuple{"set", &b.set, true}, {"binding", &b.binding, true}, {"index", &b.index, false}}) {
    auto it = live.find(key);
    int64_t v = 0;
    if (b.pushConstants && it != live.end()) return r.fail(wl, key, "push constants have no set, binding or index");
    if (b.pushConstants) continue;
    if (it == live.end() && required) return r.fail(wl, key, "missing (or give \"push_constants\": true)");
    if (it != live.end() && !jsonInteger(*it, 0, 1 << 20, v)) return r.fail(wl, key, "expected an integer 0..1048576");
    *out = uint32_t(v);
  }
  if (!r.unknownKeys(live, wl, {"pass", "set", "binding", "index", "push_constants"})) return false;
  b.matrices.rowMajor = rowMajor;
  b.matrices.worldFromView = j.contains("world_from_view");
  b.matrices.combined = j.contains("clip_from_world");
  const char* viewKey = b.matrices.worldFromView ? "world_from_view" : "view_from_world";
  std::vector<std::pair<const char*, uint64_t*>> keys = {{viewKey, &b.matrices.viewOffset}, {"clip_from_view", &b.matrices.clipOffset}};
  if (b.matrices.combined) {
    for (const char* other : {"view_from_world", "world_from_view", "clip_from_view"})
      if (j.contains(other)) return r.fail(wc, other, "clip_from_world gives both matrices: give it alone");
    keys = {{"clip_from_world", &b.matrices.clipOffset}};
  }
  for (auto [key, out] : keys) {
    auto m = j.find(key);
    int64_t v = -1;
    if (m == j.end() || !m->is_object() || m->size() != 1 || !m->contains("offset") ||
        !jsonInteger((*m)["offset"], 0, 0xFFFFFFFFll, v) || v % 4)
      return r.fail(wc, key, "expected {\"offset\": BYTES} from the start of the bound range (a multiple of 4) with camera.live");
    *out = uint64_t(v);
  }
  c.live = b;
  return true;
}

bool readCamera(Reader& r, const json& j, const Where& w, LayoutCamera& c) {
  if (!j.is_object()) return r.fail(w, "camera", "expected an object");
  Where wc = w.at("camera");
  c.present = true;
  int order = -1, conv = -1, hand = -1, worldHand = -1, projection = -1, origin = -1;
  std::string up;
  if (!r.choice(j, wc, "matrix_order", {"column_major", "row_major"}, order) ||
      !r.choice(j, wc, "convention", {"vulkan", "d3d", "gl"}, conv) ||
      !r.choice(j, wc, "view_handedness", {"right", "left"}, hand) ||
      !r.choice(j, wc, "world_handedness", {"right", "left"}, worldHand) ||
      !r.choice(j, wc, "projection", {"perspective", "orthographic"}, projection) || !r.string(j, wc, "up", up, false) ||
      !r.choice(j, wc, "image_origin", {"top", "bottom"}, origin) || !r.string(j, wc, "sidecar", c.sidecar, false) ||
      !r.string(j, wc, "from", c.from, false) ||
      !r.size(j, wc, "size", c.width, c.height))
    return false;
  if (auto g = j.find("guess"); g != j.end()) {
    if (!g->is_string() && !g->is_object()) return r.fail(wc, "guess", "expected a text or an object");
    c.guess = *g;
  }
  if (auto it = j.find("jitter"); it != j.end()) {
    double jx = 0, jy = 0;
    if (!it->is_array() || it->size() != 2 || !jsonNumber((*it)[0], jx) || !jsonNumber((*it)[1], jy) ||
        std::fabs(jx) > 64 || std::fabs(jy) > 64)
      return r.fail(wc, "jitter", "expected [x, y] in pixels (+x right, +y down)");
    c.jitter = glm::dvec2(jx, jy);
  }
  if (auto it = j.find("time"); it != j.end()) {
    double t = 0;
    if (!jsonNumber(*it, t)) return r.fail(wc, "time", "expected a number of seconds");
    c.time = t;
  }
  if (!up.empty() && !parseAxis(up, c.up))
    return r.fail(wc, "up", "\"" + up + "\" is not one of x, -x, y, -y, z, -z");
  if (conv >= 0) c.convention = LayoutCamera::Convention(conv);
  c.leftHanded = hand == 1;
  if (worldHand >= 0) c.statedWorldLeftHanded = worldHand == 1;
  if (projection >= 0) c.statedOrthographic = projection == 1;
  c.bottomOrigin = origin == 1;
  if (auto it = j.find("renderdoc"); it != j.end()) {
    Where wr = wc.at("renderdoc");
    LayoutCamera::BufferMatrix b;
    int64_t view = -1, clip = -1;
    if (!it->is_object() || !r.string(*it, wr, "buffer", b.buffer, true)) return r.fail(wr, "buffer", "missing");
    b.worldFromView = it->contains("world_from_view");
    b.combined = it->contains("clip_from_world");
    b.rowMajor = order == 1;
    const char* viewKey = b.worldFromView ? "world_from_view" : "view_from_world";
    std::vector<std::pair<const char*, int64_t*>> keys = {{viewKey, &view}, {"clip_from_view", &clip}};
    if (b.combined) {
      for (const char* other : {"view_from_world", "world_from_view", "clip_from_view"})
        if (it->contains(other)) return r.fail(wr, other, "clip_from_world gives both matrices: give it alone");
      keys = {{"clip_from_world", &clip}};
      view = 0;
    }
    for (auto [key, out] : keys) {
      auto m = it->find(key);
      // A uniform buffer is at most a few kilobytes: an offset past 2^32 is never one.
      if (m == it->end() || !m->is_object() || !m->contains("offset") ||
          !jsonInteger((*m)["offset"], 0, 0xFFFFFFFFll, *out))
        return r.fail(wr, key, "expected {\"offset\": BYTES} (0..4294967295)");
    }
    b.viewOffset = uint64_t(view);
    b.clipOffset = uint64_t(clip);
    c.renderdoc = b;
  }
  if (auto it = j.find("live"); it != j.end() && !readLiveCamera(r, j, *it, wc, order == 1, c)) return false;
  const bool fromElsewhere = !c.sidecar.empty() || c.renderdoc || c.live;
  if (!fromElsewhere) {
    // The view matrix as view_from_world, or its inverse world_from_view (a camera's transform); or
    // only their product clip_from_world, split here.
    if (j.contains("clip_from_world")) {
      for (const char* other : {"view_from_world", "world_from_view", "clip_from_view"})
        if (j.contains(other)) return r.fail(wc, other, "clip_from_world gives both matrices: give it alone");
      glm::dmat4 clipFromWorld;
      if (!readMatrix(r, j, wc, "clip_from_world", order == 1, clipFromWorld)) return false;
      if (!splitClipFromWorld(clipFromWorld, c.convention != LayoutCamera::Convention::Vulkan, c.viewFromWorld,
                              c.clipFromView))
        return r.fail(wc, "clip_from_world", "not a perspective projection (clip w is no distance): give view_from_world "
                                             "and clip_from_view");
      c.leftHanded = false;  // the split gives a right-handed view
    } else if (j.contains("world_from_view")) {
      glm::dmat4 worldFromView;
      if (!readMatrix(r, j, wc, "world_from_view", order == 1, worldFromView)) return false;
      c.viewFromWorld = glm::inverse(worldFromView);
    } else if (!readMatrix(r, j, wc, "view_from_world", order == 1, c.viewFromWorld)) {
      return false;
    }
    if (!j.contains("clip_from_world") && !readMatrix(r, j, wc, "clip_from_view", order == 1, c.clipFromView)) return false;
    std::string error;
    if (!settleWorldHandedness(c, error)) return r.fail(w, "camera", error.substr(8));
    if (c.statedOrthographic && *c.statedOrthographic != (c.clipFromView[2][3] == 0.0))
      return r.fail(wc, "projection", std::string("\"") + (*c.statedOrthographic ? "orthographic" : "perspective") +
                                          "\", but clip_from_view is " +
                                          (c.clipFromView[2][3] == 0.0 ? "orthographic" : "not orthographic"));
  }
  return r.unknownKeys(j, wc, {"view_from_world", "world_from_view", "clip_from_view", "clip_from_world", "matrix_order", "convention",
                               "view_handedness", "world_handedness", "projection", "up", "image_origin", "sidecar",
                               "renderdoc", "live", "size", "from", "guess", "jitter", "time"});
}

bool readLights(Reader& r, const json& j, const Where& w, LayoutLights& l) {
  if (!j.is_object()) return r.fail(w, "lights", "expected an object");
  Where wl = w.at("lights");
  l.present = true;
  if (!r.string(j, wl, "model", l.model, true)) return false;
  l.gblensModel = l.model == "gblens";
  if (auto it = j.find("points"); it != j.end()) {
    if (!it->is_array()) return r.fail(wl, "points", "expected a list");
    for (size_t i = 0; i < it->size(); ++i) {
      Where wp = wl.at("points[" + std::to_string(i) + "]");
      PointLightDesc p;
      glm::dvec3 color(1.0);
      double radius = NAN;
      if (!r.vec3((*it)[i], wp, "position", p.center) || !r.number((*it)[i], wp, "radius", radius) ||
          !r.vec3((*it)[i], wp, "color", color) || !r.number((*it)[i], wp, "intensity", p.intensity))
        return false;
      if (!(radius > 0.0)) return r.fail(wp, "radius", "expected a positive radius");
      p.radius = radius;
      p.color = glm::vec3(color);
      l.points.push_back(p);
    }
  }
  if (auto it = j.find("sun"); it != j.end()) {
    glm::dvec3 dir(0.0), color(l.sun.color);
    if (!r.vec3(*it, wl.at("sun"), "direction", dir) || !r.vec3(*it, wl.at("sun"), "color", color)) return false;
    if (!(glm::length(dir) > 0.0) || !std::isfinite(glm::length(dir)))
      return r.fail(wl.at("sun"), "direction", "expected a non-zero vector");
    l.sun.toSun = glm::normalize(dir);
    l.sun.color = glm::vec3(color);
  } else {
    l.sun.enabled = false;
  }
  glm::dvec3 ambient(0.0);
  if (!r.vec3(j, wl, "ambient", ambient)) return false;
  l.ambient = glm::vec3(ambient);
  return r.unknownKeys(j, wl, {"model", "points", "sun", "ambient"});
}

}  // namespace

bool resolveLayoutParameters(json& j, const LayoutParameters& params, const std::string& where, std::string& error) {
  if (j.is_object() && j.contains("by") && j.contains("cases") && j.size() == 2) {
    const std::string option = j["by"].is_string() ? j["by"].get<std::string>() : "";
    auto p = params.find(option);
    if (p == params.end()) {
      error = where + ": \"by\": \"" + option + "\" is not an option of this layout's parameters";
      return false;
    }
    if (!j["cases"].is_object() || !j["cases"].contains(p->second)) {
      error = where + ": no case for " + option + " = " + p->second;
      return false;
    }
    json chosen = j["cases"][p->second];
    j = chosen;
    return resolveLayoutParameters(j, params, where, error);
  }
  if (j.is_object()) {
    for (auto& [k, v] : j.items())
      if (k != "when" && !resolveLayoutParameters(v, params, where + ": " + k, error)) return false;
  } else if (j.is_array()) {
    json kept = json::array();
    for (size_t i = 0; i < j.size(); ++i) {
      json& e = j[i];
      bool holds = true;
      if (e.is_object() && e.contains("when")) {
        for (auto& [option, values] : e["when"].items()) {
          auto p = params.find(option);
          if (p == params.end()) {
            error = where + "[" + std::to_string(i) + "]: \"when\": \"" + option + "\" is not an option";
            return false;
          }
          holds = holds && std::find(values.begin(), values.end(), json(p->second)) != values.end();
        }
        e.erase("when");
      }
      if (!holds) continue;
      if (!resolveLayoutParameters(e, params, where + "[" + std::to_string(i) + "]", error)) return false;
      kept.push_back(e);
    }
    j = kept;
  }
  return true;
}

bool parseLayout(const json& j, const std::string& file, Layout& out, std::string& error) {
  out = Layout{};
  out.file = file;
  error.clear();
  Reader r{error};
  Where w{file.empty() ? "layout" : file};
  if (!j.is_object()) return r.fail(w, "format", "expected a JSON object");
  std::string format;
  double version = 0.0;
  if (!r.string(j, w, "format", format, true) || !r.number(j, w, "version", version)) return false;
  if (format != "gblens-layout") return r.fail(w, "format", "expected \"gblens-layout\", got \"" + format + "\"");
  if (version != 1.0) return r.fail(w, "version", "this gblens reads version 1");
  if (!r.string(j, w, "name", out.name, false) || !r.size(j, w, "size", out.width, out.height)) return false;
  if (!r.unknownKeys(j, w, {"format", "version", "name", "size", "parameters", "targets", "camera", "lights", "check"}) ||
      !readCheck(r, j, w, out.check))
    return false;
  auto ts = j.find("targets");
  if (ts == j.end() || !ts->is_array() || ts->empty()) return r.fail(w, "targets", "expected a list of targets");
  for (size_t i = 0; i < ts->size(); ++i)
    if (!readTarget(r, (*ts)[i], w.at("targets[" + std::to_string(i) + "]"), out)) return false;
  if (!checkHistories(r, *ts, w, out)) return false;
  if (auto it = j.find("camera"); it != j.end() && !readCamera(r, *it, w, out.camera)) return false;
  if (auto it = j.find("lights"); it != j.end() && !readLights(r, *it, w, out.lights)) return false;
  return true;
}

bool parseLayoutCamera(const json& j, const std::string& where, LayoutCamera& out, std::string& error) {
  out = LayoutCamera{};
  error.clear();
  Reader r{error};
  return readCamera(r, j, Where{where}, out);
}

bool loadLayoutFile(const std::string& path, const LayoutParameters& params, Layout& out, std::string& error) {
  json j;
  if (!readJsonFile(path, j, error)) {
    if (size_t at = error.find(": cannot read"); at != std::string::npos)
      error.replace(at, 13, ": cannot read the layout file");
    return false;
  }
  return resolveLayoutParameters(j, params, path, error) && parseLayout(j, path, out, error);
}

}  // namespace gb
