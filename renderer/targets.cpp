// Target names, channel names and formats.
#include "renderer/targets.h"

#include "renderer/scene.h"

#include "renderer/vk/check.h"

namespace gb {

static const char* const kNames[kTargetCount] = {"albedo_specular", "normal_shadow", "depth",
                                                 "depth_stencil",   "shadow_map",    "hdr",
                                                 "final",           "coverage_masked", "coverage_full",
                                                 "primitive_id",    "position"};

const char* targetName(Target t) { return kNames[size_t(t)]; }

bool parseTarget(const std::string& name, Target& out) {
  for (size_t i = 0; i < kTargetCount; ++i)
    if (name == kNames[i]) {
      out = Target(i);
      return true;
    }
  return false;
}

std::vector<std::string> channelNames(Target t) {
  switch (t) {
    case Target::AlbedoSpecular: return {"Albedo.R", "Albedo.G", "Albedo.B", "Specular"};
    case Target::NormalShadow: return {"N.X", "N.Y", "N.Z", "Shadow"};
    case Target::Depth: return {"Z"};
    case Target::DepthStencil: return {"Depth", "Stencil"};
    case Target::ShadowMap: return {"Depth"};
    case Target::Hdr:
    case Target::Final: return {"R", "G", "B", "A"};
    case Target::CoverageMasked:
    case Target::CoverageFull: return {"Count"};
    case Target::PrimitiveId: return {"ID"};
    case Target::Position: return {"P.X", "P.Y", "P.Z", "W"};
    case Target::Count: break;
  }
  return {};
}

VkFormat targetFormat(Target t, const RenderOptions& o) {
  switch (t) {
    case Target::AlbedoSpecular: return VK_FORMAT_R8G8B8A8_SRGB;
    case Target::NormalShadow:
      switch (o.normalFormat) {
        case NormalFormat::Rgba16f: return VK_FORMAT_R16G16B16A16_SFLOAT;
        case NormalFormat::Rgba8Snorm: return VK_FORMAT_R8G8B8A8_SNORM;
        // The normal is octahedral in x, y: 16 + 16 bits (SNORM). The shadow term keeps its own
        // 16 bits in w, so the texel is 64 bits like rgba16f's; z is unused (written 0).
        case NormalFormat::OctRg16: return VK_FORMAT_R16G16B16A16_SNORM;
        case NormalFormat::Rgb10a2: return VK_FORMAT_A2B10G10R10_UNORM_PACK32;
      }
      break;
    case Target::Depth: return VK_FORMAT_R32_SFLOAT;
    case Target::DepthStencil:
      return o.depthFormat == DepthFormat::D24S8 ? VK_FORMAT_D24_UNORM_S8_UINT : VK_FORMAT_D32_SFLOAT_S8_UINT;
    case Target::ShadowMap: return o.shadowFormat == ShadowFormat::D16 ? VK_FORMAT_D16_UNORM : VK_FORMAT_D32_SFLOAT;
    case Target::Hdr:
      switch (o.accumFormat) {
        case AccumFormat::Rgba16f: return VK_FORMAT_R16G16B16A16_SFLOAT;
        case AccumFormat::Rgba32f: return VK_FORMAT_R32G32B32A32_SFLOAT;
        case AccumFormat::Rgba8: return VK_FORMAT_R8G8B8A8_UNORM;
      }
      break;
    case Target::Final: return VK_FORMAT_R8G8B8A8_SRGB;
    case Target::CoverageMasked:
    case Target::CoverageFull: return VK_FORMAT_R32_UINT;
    case Target::PrimitiveId: return VK_FORMAT_R32_UINT;
    case Target::Position:
      return o.position == PositionSource::Rgba32f ? VK_FORMAT_R32G32B32A32_SFLOAT : VK_FORMAT_R16G16B16A16_SFLOAT;
    case Target::Count: break;
  }
  GB_ASSERT(!"targetFormat: unknown target");
  return VK_FORMAT_UNDEFINED;
}

void describeReadback(Target t, const RenderOptions& o, CpuImage& img) {
  img.name = targetName(t);
  img.channels = channelNames(t);
  switch (targetFormat(t, o)) {
    case VK_FORMAT_R8G8B8A8_SRGB: img.type = PixelType::U8; img.encoding = Encoding::Srgb; break;
    case VK_FORMAT_R8G8B8A8_UNORM: img.type = PixelType::U8; img.encoding = Encoding::Unorm; break;
    case VK_FORMAT_R8G8B8A8_SNORM: img.type = PixelType::I8; img.encoding = Encoding::Snorm; break;
    case VK_FORMAT_R16G16B16A16_SNORM: img.type = PixelType::I16; img.encoding = Encoding::Snorm; break;
    case VK_FORMAT_A2B10G10R10_UNORM_PACK32: img.type = PixelType::U16; img.encoding = Encoding::Unorm10; break;
    case VK_FORMAT_R16G16B16A16_SFLOAT: img.type = PixelType::F16; img.encoding = Encoding::Float; break;
    case VK_FORMAT_R32_UINT: img.type = PixelType::U32; img.encoding = Encoding::Uint; break;
    case VK_FORMAT_D16_UNORM: img.type = PixelType::U16; img.encoding = Encoding::Unorm; break;
    default: img.type = PixelType::F32; img.encoding = Encoding::Float; break;  // R32F, RGBA32F, D32, D/S
  }
}

std::string targetUnavailable(Target t, const RenderOptions& o, const Scene* scene) {
  const bool forward = o.method == Method::Forward;
  switch (t) {
    case Target::AlbedoSpecular:
    case Target::NormalShadow:
    case Target::Depth:
      if (forward) return "not produced: forward shading has no G-buffer (method forward)";
      if (transientGBuffer(o))
        return "transient: the single-pass G-buffer stays in tile memory (keep_gbuffer off)";
      break;
    case Target::CoverageMasked:
    case Target::CoverageFull:
      if (!o.coverage) return "not computed: coverage off";
      break;
    case Target::PrimitiveId:
      if (!o.primitiveId) return "not computed: primitive_id off";
      if (forward) return "not produced: forward shading has no G-buffer (method forward)";
      break;
    case Target::Position:
      if (o.position == PositionSource::Depth) return "not computed: positions come from depth (position depth)";
      if (forward) return "not produced: forward shading has no G-buffer (method forward)";
      if (transientGBuffer(o))
        return "transient: the single-pass G-buffer stays in tile memory (keep_gbuffer off)";
      break;
    case Target::ShadowMap:
      if (scene && !scene->sun.enabled) return "not computed: the scene has no sun (shadow term 1)";
      break;
    default: break;
  }
  return "";
}

}  // namespace gb
