// Layout types: storage format names, quantity kinds, lookups (see layout.h).
#include "renderer/core/layout.h"

#include <cctype>

#include <regex>

namespace gb {

uint32_t StorageFormat::packedBytes() const {
  if (packed10) return 4;
  if (depth) return type == PixelType::U16 ? 2 : 4;  // d16; d24 in 32 bits; d32f
  return uint32_t(pixelTypeSize(type)) * channels;
}

bool parseStorageFormat(const std::string& text, StorageFormat& f) {
  f = StorageFormat{};
  f.name = text;
  if (text == "rgb10a2_unorm") {
    f.type = PixelType::U16;
    f.encoding = Encoding::Unorm10;
    f.packed10 = true;
    return true;
  }
  if (text == "d16" || text == "d32f" || text == "d24s8" || text == "d32s8") {
    f.depth = true;
    f.stencil = text == "d24s8" || text == "d32s8";
    f.channels = f.stencil ? 2 : 1;
    f.type = text == "d16" ? PixelType::U16 : PixelType::F32;
    f.encoding = text == "d16" ? Encoding::Unorm : Encoding::Float;  // D24 is widened to float (texels.h)
    return true;
  }
  static const std::regex re("(r|rg|rgb|rgba)(8|16|32)(_unorm|_snorm|_srgb|_uint|f)");
  std::smatch m;
  if (!std::regex_match(text, m, re)) return false;
  f.channels = uint32_t(m[1].length());
  const int bits = std::stoi(m[2]);
  const std::string kind = m[3];
  if (kind == "f") {
    if (bits == 8) return false;
    f.type = bits == 16 ? PixelType::F16 : PixelType::F32;
    f.encoding = Encoding::Float;
  } else if (kind == "_uint") {
    f.type = bits == 8 ? PixelType::U8 : bits == 16 ? PixelType::U16 : PixelType::U32;
    f.encoding = Encoding::Uint;
  } else {
    if (bits == 32) return false;
    const bool snorm = kind == "_snorm";
    if (kind == "_srgb" && bits != 8) return false;
    f.type = bits == 8 ? (snorm ? PixelType::I8 : PixelType::U8) : (snorm ? PixelType::I16 : PixelType::U16);
    f.encoding = snorm ? Encoding::Snorm : kind == "_srgb" ? Encoding::Srgb : Encoding::Unorm;
    f.srgb = kind == "_srgb";
  }
  return true;
}

static const char* const kKindNames[] = {"albedo",   "base_color", "emission", "specular", "roughness",
                                         "metallic", "occlusion",  "shadow",   "radiance", "display",
                                         "normal",   "depth",      "position", "motion",   "id",
                                         "stencil",  "count",      "scalar",   "vector"};
static_assert(sizeof(kKindNames) / sizeof(kKindNames[0]) == size_t(QuantityKind::Vector) + 1);

const char* name(QuantityKind k) { return kKindNames[size_t(k)]; }

bool parseQuantityKind(const std::string& text, QuantityKind& out) {
  for (size_t i = 0; i < std::size(kKindNames); ++i)
    if (text == kKindNames[i]) {
      out = QuantityKind(i);
      return true;
    }
  return false;
}

const char* name(NormalEncoding e) {
  static const char* n[] = {"xyz", "xyz_unorm", "octahedral", "octahedral_unorm", "octahedral", "spheremap", "lambert"};
  return n[size_t(e)];
}
const char* name(DepthEncoding e) {
  static const char* n[] = {"hardware", "eye", "radial"};
  return n[size_t(e)];
}

std::string framePath(const std::string& pattern, int64_t number) {
  std::string out;
  for (size_t i = 0; i < pattern.size();) {
    if (pattern[i] != '#') {
      out += pattern[i++];
      continue;
    }
    size_t n = 0;
    while (i + n < pattern.size() && pattern[i + n] == '#') ++n;
    std::string digits = std::to_string(number < 0 ? -number : number);
    if (digits.size() < n) digits.insert(0, n - digits.size(), '0');
    out += (number < 0 ? "-" : "") + digits;
    i += n;
  }
  return out;
}

bool hasFramePattern(const Layout& l) {
  for (const LayoutTarget& t : l.targets)
    if (t.source.path.find('#') != std::string::npos) return true;
  return l.camera.sidecar.find('#') != std::string::npos;
}

Layout layoutForFrame(const Layout& l, int64_t number) {
  Layout out = l;
  for (LayoutTarget& t : out.targets) t.source.path = framePath(t.source.path, number);
  out.camera.sidecar = framePath(out.camera.sidecar, number);
  return out;
}

void describeImage(const LayoutTarget& t, CpuImage& img) {
  img.name = t.name;
  img.channels = t.channels;
  img.type = t.format.type;
  img.encoding = t.format.encoding;
}

int Layout::findTarget(const std::string& targetName) const {
  for (size_t i = 0; i < targets.size(); ++i)
    if (targets[i].name == targetName) return int(i);
  return -1;
}

const Quantity* Layout::find(QuantityKind kind, const std::string& quantityName) const {
  for (const Quantity& q : quantities)
    if (q.kind == kind && (quantityName.empty() || q.name == quantityName)) return &q;
  return nullptr;
}

const Quantity* Layout::findByName(const std::string& quantityName) const {
  for (const Quantity& q : quantities)
    if (q.name == quantityName) return &q;
  return nullptr;
}

std::vector<const Quantity*> Layout::quantitiesOf(uint32_t target) const {
  std::vector<const Quantity*> out;
  for (const Quantity& q : quantities)
    if (q.target == target) out.push_back(&q);
  return out;
}

static const char* const kAxisNames[] = {"x", "-x", "y", "-y", "z", "-z"};

const char* name(Axis a) { return kAxisNames[size_t(a)]; }

bool parseAxis(const std::string& text, Axis& out) {
  for (size_t i = 0; i < std::size(kAxisNames); ++i)
    if (text == kAxisNames[i] || text == std::string("+") + kAxisNames[i]) {
      out = Axis(i);
      return true;
    }
  return false;
}

std::string liveCameraText(const LayoutCamera::LiveBinding& b) {
  std::string t = b.passIndex >= 0 ? "render pass " + std::to_string(b.passIndex) : "render pass \"" + b.pass + "\"";
  if (b.pushConstants) return t + ", push constants";
  return t + ", set " + std::to_string(b.set) + " binding " + std::to_string(b.binding) +
         (b.index ? " index " + std::to_string(b.index) : "");
}

std::string importCameraRefusal(const Layout& l) {
  if (!l.camera.live) return "";
  return (l.file.empty() ? std::string("layout") : l.file) +
         ": camera: live: the bytes a running application binds are only read by gblens attach; an import reads "
         "the camera from the layout's matrices, a sidecar, --camera or camera.renderdoc";
}

bool settleWorldHandedness(LayoutCamera& c, std::string& error) {
  // A view matrix maps the world to the view rigidly: det +1 between frames of one handedness, -1
  // (a mirror) between a left- and a right-handed one.
  const bool mirrors = glm::determinant(glm::dmat3(c.viewFromWorld)) < 0.0;
  c.worldLeftHanded = c.leftHanded != mirrors;
  if (c.statedWorldLeftHanded && *c.statedWorldLeftHanded != c.worldLeftHanded) {
    error = std::string("camera: world_handedness: \"") + (*c.statedWorldLeftHanded ? "left" : "right") +
            "\", but the view matrix " + (mirrors ? "mirrors" : "does not mirror") + " and the view is " +
            (c.leftHanded ? "left" : "right") + "-handed: the world is " + (c.worldLeftHanded ? "left" : "right") +
            "-handed (or view_handedness is wrong)";
    return false;
  }
  return true;
}

glm::dmat3 worldFromLayoutWorld(const LayoutCamera& c) {
  // The images of the layout's x, y and z axes in gblens's world: a rotation taking `up` to +Y.
  static const glm::dvec3 kImages[6][3] = {
      {{0, 1, 0}, {-1, 0, 0}, {0, 0, 1}},  // x: (x, y, z) -> (-y, x, z)
      {{0, -1, 0}, {1, 0, 0}, {0, 0, 1}},  // -x: (y, -x, z)
      {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}},   // y
      {{1, 0, 0}, {0, -1, 0}, {0, 0, -1}}, // -y: (x, -y, -z), half a turn about X
      {{1, 0, 0}, {0, 0, -1}, {0, 1, 0}},  // z (Blender): (x, z, -y)
      {{1, 0, 0}, {0, 0, 1}, {0, -1, 0}},  // -z: (x, -z, y)
  };
  const glm::dvec3* m = kImages[size_t(c.up)];
  glm::dmat3 r(m[0], m[1], m[2]);  // glm: columns
  // A left-handed world: mirror an axis across up first (z, or y when z is up), so gblens's is right-handed.
  if (c.worldLeftHanded) r[c.up == Axis::PosZ || c.up == Axis::NegZ ? 1 : 2] *= -1.0;
  return r;
}

glm::dmat3 layoutWorldFromWorld(const LayoutCamera& c) { return glm::transpose(worldFromLayoutWorld(c)); }

std::string upAxisText(const LayoutCamera& c) {
  std::string t = name(c.up);  // "y" -> "Y-up", "-y" -> "Y-down": "world (layout: Y-down)"
  const bool down = !t.empty() && t[0] == '-';
  if (down) t.erase(0, 1);
  for (char& ch : t) ch = char(std::toupper(static_cast<unsigned char>(ch)));
  return t + (down ? "-down" : "-up");
}

std::string nameKey(const std::string& name) {
  std::string k;
  for (char ch : name)
    if (ch != '_' && ch != '-' && ch != ' ') k += char(std::tolower(static_cast<unsigned char>(ch)));
  return k;
}

}  // namespace gb
