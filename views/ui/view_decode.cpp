// Views of a stored frame decoded on the GPU (view_decode.h): each view's parameters from its layout
// quantity, the texels of the targets the views read in one host-visible buffer, one dispatch a view.
#include "views/ui/view_decode.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "renderer/core/assert.h"
#include "renderer/core/decode.h"
#include "renderer/vk/check.h"
#include "renderer/vk/pipeline.h"

namespace gb {

using namespace gpu;

static_assert(uint32_t(PixelType::U8) == kPixelU8 && uint32_t(PixelType::I8) == kPixelI8 &&
              uint32_t(PixelType::U16) == kPixelU16 && uint32_t(PixelType::I16) == kPixelI16 &&
              uint32_t(PixelType::U32) == kPixelU32 && uint32_t(PixelType::F16) == kPixelF16 &&
              uint32_t(PixelType::F32) == kPixelF32);
static_assert(uint32_t(Encoding::Unorm) == kEncodingUnorm && uint32_t(Encoding::Snorm) == kEncodingSnorm &&
              uint32_t(Encoding::Srgb) == kEncodingSrgb && uint32_t(Encoding::Float) == kEncodingFloat &&
              uint32_t(Encoding::Uint) == kEncodingUint && uint32_t(Encoding::Unorm10) == kEncodingUnorm10 &&
              uint32_t(Encoding::Unorm24) == kEncodingUnorm24);
static_assert(uint32_t(NormalEncoding::Lambert) == 6);  // view_decode.comp numbers them in layout.h's order

static constexpr uint32_t kMaxViews = 64, kSlotsPerView = 4;
static constexpr VkDeviceSize kTexelAlignment = 256;  // >= every device's minStorageBufferOffsetAlignment

void initViewDecoder(ViewDecoder& d, GpuContext& ctx) {
  std::vector<VkDescriptorSetLayoutBinding> bindings;  // texels, surface texels, the image, params, results
  for (uint32_t b = 0; b < 5; ++b)
    bindings.push_back({b, b == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1,
                        VK_SHADER_STAGE_COMPUTE_BIT, nullptr});
  d.setLayout = createSetLayout(ctx, bindings, VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR, "set0.view_decode");
  VkPushConstantRange push{VK_SHADER_STAGE_COMPUTE_BIT, 0, 16};
  VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pci.setLayoutCount = 1;
  pci.pSetLayouts = &d.setLayout;
  pci.pushConstantRangeCount = 1;
  pci.pPushConstantRanges = &push;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &pci, nullptr, &d.layout));
  d.params = createBuffer(ctx, kMaxViews * sizeof(ViewDecodeParams), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Upload,
                          "view_decode params");
  d.results = createBuffer(ctx, kMaxViews * kSlotsPerView * sizeof(RangeResult), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           MemoryUse::Readback, "view_decode ranges");
}

void destroyViewDecoder(ViewDecoder& d, GpuContext& ctx) {
  if (!d.layout) return;
  vkDeviceWaitIdle(ctx.device);
  for (auto& [key, pipeline] : d.pipelines) vkDestroyPipeline(ctx.device, pipeline, nullptr);
  vkDestroyPipelineLayout(ctx.device, d.layout, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, d.setLayout, nullptr);
  for (Buffer* b : {&d.texels, &d.params, &d.results}) destroyBuffer(ctx, *b);
  d = ViewDecoder{};
}

namespace {

VkDeviceSize texelBytes(const CpuImage& image) { return (image.data.size() + 3) / 4 * 4; }

// The camera depth that says where surfaces are (decode.cpp hasSurface): the first one whose target
// the frame holds (mode kDecodeSurfaceDepth); kDecodeSurfaceNone when the layout has some and the
// frame none. A property of the frame, read only by the views of normals and positions.
struct SurfaceDepth {
  uint32_t mode = kDecodeSurfaceAll;
  const Quantity* quantity = nullptr;
};
SurfaceDepth surfaceDepthOf(const FrameSnapshot& f) {
  SurfaceDepth s;
  for (const Quantity& q : f.layout.quantities) {
    if (q.kind != QuantityKind::Depth || q.ofSun) continue;
    s.mode = kDecodeSurfaceNone;
    if (layoutImage(f, q.target)) return {kDecodeSurfaceDepth, &q};
  }
  return s;
}
bool needsSurface(const ViewDef& view) { return view.visual == Visual::Normal || view.visual == Visual::Position; }

// Which stored values equal `value` as CpuImage::value's double would (decode.cpp compares doubles).
DecodeMatch matchOf(const CpuImage& image, uint32_t channel, std::optional<double> value) {
  DecodeMatch m{};
  if (!value) return m;
  if (image.type == PixelType::F32 || image.type == PixelType::F16) {
    if (double(float(*value)) == *value) m.codes.x = 1, m.value.x = float(*value);  // else no float equals it
    return m;
  }
  std::vector<uint32_t> codes;
  auto test = [&](uint64_t code) {
    if (code <= 0xFFFFFFFFu && decodeRaw(image.type, image.encoding, channel, uint32_t(code)) == *value &&
        std::find(codes.begin(), codes.end(), uint32_t(code)) == codes.end())
      codes.push_back(uint32_t(code));
  };
  if (pixelTypeSize(image.type) <= 2) {
    for (uint32_t c = 0; c < (1u << (8 * pixelTypeSize(image.type))); ++c) test(c);
  } else {  // 32-bit codes: plain integers, 24-bit unorm (d24), unorm over 255
    const double scale = image.encoding == Encoding::Unorm24 ? 16777215.0 : image.encoding == Encoding::Unorm ? 255.0 : 1.0;
    const double near = std::round(*value * scale);
    for (double c = near - 1.0; c <= near + 1.0; c += 1.0)
      if (c >= 0.0) test(uint64_t(c));
  }
  GB_ASSERT(codes.size() <= 2);  // one code per value, or snorm's two for -1
  if (!codes.empty()) m.codes = {2u, codes[0], codes.back(), 0u};
  return m;
}

// A depth's "nothing drawn" value: its background, or for a camera's hardware depth without one the
// far plane (decode.cpp decodeEyeDepth).
std::optional<double> nothingDrawn(const FrameSnapshot& f, const Quantity& q) {
  if (q.background || q.ofSun || q.depth != DepthEncoding::Hardware) return q.background;
  return f.camera.reversedZ ? 0.0 : 1.0;
}

DecodeTexels texelsOf(const TargetImage& t) {
  DecodeTexels out{};
  out.size = {t.image.width, t.image.height, t.x0, t.y0};
  out.format = {uint32_t(t.image.type), uint32_t(t.image.encoding), t.image.channelCount(), uint32_t(t.image.texelBytes())};
  return out;
}

uint32_t decodeKind(Visual v) {
  switch (v) {
    case Visual::Color: return kDecodeColor;
    case Visual::Scalar: return kDecodeScalar;
    case Visual::Vector: return kDecodeVector;
    case Visual::Normal: return kDecodeNormal;
    case Visual::Depth: return kDecodeDepth;
    case Visual::Position: return kDecodePosition;
    case Visual::Motion: return kDecodeMotion;
    case Visual::Id:
    case Visual::Stencil:
    case Visual::Count: return kDecodeInteger;
  }
  return kDecodeScalar;
}

// The view's parameters (its quantity's encodings, the surface depth, the camera where it matters).
ViewDecodeParams paramsOf(const FrameSnapshot& f, const ViewDef& view, const SurfaceDepth& surfaceDepth, uint32_t slot) {
  const Quantity& q = f.layout.quantities[size_t(view.quantity)];
  const TargetImage& ti = f.images[q.target];
  ViewDecodeParams p{};
  p.texels = texelsOf(ti);
  for (size_t k = 0; k < q.channels.size() && k < 4; ++k) p.channels[int(k)] = q.channels[k];
  uint32_t flags = 0;
  if (q.color == ColorEncoding::Srgb) flags |= kDecodeFlagSrgb;
  if (q.ofSun) flags |= kDecodeFlagSun;
  if (q.motionYUp) flags |= kDecodeFlagMotionYUp;
  if (!q.toPrevious) flags |= kDecodeFlagToNext;
  if (q.kind == QuantityKind::Depth && q.depth == DepthEncoding::Hardware) flags |= kDecodeFlagHardware;
  p.values = glm::vec4(float(q.scale), float(q.bias), 1.0f, 0.0f);
  p.encoding = {uint32_t(q.normal), 0u, slot, 0u};
  if (q.kind == QuantityKind::Depth) p.background = matchOf(ti.image, q.channels[0], nothingDrawn(f, q));
  const uint32_t surface = needsSurface(view) ? surfaceDepth.mode : kDecodeSurfaceAll;
  const Quantity* s = surfaceDepth.quantity;
  p.surface = p.texels;
  if (surface == kDecodeSurfaceDepth) {
    const TargetImage& st = f.images[s->target];
    p.surface = texelsOf(st);
    p.encoding.y = s->channels[0];
    p.values.z = float(s->scale), p.values.w = float(s->bias);
    p.surfaceBackground = matchOf(st.image, s->channels[0], nothingDrawn(f, *s));
    if (s->depth == DepthEncoding::Hardware) flags |= kDecodeFlagSurfaceHardware;
  }
  p.mode = {decodeKind(view.visual), uint32_t(q.channels.size()), flags, surface};
  const glm::dvec2 size(f.camera.width, f.camera.height);
  const glm::dvec2 units = q.units == MotionUnits::Ndc ? size * 0.5 : q.units == MotionUnits::Uv ? size : glm::dvec2(1.0);
  p.camera = glm::vec4(float(units.x), float(units.y), 0.0f, 0.0f);
  // A stored position into eye space (decode.cpp eyeFromSpace: a camera-relative one without the
  // eye's translation): its distance to the eye is the view's fourth component.
  glm::dmat4 eye(1.0);
  const glm::dmat3 world = worldFromLayoutWorld(f.layout.camera);
  if (q.space == Space::View && f.layout.camera.leftHanded) eye[2][2] = -1.0;
  if (q.space == Space::World) eye = f.camera.eyeFromWorld * glm::dmat4(world);
  if (q.space == Space::CameraRelative) eye = glm::dmat4(glm::dmat3(f.camera.eyeFromWorld) * world);
  p.eyeFromStored = glm::mat4(eye);
  return p;
}

}  // namespace

std::string gpuDecodeRefusal(const GpuContext& ctx, const FrameSnapshot& f, const ViewDef& view) {
  if (view.spreadOf >= 0) return "a sample spread is computed on the CPU";
  if (view.quantity < 0 || size_t(view.quantity) >= f.layout.quantities.size()) return "not a layout quantity's view";
  const TargetImage* ti = layoutImage(f, view.target);
  if (!ti) return "the frame does not hold its target";
  const Quantity& q = f.layout.quantities[size_t(view.quantity)];
  if (view.visual == Visual::Position && q.kind != QuantityKind::Position) return "a position from depth";
  const uint64_t limit = ctx.properties.limits.maxStorageBufferRange;
  const SurfaceDepth s = surfaceDepthOf(f);
  const bool surface = needsSurface(view) && s.mode == kDecodeSurfaceDepth;
  if (texelBytes(ti->image) > limit || (surface && texelBytes(f.images[s.quantity->target].image) > limit))
    return "its target is larger than the device's storage buffer range";
  return "";
}

std::vector<RangeStats> selectRanges(const std::vector<RangeStats>& all, const ViewDef& view, uint32_t mask) {
  if (view.visual == Visual::Motion || view.integer) return all.empty() ? all : std::vector<RangeStats>{all[0]};
  std::vector<RangeStats> out;
  for (size_t c = 0; c < all.size(); ++c)
    if (mask & (1u << c)) out.push_back(all[c]);
  return out;
}

namespace {

// The targets the views read, each at an aligned offset of the texel buffer (grown when short).
std::vector<VkDeviceSize> uploadTexels(ViewDecoder& d, GpuContext& ctx, const FrameSnapshot& f, const std::vector<bool>& used) {
  std::vector<VkDeviceSize> at(f.images.size(), 0);
  VkDeviceSize bytes = 0;
  for (size_t t = 0; t < f.images.size(); ++t)
    if (used[t]) at[t] = bytes, bytes += (texelBytes(f.images[t].image) + kTexelAlignment - 1) / kTexelAlignment * kTexelAlignment;
  if (d.texels.size < bytes) {
    destroyBuffer(ctx, d.texels);
    d.texels = createBuffer(ctx, bytes + bytes / 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, MemoryUse::Upload, "view_decode texels");
  }
  for (size_t t = 0; t < f.images.size(); ++t)
    if (used[t]) std::memcpy(static_cast<uint8_t*>(d.texels.mapped) + at[t], f.images[t].image.data.data(), f.images[t].image.data.size());
  return at;
}

// The view's pipeline: its shader variant specialised with what its parameters say of kind and storage.
VkPipeline pipelineOf(ViewDecoder& d, GpuContext& ctx, const ViewDecodeParams& p, bool integer) {
  const uint32_t values[17] = {p.mode.x,       p.mode.z,       p.mode.y,       p.texels.format.x, p.texels.format.y, p.texels.format.w,
                               p.channels.x,   p.channels.y,   p.channels.z,   p.channels.w,      p.encoding.x,      p.mode.w,
                               p.surface.format.x, p.surface.format.y, p.surface.format.w, p.encoding.y, p.encoding.w};
  std::vector<SpecConstant> spec;
  for (uint32_t i = 0; i < 17; ++i) spec.push_back({i, values[i]});
  std::vector<uint32_t> key(values, values + 17);
  key.push_back(integer);
  VkPipeline& pipeline = d.pipelines[key];
  if (!pipeline) pipeline = createComputePipeline(ctx, integer ? Shader::view_decode_uint_comp : Shader::view_decode_comp, spec, d.layout);
  return pipeline;
}

// The components a view's mappings can select (visualize.cpp viewMapping: a normal's and a
// position's fourth, their length and distance, too): the only ones whose statistics are reduced.
uint32_t rangeComponents(const ViewDef& view) {
  if (view.integer || view.visual == Visual::Motion) return 1;
  if (view.visual == Visual::Normal || view.visual == Visual::Position) return 4;
  return std::clamp(view.components, 1u, kSlotsPerView);
}

RangeStats statsOf(const RangeResult& s, bool integer) {
  RangeStats o;
  o.count = s.minMax.z;
  o.nan = s.minMax.w;
  o.inf = s.counts.x;
  o.negative = s.counts.y;
  if (o.count && integer) o.lo = double(s.minMax.x), o.hi = double(s.minMax.y);
  else if (o.count) o.lo = floatFromOrdered(s.minMax.x), o.hi = floatFromOrdered(s.minMax.y);
  return o;
}

}  // namespace

std::vector<std::vector<RangeStats>> decodeViewsOnGpu(ViewDecoder& d, GpuContext& ctx, const FrameSnapshot& f,
                                                      const std::vector<ViewDef>& views, const std::vector<int>& which,
                                                      const std::vector<bool>& ranges, ViewImages& images) {
  std::vector<std::vector<RangeStats>> out(views.size());
  if (which.empty()) return out;
  if (which.size() > kMaxViews) {  // a layout of more views than the parameter slots: in turns
    for (size_t at = 0; at < which.size(); at += kMaxViews) {
      const std::vector<int> part(which.begin() + long(at), which.begin() + long(std::min(which.size(), at + kMaxViews)));
      std::vector<std::vector<RangeStats>> some = decodeViewsOnGpu(d, ctx, f, views, part, ranges, images);
      for (int k : part) out[size_t(k)] = std::move(some[size_t(k)]);
    }
    return out;
  }
  if (!images.images.empty()) vkDeviceWaitIdle(ctx.device);  // the view images are sampled by frames in flight
  images.images.resize(std::max(images.images.size(), views.size()));
  std::vector<bool> used(f.images.size(), false);
  auto* params = static_cast<ViewDecodeParams*>(d.params.mapped);
  auto* slots = static_cast<RangeResult*>(d.results.mapped);
  const SurfaceDepth surfaceDepth = surfaceDepthOf(f);
  std::vector<uint32_t> surfaceOf(which.size(), 0);  // the target bound as the surface texels (none: the view's own)
  for (size_t i = 0; i < which.size(); ++i) {
    const ViewDef& view = views[size_t(which[i])];
    GB_ASSERT(gpuDecodeRefusal(ctx, f, view).empty());
    params[i] = paramsOf(f, view, surfaceDepth, uint32_t(i * kSlotsPerView));
    params[i].encoding.w = size_t(which[i]) < ranges.size() && ranges[size_t(which[i])] ? rangeComponents(view) : 0u;
    used[view.target] = true;
    surfaceOf[i] = params[i].mode.w == kDecodeSurfaceDepth ? surfaceDepth.quantity->target : view.target;
    used[surfaceOf[i]] = true;
    const TargetImage& ti = f.images[view.target];
    ensureViewImage(ctx, images.images[size_t(which[i])], view.integer, ti.image.width, ti.image.height, view.name);
    for (uint32_t k = 0; k < kSlotsPerView; ++k) slots[i * kSlotsPerView + k] = {glm::uvec4(0xFFFFFFFFu, 0u, 0u, 0u), glm::uvec4(0u)};
  }
  const std::vector<VkDeviceSize> at = uploadTexels(d, ctx, f, used);
  const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
  submitOnce(ctx, [&](VkCommandBuffer cmd) {
    for (int k : which)  // every texel is written: what the image held does not matter
      imageBarrier(cmd, images.images[size_t(k)].image, all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL, VK_PIPELINE_STAGE_2_NONE, 0,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
    for (size_t i = 0; i < which.size(); ++i) {
      const ViewDef& view = views[size_t(which[i])];
      const Image& out = images.images[size_t(which[i])];
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, pipelineOf(d, ctx, params[i], view.integer));
      const CpuImage& texels = f.images[view.target].image;
      const VkDescriptorBufferInfo buffers[4] = {
          {d.texels.buffer, at[view.target], texelBytes(texels)},
          {d.texels.buffer, at[surfaceOf[i]], texelBytes(f.images[surfaceOf[i]].image)},
          {d.params.buffer, 0, VK_WHOLE_SIZE},
          {d.results.buffer, 0, VK_WHOLE_SIZE}};
      const VkDescriptorImageInfo image{VK_NULL_HANDLE, view.integer ? out.view : out.clearView, VK_IMAGE_LAYOUT_GENERAL};
      VkWriteDescriptorSet writes[5];
      for (uint32_t b = 0; b < 5; ++b) {
        writes[b] = {VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
        writes[b].dstBinding = b;
        writes[b].descriptorCount = 1;
        writes[b].descriptorType = b == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
        if (b == 2) writes[b].pImageInfo = &image;
        else writes[b].pBufferInfo = &buffers[b < 2 ? b : b - 1];
      }
      ctx.cmdPushDescriptorSet(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, d.layout, 0, 5, writes);
      const glm::uvec4 select(uint32_t(i), 0u, 0u, 0u);
      vkCmdPushConstants(cmd, d.layout, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof select, &select);
      vkCmdDispatch(cmd, (texels.width + 15) / 16, (texels.height + 63) / 64, 1);  // 16 x 64 texels a workgroup
    }
    for (int k : which)
      imageBarrier(cmd, images.images[size_t(k)].image, all, VK_IMAGE_LAYOUT_GENERAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                   VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  });
  for (size_t i = 0; i < which.size(); ++i) {
    const ViewDef& view = views[size_t(which[i])];
    for (uint32_t k = 0; k < params[i].encoding.w; ++k) out[size_t(which[i])].push_back(statsOf(slots[i * kSlotsPerView + k], view.integer));
  }
  return out;
}

}  // namespace gb
