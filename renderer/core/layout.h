// A G-buffer layout: the targets of a G-buffer (how texels are stored, where they come from) and the
// quantities in their channels with their encodings, the camera and the lights. Every frame gblens
// analyses carries one (docs/layout-format.md); decoding is driven by it (decode.h).
#pragma once
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "renderer/core/image.h"
#include "renderer/core/lights.h"

namespace gb {

// How the texels of a target are stored: per-channel type and encoding, or a packed format.
struct StorageFormat {
  std::string name;  // as written: "rgba16f", "rg16_snorm", "d32s8", ...
  PixelType type = PixelType::F32;
  Encoding encoding = Encoding::Float;
  uint32_t channels = 4;
  bool srgb = false;                 // 8_srgb: colour channels sRGB-encoded (alpha linear)
  bool depth = false, stencil = false;
  bool packed10 = false;             // rgb10a2_unorm
  // Bytes a texel takes when packed (texels.h); depth/stencil: the depth plane only.
  uint32_t packedBytes() const;
};
// Parses a storage format name; false when the text names none.
bool parseStorageFormat(const std::string& text, StorageFormat& out);

enum class QuantityKind : uint8_t {
  Albedo, BaseColor, Emission, Specular, Roughness, Metallic, Occlusion, Shadow, Radiance, Display,
  Normal, Depth, Position, Motion, Id, Stencil, Count, Scalar, Vector
};
const char* name(QuantityKind k);
bool parseQuantityKind(const std::string& text, QuantityKind& out);

enum class ColorEncoding : uint8_t { Linear, Srgb };
enum class NormalEncoding : uint8_t { Xyz, XyzUnorm, Octahedral, OctahedralUnorm, Octahedral12, Spheremap, Lambert };
enum class DepthEncoding : uint8_t { Hardware, Eye, Radial };
// Where vectors are: view space (the camera's), world space, or camera-relative (world axes, the
// eye at the origin: camera-relative rendering).
enum class Space : uint8_t { View, World, CameraRelative };
enum class MotionUnits : uint8_t { Pixels, Ndc, Uv };
const char* name(NormalEncoding e);
const char* name(DepthEncoding e);

struct Quantity {
  QuantityKind kind = QuantityKind::Scalar;
  std::string name;                 // unique in the layout; the prefix of its channel names
  uint32_t target = 0;              // index into Layout::targets
  std::vector<uint32_t> channels;   // channels of that target, in component order
  ColorEncoding color = ColorEncoding::Linear;
  NormalEncoding normal = NormalEncoding::Xyz;
  DepthEncoding depth = DepthEncoding::Eye;
  Space space = Space::View;
  bool normalized = true;
  std::optional<double> background;  // depth: the value stored where nothing was drawn
  bool ofSun = false;                // depth: the sun's shadow-map depth, not the camera's
  double scale = 1.0, bias = 0.0;
  MotionUnits units = MotionUnits::Pixels;
  bool toPrevious = true;            // motion: current -> previous frame ("to_next": the negated vector)
  bool motionYUp = false;            // motion: +y points up the image ("y": "up")
  bool jitterIncluded = false;       // motion: the difference of jittered positions ("jitter": "included")
  std::string unit;                  // scalar/vector: for people
  std::map<uint32_t, std::string> idNames;      // id: value -> name
  std::map<std::string, uint32_t> stencilBits;  // stencil: name -> mask
  nlohmann::json guess;              // a draft layout's note (import --suggest-layout): text or an object
  std::map<std::string, std::string> check;     // `gblens check` policy for this quantity: class -> level
  // A history target (TAA's previous frame, docs/temporal.md): the quantity holds another quantity
  // of the layout as it was one frame earlier ("history_of": its name; "" : not a history), either as
  // that frame's pixels held it ("history_space": "previous", the default) or reprojected into this
  // frame's pixels ("current").
  std::string historyOf;
  bool historyCurrent = false;
};

// Where an imported target's texels come from (ignored for gblens's own frames).
struct TargetSource {
  enum class Kind : uint8_t { None, File, Raw, RenderDoc, Live } kind = Kind::None;
  std::string path;                  // File / Raw: as written (relative to the layout file)
  std::string part;                  // File: EXR part (index or name; "" the first)
  std::vector<std::string> channels; // File: the file's channel names in target channel order
  uint64_t offset = 0;               // Raw: bytes skipped at the start
  uint64_t rowStride = 0;            // Raw: bytes from one row's start to the next (0: rows packed)
  std::string resource;              // RenderDoc: texture name or "#id"
  // Live (`gblens attach`): the attachment the gblens layer copies at the end of a render pass.
  // One of name, color, depth, format picks the attachment; pass (a label) or passIndex the pass.
  struct LivePick {
    std::string pass;                // a debug label around the render pass, or the render pass's name
    int passIndex = -1;              // or the render pass's ordinal in its command buffer (0: the first)
    std::string name;                // the attachment's image (or image view) debug name
    int color = -1;                  // colour attachment N (of the pass's last subpass, or of `subpass`)
    bool depth = false;              // the depth/stencil attachment (of the last subpass drawing with one, or of `subpass`)
    std::string format;              // the one attachment of this storage format
    int subpass = -1;                // with color or depth: that subpass's (a G-buffer read as input attachments later)
    int attachment = -1;             // the render pass's attachment N (VkRenderPassCreateInfo::pAttachments;
                                     // dynamic rendering: colour attachments 0.., then depth)
    int storageSet = -1, storageBinding = -1;  // or the storage image a compute dispatch binds at set / binding
  } live;
};

struct LayoutTarget {
  std::string name;
  StorageFormat format;
  // Formats a file may hold the target in ("format": ["rgba16f", "rgba32f"]): import takes the one
  // the file's channel type holds exactly and sets `format` to it. Empty: `format` only.
  std::vector<StorageFormat> formatChoices;
  nlohmann::json guess;              // a draft layout's note (import --suggest-layout); for people
  std::vector<std::string> channels;
  uint32_t width = 0, height = 0;    // 0: the layout's size (or the source's)
  TargetSource source;
};
// A CpuImage described as the target stores it (name, channel names, type, encoding; no texels).
void describeImage(const LayoutTarget& t, CpuImage& image);

// A world axis with its sign: which way is up in a layout's world ("up": "-y" for a Y-down world).
enum class Axis : uint8_t { PosX, NegX, PosY, NegY, PosZ, NegZ };
const char* name(Axis a);
bool parseAxis(const std::string& text, Axis& out);

// The camera as the layout gives it (before conversion to gblens's convention, import.h).
struct LayoutCamera {
  enum class Convention : uint8_t { Vulkan, D3d, Gl };
  bool present = false;
  glm::dmat4 viewFromWorld{1.0}, clipFromView{1.0};  // as glm matrices (column-major), already reordered
  Convention convention = Convention::Vulkan;
  bool leftHanded = false;   // the view looks down +Z
  Axis up = Axis::PosY;      // the world's up axis
  // The world's axes are left-handed (Unity, Unreal): follows from the view matrix and the view's
  // handedness (settleWorldHandedness); a layout may state it ("world_handedness"), and is checked.
  bool worldLeftHanded = false;
  std::optional<bool> statedWorldLeftHanded;
  std::optional<bool> statedOrthographic;  // "projection", when the layout states it (checked on import)
  bool bottomOrigin = false; // row 0 of the stored images is the bottom of the picture
  uint32_t width = 0, height = 0;  // the image size the projection was made for (0: not given)
  std::string sidecar;       // the matrices come from this JSON file (resolved at import)
  // A sequence's frame (docs/temporal.md): the sub-pixel offset the projection was moved by (pixels,
  // +x right, +y down the image as shown; the matrices are the unjittered ones) and the time.
  std::optional<glm::dvec2> jitter;
  std::optional<double> time;
  struct BufferMatrix {
    std::string buffer;
    uint64_t viewOffset = 0, clipOffset = 0;
    bool worldFromView = false;  // the view matrix given is world_from_view (inverted when read)
    bool rowMajor = false;
    // Only clip_from_world is given (at clipOffset; engines that keep view * projection only): split
    // into view and projection when read (camera.h splitClipFromWorld).
    bool combined = false;
  };
  std::optional<BufferMatrix> renderdoc;  // the matrices come from a capture's uniform buffer
  // `gblens attach` only: the matrices come from the bytes a render pass of the running application
  // binds, a uniform/storage buffer range at set / binding / index, or its push constants; the
  // offsets (in `matrices`, whose buffer name is empty) count from the start of the bound range
  // (push constants: from push-constant byte 0).
  struct LiveBinding {
    std::string pass;        // a debug label or render pass name ...
    int passIndex = -1;      // ... or its ordinal in its command buffer
    uint32_t set = 0, binding = 0, index = 0;
    bool pushConstants = false;
    BufferMatrix matrices;
  };
  std::optional<LiveBinding> live;
  std::string from;  // where import read the matrices (a sidecar's path, a buffer and its offsets)
  nlohmann::json guess;  // a draft layout's note (import --suggest-layout): why this camera; for people
};

// The world's handedness from the view matrix (a mirror, det < 0, between a world and a view of the
// same handedness is impossible for a camera): sets worldLeftHanded; false with a message naming
// "world_handedness" when the layout stated the other one.
bool settleWorldHandedness(LayoutCamera& c, std::string& error);
// camera.live as people read it: "render pass 0, set 0 binding 0" / "render pass \"GBuffer\", push constants".
std::string liveCameraText(const LayoutCamera::LiveBinding& b);

// gblens's world is Y-up and right-handed; a layout's world may have another up axis and sign
// (camera.up) and left-handed axes. The rotation (with a mirror for a left-handed world) that takes
// the layout's world coordinates into gblens's (applied on import to the camera, and to world-space
// vectors when decoded), and back (what people and scripts see: the layout's own axes). The one
// place the up axis is turned.
glm::dmat3 worldFromLayoutWorld(const LayoutCamera& c);
glm::dmat3 layoutWorldFromWorld(const LayoutCamera& c);
// The layout's up axis as a label of world-space values: "Y-up", "Z-up", "Y-down" (up "-y").
std::string upAxisText(const LayoutCamera& c);
// Names that must not be confused: lower case, without '_', '-' and spaces ("HardwareDepth" and
// "hardware_depth" are one name; quantities are found and kept unique by it).
std::string nameKey(const std::string& name);

struct LayoutLights {
  bool present = false;
  bool gblensModel = false;  // attenuation and shading as shaders/shading.h: the probe can evaluate them
  std::string model;
  std::vector<PointLightDesc> points;  // world space
  Sun sun;
  glm::vec3 ambient{0.0f};
};

struct Layout {
  std::string name;
  std::string file;  // where it was read from ("" : built in)
  uint32_t width = 0, height = 0;
  std::vector<LayoutTarget> targets;
  std::vector<Quantity> quantities;
  LayoutCamera camera;
  LayoutLights lights;
  std::map<std::string, std::string> check;  // `gblens check` policy of every quantity: class -> level

  int findTarget(const std::string& targetName) const;  // -1 when none
  // The first quantity of this kind (and name, when given), or null.
  const Quantity* find(QuantityKind kind, const std::string& quantityName = {}) const;
  const Quantity* findByName(const std::string& quantityName) const;
  // The quantities stored in one target, in layout order.
  std::vector<const Quantity*> quantitiesOf(uint32_t target) const;
};

// Why `gblens import` (files, a RenderDoc capture, the Python module) cannot read this layout's
// camera, one line naming the file and the field; "" when it can. camera.live is a running
// application's bytes: only `gblens attach` has them.
std::string importCameraRefusal(const Layout& l);

// Sequences (docs/temporal.md): a run of '#' in a source's path or the camera's sidecar is the frame
// number, zero-padded to the run's length ("cycles_####.exr", Blender's pattern). Whether a layout
// has one, and the layout of frame `number` (every run replaced).
bool hasFramePattern(const Layout& layout);
Layout layoutForFrame(const Layout& layout, int64_t number);
std::string framePath(const std::string& pattern, int64_t number);

}  // namespace gb
