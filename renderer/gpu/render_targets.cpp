// The frame's targets on the GPU: sizes, usage from the target table's roles, (re)creation when
// the size or a format changes, and which of them a frame can read back.
#include "renderer/gpu/render_targets.h"

#include <algorithm>

#include "renderer/core/texels.h"
#include "renderer/gpu/visibility_scene.h"
#include "renderer/vk/check.h"
#include "renderer/vk/formats.h"

namespace gb {

bool primitiveIdOn(const GpuContext& ctx, const RenderOptions& o) { return o.primitiveId && ctx.features.primitiveId; }

bool clearViews(const GpuContext& ctx, const RenderOptions& o) {
  return !transientGBuffer(o) && (o.gbufferClear == GBufferClear::Compute ||
                                  (o.gbufferClear == GBufferClear::Auto && !ctx.isCpu));
}

bool computeClears(const GpuContext& ctx, const RenderOptions& o, Method ran, std::string& reason) {
  if (transientGBuffer(o))
    return reason = "the single-pass G-buffer may live in tile memory: the render pass clears it", false;
  if (o.gbufferClear == GBufferClear::RenderPass) return reason = "the render pass clears (--gbuffer-clear render-pass)", false;
  if (o.gbufferClear == GBufferClear::Compute) return reason = "--gbuffer-clear compute", true;
  if (ctx.isCpu) return reason = "the render pass clears: a CPU device (a memset there)", false;
  if (ran == Method::Deferred)
    return reason = "the render pass clears: method deferred (compute clears measured slower there, docs/perf-gpu.md)", false;
  return reason = "auto: a GPU device, method " + std::string(name(ran)), true;
}

GBufferChoice frameGBuffer(const Renderer& r, const RenderOptions& o) {
  const GBufferChoice choice = chooseGBuffer(o, r.ctx->isCpu ? DeviceKind::Cpu : DeviceKind::Gpu);
  if (choice.gbuffer != GBufferKind::Visibility) return choice;
  RenderOptions visibility = o;
  visibility.gbuffer = GBufferKind::Visibility;
  const std::string refused = visibilityRefusal(r, visibility);
  if (refused.empty()) return choice;
  if (o.gbuffer == GBufferKind::Auto) return {GBufferKind::Raster, "auto: raster (" + refused + ")"};
  // Method forward draws no G-buffer at all: nothing ran instead.
  return {GBufferKind::Raster, refused + (o.method == Method::Forward ? "" : " (the G-buffer pass ran instead)")};
}

RenderOptions frameOptions(const Renderer& r, const RenderOptions& o) {
  RenderOptions ran = o;
  ran.gbuffer = frameGBuffer(r, o).gbuffer;
  return ran;
}

bool finalStorageView(const GpuContext& ctx, const RenderOptions& o) {
  return !singlePassFrame(o) &&
         (o.tonemapPass == TonemapPass::Compute || (o.tonemapPass == TonemapPass::Auto && !ctx.isCpu));
}

bool computeToneMap(const GpuContext& ctx, const RenderOptions& o, Method ran, std::string& reason) {
  if (singlePassFrame(o))
    return reason = "raster: the single-pass path tone-maps in its last subpass (hdr as an input attachment)", false;
  if (o.tonemapPass == TonemapPass::Raster) return reason = "raster (--tonemap-pass raster)", false;
  if (o.tonemapPass == TonemapPass::Compute) return reason = "--tonemap-pass compute", true;
  if (ctx.isCpu) return reason = "raster: a CPU device (compute image stores are slow there, docs/performance.md)", false;
  if (ran != Method::Tiled && ran != Method::Clustered)
    return reason = std::string("raster: method ") + name(ran) + " (auto: compute for tiled and clustered)", false;
  return reason = "auto: a GPU device, method " + std::string(name(ran)), true;
}

// The unsigned format of a colour format's texel size: the storage view clear_gbuffer writes
// zeros through (formats of one size are view-compatible; zero bits are 0 in every format).
static VkFormat clearViewFormat(TexelFormat f) {
  switch (packedTexelBytes(f)) {
    case 4: return VK_FORMAT_R32_UINT;
    case 8: return VK_FORMAT_R32G32_UINT;
    case 16: return VK_FORMAT_R32G32B32A32_UINT;
  }
  GB_ASSERT(!"G-buffer texel size");
  return VK_FORMAT_UNDEFINED;
}

std::vector<Target> readableTargets(const Renderer& r, const RenderOptions& o) {
  std::vector<Target> out;
  for (const TargetInfo& info : targetTable()) {
    if (targetAbsence(info.target, o, r.scene->sun.enabled) != Absent::No) continue;
    if (info.target == Target::PrimitiveId && !primitiveIdOn(*r.ctx, o)) continue;
    if (info.target == Target::Visibility && !visibilityRefusal(r, o).empty()) continue;  // rasterized instead
    out.push_back(info.target);
  }
  return out;
}

FrameRequest captureRequest(const std::vector<Target>& targets, const RenderOptions& o) {
  FrameRequest r;
  r.readback = targets;
  auto has = [&](Target t) { return std::find(targets.begin(), targets.end(), t) != targets.end(); };
  r.cullingStats = o.coverage && has(Target::CoverageMasked) && has(Target::Depth);
  return r;
}

static TargetsKey targetsKey(const Renderer& r, const RenderOptions& o) {
  const GpuContext& ctx = *r.ctx;
  const Scene& s = *r.scene;
  TargetsKey k;
  k.width = o.width;
  k.height = o.height;
  k.shadowMapSize = s.sun.enabled ? o.shadowMapSize : 1;
  k.normalFormat = o.normalFormat;
  k.depthFormat = o.depthFormat;
  k.accumFormat = o.accumFormat;
  k.shadowFormat = o.shadowFormat;
  k.position = o.position;
  k.coverage = o.coverage;
  k.transientGBuffer = transientGBuffer(o);
  k.primitiveId = primitiveIdOn(ctx, o);
  k.motion = o.motion;
  k.clearViews = clearViews(ctx, o);
  k.finalStorage = finalStorageView(ctx, o);
  k.visibility = visibilityFrame(o);
  k.slotImages = r.overlapAllowed && k.visibility;  // frames may overlap (side_queue.h)
  return k;
}

VkExtent2D targetExtent(const GpuContext& ctx, Target t, const Scene& s, const RenderOptions& o) {
  // Targets this frame does not compute keep a valid, tiny 1x1 image.
  bool unused = false;
  switch (t) {
    case Target::CoverageMasked:
    case Target::CoverageFull: unused = !o.coverage; break;
    case Target::PrimitiveId: unused = !primitiveIdOn(ctx, o); break;
    case Target::Position: unused = o.position == PositionSource::Depth; break;
    case Target::Motion: unused = !o.motion; break;
    case Target::Visibility: unused = !visibilityFrame(o); break;
    case Target::ShadowMap: unused = !s.sun.enabled; break;
    default: break;
  }
  if (unused) return {1, 1};
  if (targetInfo(t).size == SizeRule::ShadowMap) return {o.shadowMapSize, o.shadowMapSize};
  return {o.width, o.height};
}

bool targetTransient(Target t, const RenderOptions& o) {
  const bool placeholder = t == Target::Position && o.position == PositionSource::Depth;
  return targetInfo(t).role == TargetRole::GBuffer && transientGBuffer(o) && !placeholder;
}

// Usage flags from the target's role (renderer/core/targets.h).
static VkImageUsageFlags targetUsage(TargetRole role, bool transient) {
  const VkImageUsageFlags color = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                  VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  switch (role) {
    case TargetRole::GBuffer:
      return transient ? (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT) : color;
    case TargetRole::DepthStencil:
      return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
             VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case TargetRole::ShadowMap:
      return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case TargetRole::Light: return color | VK_IMAGE_USAGE_STORAGE_BIT;
    case TargetRole::Display: return color;
    case TargetRole::Counter:
      return VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
             VK_IMAGE_USAGE_SAMPLED_BIT;
    case TargetRole::Id:
    case TargetRole::Motion:
      return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  }
  GB_ASSERT(!"target role");
  return 0;
}

static ImageDesc targetDesc(const GpuContext& ctx, Target t, const Scene& s, const RenderOptions& o) {
  ImageDesc d;
  d.format = targetFormat(t, o);
  VkExtent2D e = targetExtent(ctx, t, s, o);
  d.width = e.width;
  d.height = e.height;
  d.name = targetName(t);
  d.transient = targetTransient(t, o);
  // An unused stored position is a 1x1 placeholder only ever bound for sampling.
  d.usage = t == Target::Position && o.position == PositionSource::Depth ? VkImageUsageFlags(VK_IMAGE_USAGE_SAMPLED_BIT)
                                                                          : targetUsage(targetInfo(t).role, d.transient);
  const TargetRole role = targetInfo(t).role;
  const bool colour = role == TargetRole::GBuffer || role == TargetRole::Id || role == TargetRole::Motion;
  // The G-buffer's colour targets under --gbuffer visibility: gbuffer_resolve writes them through the same views.
  const bool resolved = visibilityFrame(o) && role != TargetRole::Id && t != Target::Visibility;
  if (colour && !d.transient && (d.usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT) && (clearViews(ctx, o) || resolved))
    d.clearFormat = clearViewFormat(texelFormat(t, o));
  if (t == Target::PrimitiveId && visibilityFrame(o) && (d.usage & VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT))
    d.clearFormat = VK_FORMAT_R32_UINT;
  // final (sRGB, no storage support) written by tonemap_compute through a UNORM view, the shader
  // encoding sRGB itself.
  if (t == Target::Final && finalStorageView(ctx, o)) {
    GB_ASSERT(d.format == VK_FORMAT_R8G8B8A8_SRGB);
    d.clearFormat = VK_FORMAT_R8G8B8A8_UNORM;
  }
  return d;
}

void destroyTargets(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  for (GraphTarget& t : r.targets) {
    destroyImage(ctx, t.image);
    t = GraphTarget{};
  }
  for (GraphTarget& t : r.parked) {
    if (t.image.image) destroyImage(ctx, t.image);
    t = GraphTarget{};
  }
  for (Buffer& b : r.readbackBuffers) destroyBuffer(ctx, b);
  clearFramebuffers(ctx, r.graphCache);
  r.shadowKey.reset();
  r.skyKey.reset();
  r.targetsValid = false;
}

bool targetsCurrent(const Renderer& r, const RenderOptions& o) {
  return r.targetsValid && targetsKey(r, o) == r.targetsKey;
}

void ensureTargets(Renderer& r, const RenderOptions& o) {
  TargetsKey key = targetsKey(r, o);
  if (r.targetsValid && key == r.targetsKey) return;
  vkDeviceWaitIdle(r.ctx->device);  // frames in flight use the old ones
  destroyTargets(r);
  for (size_t i = 0; i < kTargetCount; ++i)
    r.targets[i].image = createImage(*r.ctx, targetDesc(*r.ctx, Target(i), *r.scene, o));
  // The other slot's depth and id, named alike (an application's capture of gblens shows both).
  if (key.slotImages)
    for (size_t i = 0; i < kSlotTargets.size(); ++i)
      r.parked[i].image = createImage(*r.ctx, targetDesc(*r.ctx, kSlotTargets[i], *r.scene, o));
  r.targetsSlot = r.slot;
  r.targets[size_t(Target::ShadowMap)].keep = true;  // reused while the sun and geometry stay
  // The frame's product: stored even when nothing reads it in the frame (a frame in flight is read
  // back, presented or compared after it, not in it).
  r.targets[size_t(Target::Final)].keep = true;
  r.targetsValid = true;
  r.targetsKey = key;
}

}  // namespace gb
