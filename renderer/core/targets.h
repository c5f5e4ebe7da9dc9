// The target table: every render target of the frame under one name (UI, capture channels, JSON,
// bench and docs all use it), with its channel names, storage format under the options, role
// (which decides its GPU usage), size rule and meaning. No Vulkan here: renderer/vk maps
// TexelFormat to VkFormat, the renderer maps roles to usage flags.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <vector>

#include "renderer/core/image.h"
#include "renderer/core/options.h"

namespace gb {

enum class Target : uint8_t {
  AlbedoSpecular,   // "albedo_specular": Albedo.R/G/B (sRGB), Specular
  NormalShadow,     // "normal_shadow": N.X/N.Y/N.Z, Shadow
  Depth,            // "depth": eye depth (USE_EYE_DEPTH) Z
  DepthStencil,     // "depth_stencil": hardware Depth, Stencil
  ShadowMap,        // "shadow_map": light-space Depth
  Hdr,              // "hdr": accumulated light R/G/B/A
  Final,            // "final": tone-mapped sRGB R/G/B/A
  CoverageMasked,   // "coverage_masked": point-light fragment shader runs per pixel
  CoverageFull,     // "coverage_full": light volumes covering the pixel in screen space
  PrimitiveId,      // "primitive_id": ID (first triangle of the instance + triangle + 1; 0 = none), on request
  Position,         // "position": stored P.X/P.Y/P.Z, W (1 = geometry), when options.position is a format
  Motion,           // "motion": M.X/M.Y screen motion in pixels toward the previous frame (+y down), on request
  Visibility,       // "visibility": ID (packed draw + 1 and triangle, renderer/core/visibility.h; 0 = none), --gbuffer visibility
  Count
};
constexpr size_t kTargetCount = size_t(Target::Count);

// How texels are stored, independent of the graphics API.
enum class TexelFormat : uint8_t {
  Rgba8Srgb, Rgba8Unorm, Rgba8Snorm, Rgba16Snorm, Rgb10a2Unorm, Rgba16f, Rgba32f, R32f, R32Uint, Rg16f,
  D32fS8, D24S8, D32f, D16
};
struct TexelFormatInfo {
  const char* name;   // "rgba16f", "d32s8", ...
  PixelType type;     // how a CPU copy holds each channel (D24: U32 of 24 bits; RGB10A2: U16)
  Encoding encoding;
  bool depth = false, stencil = false;
};
const TexelFormatInfo& texelFormatInfo(TexelFormat f);

// What a target is for on the GPU; the renderer derives its usage flags from this.
enum class TargetRole : uint8_t {
  GBuffer,       // colour attachment read by lighting (sampled or subpass input); transient when single pass
  DepthStencil,  // the hardware depth/stencil attachment, also read by lighting
  ShadowMap,     // depth attachment sampled by the G-buffer pass
  Light,         // hdr: blended colour attachment, also written by compute
  Display,       // final: colour attachment
  Counter,       // storage image counted into with atomics
  Id,            // integer colour attachment
  Motion,        // colour attachment written by the geometry pass, read by no pass (views, captures)
};
enum class SizeRule : uint8_t { Output, ShadowMap };

struct TargetInfo {
  Target target;
  const char* name;
  std::vector<std::string> channels;
  TargetRole role;
  SizeRule size;
  TexelFormat (*format)(const RenderOptions&);
  const char* meaning;
};
const std::array<TargetInfo, kTargetCount>& targetTable();
inline const TargetInfo& targetInfo(Target t) { return targetTable()[size_t(t)]; }

inline const char* targetName(Target t) { return targetInfo(t).name; }
bool parseTarget(const std::string& name, Target& out);
inline const std::vector<std::string>& channelNames(Target t) { return targetInfo(t).channels; }
inline TexelFormat texelFormat(Target t, const RenderOptions& o) { return targetInfo(t).format(o); }

// How read-back bytes are described on the CPU (name, channels, type/encoding of each channel).
void describeReadback(Target t, const RenderOptions& options, CpuImage& image);

// Why a target holds nothing in a frame or a capture. One list; text for people from absentText().
enum class Absent : uint8_t {
  No,                 // present
  ForwardNoGBuffer,   // method forward has no G-buffer
  Transient,          // single pass: the G-buffer stays in tile memory
  CoverageOff,
  PrimitiveIdOff,
  PositionFromDepth,  // position depth: no stored position
  MotionOff,          // motion off: no motion target
  RasterGBuffer,      // gbuffer raster: no visibility target
  NoSun,              // no sun: no shadow map
  NotReadBack,        // computed, but the frame's request did not read it back
  NotRequested,       // a capture's --targets left it out
  NotCaptured,        // a capture does not hold it (older manifests, synthetic frames)
  OutsideRegion,      // the viewer read back a window that does not contain the pixel
  NotInLayout,        // an imported frame's layout has no quantity for it (views/analysis/viewable.h)
  NotInSource,        // an imported or streamed frame's source has no such image (compare: reported apart)
};
const char* absentText(Absent a);
// The Absent whose absentText() is `text` (manifests store the text); NotCaptured when none is.
Absent absentFromText(const std::string& text);

// Why a target cannot be read back under these options (Absent::No when it can): transient
// targets, targets that are not computed, and (sceneHasSun false) the shadow map of a sunless scene.
Absent targetAbsence(Target t, const RenderOptions& options, bool sceneHasSun = true);

}  // namespace gb
