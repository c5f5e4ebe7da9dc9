// The frame's render targets: one name each (UI, capture channels, JSON, bench all use it),
// their channel names, and their Vulkan formats under the current options.
#pragma once
#include <vulkan/vulkan.h>

#include <array>
#include <string>
#include <vector>

#include "renderer/image.h"
#include "renderer/options.h"

namespace gb {

struct Scene;

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
  Count
};
constexpr size_t kTargetCount = size_t(Target::Count);

const char* targetName(Target t);
bool parseTarget(const std::string& name, Target& out);
std::vector<std::string> channelNames(Target t);

VkFormat targetFormat(Target t, const RenderOptions& options);

// How read-back bytes are described on the CPU (type/encoding of each channel).
void describeReadback(Target t, const RenderOptions& options, CpuImage& image);

// Why a target cannot be read back under these options ("" when it can): transient targets
// (single-pass G-buffer kept in tile memory) and targets that are not computed (coverage off).
// Captures and the viewer list the reason instead of the target. With the scene: a scene without
// a sun has no shadow map (a 1x1 placeholder no pass writes).
std::string targetUnavailable(Target t, const RenderOptions& options, const Scene* scene = nullptr);

}  // namespace gb
