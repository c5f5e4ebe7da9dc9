// The target table, the texel formats and the reasons a target is absent.
#include "renderer/core/targets.h"

#include "renderer/core/layout_json.h"
#include "renderer/core/visibility.h"

#include "renderer/core/assert.h"

namespace gb {

const TexelFormatInfo& texelFormatInfo(TexelFormat f) {
  static const TexelFormatInfo table[] = {
      {"rgba8_srgb", PixelType::U8, Encoding::Srgb},
      {"rgba8_unorm", PixelType::U8, Encoding::Unorm},
      {"rgba8_snorm", PixelType::I8, Encoding::Snorm},
      {"rgba16_snorm", PixelType::I16, Encoding::Snorm},
      {"rgb10a2_unorm", PixelType::U16, Encoding::Unorm10},
      {"rgba16f", PixelType::F16, Encoding::Float},
      {"rgba32f", PixelType::F32, Encoding::Float},
      {"r32f", PixelType::F32, Encoding::Float},
      {"r32_uint", PixelType::U32, Encoding::Uint},
      {"rg16f", PixelType::F16, Encoding::Float},
      {"d32s8", PixelType::F32, Encoding::Float, true, true},
      {"d24s8", PixelType::F32, Encoding::Float, true, true},  // read back as float depth + stencil
      {"d32f", PixelType::F32, Encoding::Float, true, false},
      {"d16", PixelType::U16, Encoding::Unorm, true, false},
  };
  static_assert(sizeof(table) / sizeof(table[0]) == size_t(TexelFormat::D16) + 1);
  return table[size_t(f)];
}

static TexelFormat normalFormat(const RenderOptions& o) {
  switch (o.normalFormat) {
    case NormalFormat::Rgba16f: return TexelFormat::Rgba16f;
    case NormalFormat::Rgba8Snorm: return TexelFormat::Rgba8Snorm;
    // The normal is octahedral in x, y: 16 + 16 bits (SNORM). The shadow term keeps its own
    // 16 bits in w, so the texel is 64 bits like rgba16f's; z is unused (written 0).
    case NormalFormat::OctRg16: return TexelFormat::Rgba16Snorm;
    case NormalFormat::Rgb10a2: return TexelFormat::Rgb10a2Unorm;
  }
  GB_ASSERT(!"normal format");
  return TexelFormat::Rgba16f;
}
static TexelFormat accumFormat(const RenderOptions& o) {
  switch (o.accumFormat) {
    case AccumFormat::Rgba16f: return TexelFormat::Rgba16f;
    case AccumFormat::Rgba32f: return TexelFormat::Rgba32f;
    case AccumFormat::Rgba8: return TexelFormat::Rgba8Unorm;
  }
  GB_ASSERT(!"accumulation format");
  return TexelFormat::Rgba32f;
}
static TexelFormat depthStencilFormat(const RenderOptions& o) {
  return o.depthFormat == DepthFormat::D24S8 ? TexelFormat::D24S8 : TexelFormat::D32fS8;
}
static TexelFormat shadowFormat(const RenderOptions& o) {
  return o.shadowFormat == ShadowFormat::D16 ? TexelFormat::D16 : TexelFormat::D32f;
}
static TexelFormat positionFormat(const RenderOptions& o) {
  return o.position == PositionSource::Rgba32f ? TexelFormat::Rgba32f : TexelFormat::Rgba16f;
}

const std::array<TargetInfo, kTargetCount>& targetTable() {
  using T = Target;
  using R = TargetRole;
  static const std::array<TargetInfo, kTargetCount> table = {{
      {T::AlbedoSpecular, "albedo_specular", {"Albedo.R", "Albedo.G", "Albedo.B", "Specular"}, R::GBuffer,
       SizeRule::Output, [](const RenderOptions&) { return TexelFormat::Rgba8Srgb; },
       "surface albedo (sRGB) and Blinn-Phong specular intensity"},
      {T::NormalShadow, "normal_shadow", {"N.X", "N.Y", "N.Z", "Shadow"}, R::GBuffer, SizeRule::Output, normalFormat,
       "eye-space normal (normal_format) and the sun's shadow term"},
      {T::Depth, "depth", {"Z"}, R::GBuffer, SizeRule::Output, [](const RenderOptions&) { return TexelFormat::R32f; },
       "eye depth, positive distance along -Z (USE_EYE_DEPTH)"},
      {T::DepthStencil, "depth_stencil", {"Depth", "Stencil"}, R::DepthStencil, SizeRule::Output, depthStencilFormat,
       "hardware depth and the stencil (128: geometry; light-mask bits)"},
      {T::ShadowMap, "shadow_map", {"Depth"}, R::ShadowMap, SizeRule::ShadowMap, shadowFormat,
       "the sun's orthographic depth"},
      {T::Hdr, "hdr", {"R", "G", "B", "A"}, R::Light, SizeRule::Output, accumFormat, "accumulated light, linear"},
      {T::Final, "final", {"R", "G", "B", "A"}, R::Display, SizeRule::Output,
       [](const RenderOptions&) { return TexelFormat::Rgba8Srgb; }, "tone-mapped image, sRGB"},
      {T::CoverageMasked, "coverage_masked", {"Count"}, R::Counter, SizeRule::Output,
       [](const RenderOptions&) { return TexelFormat::R32Uint; }, "point-light fragment shader runs per pixel"},
      {T::CoverageFull, "coverage_full", {"Count"}, R::Counter, SizeRule::Output,
       [](const RenderOptions&) { return TexelFormat::R32Uint; }, "light volumes covering the pixel in screen space"},
      {T::PrimitiveId, "primitive_id", {"ID"}, R::Id, SizeRule::Output,
       [](const RenderOptions&) { return TexelFormat::R32Uint; },
       "first triangle of the instance + triangle + 1 (0: no geometry)"},
      {T::Position, "position", {"P.X", "P.Y", "P.Z", "W"}, R::GBuffer, SizeRule::Output, positionFormat,
       "stored surface position (position_space), W 1 on geometry"},
      // RG16F, as TAA renderers store it: 4 bytes a pixel, and half precision keeps 11 significant
      // bits, so a vector of under 16 pixels is exact to 1/128 pixel and one under 1 pixel to 1/2048
      // (reprojection samples bilinearly at far coarser steps); RG32F would double the bandwidth.
      {T::Motion, "motion", {"M.X", "M.Y"}, R::Motion, SizeRule::Output,
       [](const RenderOptions&) { return TexelFormat::Rg16f; },
       "screen motion in pixels toward the previous frame (time - time_step), +y down, jitter excluded; 0 where no "
       "geometry"},
      {T::Visibility, "visibility", {"ID"}, R::Id, SizeRule::Output,
       [](const RenderOptions&) { return TexelFormat::R32Uint; },
       "visibility id: (draw + 1) << triangle bits | triangle (renderer/core/visibility.h; 0: no geometry)"},
  }};
  return table;
}

bool parseTarget(const std::string& name, Target& out) {
  for (const TargetInfo& t : targetTable())
    if (name == t.name) {
      out = t.target;
      return true;
    }
  return false;
}

void describeReadback(Target t, const RenderOptions& o, CpuImage& img) {
  img.name = targetName(t);
  // The channels as gblens's layout names them under these options (what captures and views call them).
  const Layout& l = nativeLayout(o);
  const int i = l.findTarget(img.name);
  img.channels = i >= 0 ? l.targets[size_t(i)].channels : channelNames(t);
  const TexelFormatInfo& f = texelFormatInfo(texelFormat(t, o));
  img.type = f.type;
  img.encoding = f.encoding;
}

static const char* const kAbsentText[] = {
    "",
    "not produced: forward shading has no G-buffer (method forward)",
    "transient: the single-pass G-buffer stays in tile memory (keep_gbuffer off)",
    "not computed: coverage off",
    "not computed: primitive_id off",
    "not computed: positions come from depth (position depth)",
    "not computed: motion off",
    "not computed: the G-buffer is rasterized (gbuffer raster)",
    "not computed: the scene has no sun (shadow term 1)",
    "not read back",
    "not requested (--targets)",
    "not captured",
    "pixel outside the read-back region",
    "not in this G-buffer's layout (no quantity of the imported frame fills it)",
    "not in the source (the imported capture or the streamed frame has no such image)",
};
static_assert(sizeof(kAbsentText) / sizeof(kAbsentText[0]) == size_t(Absent::NotInSource) + 1);

const char* absentText(Absent a) { return kAbsentText[size_t(a)]; }

Absent absentFromText(const std::string& text) {
  for (size_t i = 1; i < std::size(kAbsentText); ++i)
    if (text == kAbsentText[i]) return Absent(i);
  return Absent::NotCaptured;
}

Absent targetAbsence(Target t, const RenderOptions& o, bool sceneHasSun) {
  const bool forward = o.method == Method::Forward;
  switch (t) {
    case Target::AlbedoSpecular:
    case Target::NormalShadow:
    case Target::Depth:
      if (forward) return Absent::ForwardNoGBuffer;
      if (transientGBuffer(o)) return Absent::Transient;
      break;
    case Target::CoverageMasked:
    case Target::CoverageFull:
      if (!o.coverage) return Absent::CoverageOff;
      break;
    case Target::PrimitiveId:
      if (!o.primitiveId) return Absent::PrimitiveIdOff;
      if (forward) return Absent::ForwardNoGBuffer;
      break;
    case Target::Motion:
      if (!o.motion) return Absent::MotionOff;
      if (forward) return Absent::ForwardNoGBuffer;
      break;
    case Target::Position:
      if (o.position == PositionSource::Depth) return Absent::PositionFromDepth;
      if (forward) return Absent::ForwardNoGBuffer;
      if (transientGBuffer(o)) return Absent::Transient;
      break;
    case Target::Visibility:
      // Auto here is a frame whose options no renderer resolved (frameOptions): an import's, or a
      // manifest's from before --gbuffer. Neither holds a visibility target.
      if (o.gbuffer != GBufferKind::Visibility) return Absent::RasterGBuffer;
      if (forward) return Absent::ForwardNoGBuffer;
      if (!visibilityFrame(o)) return Absent::RasterGBuffer;  // the single-pass path rasterizes its G-buffer
      break;
    case Target::ShadowMap:
      if (!sceneHasSun) return Absent::NoSun;
      break;
    default: break;
  }
  return Absent::No;
}

}  // namespace gb
