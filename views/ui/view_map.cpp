// View mapping pipelines (view_map.frag variants) and the range reduction (view_range.comp).
#include "views/ui/view_map.h"

#include <algorithm>
#include <cstring>

#include "renderer/gpu/pipelines.h"
#include "renderer/vk/check.h"

namespace gb {

static constexpr uint32_t kMaxRanges = 64;

void initViewMapper(ViewMapper& m, Renderer& r) {
  GpuContext& ctx = *r.ctx;
  const VkShaderStageFlags stages = VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT;
  m.setLayout = createSetLayout(ctx,
                                {{0, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr},
                                 {1, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr},
                                 {2, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr}},
                                VK_DESCRIPTOR_SET_LAYOUT_CREATE_PUSH_DESCRIPTOR_BIT_KHR, "set1.view_map");
  VkDescriptorSetLayout sets[] = {r.sceneSetLayout, m.setLayout};
  VkPushConstantRange push{stages, 0, sizeof(gpu::ViewParams)};
  VkPipelineLayoutCreateInfo pci{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  pci.setLayoutCount = 2;
  pci.pSetLayouts = sets;
  pci.pushConstantRangeCount = 1;
  pci.pPushConstantRanges = &push;
  VK_CHECK(vkCreatePipelineLayout(ctx.device, &pci, nullptr, &m.layout));
  m.results = createBuffer(ctx, kMaxRanges * sizeof(gpu::RangeResult), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                           MemoryUse::Readback);
}

void destroyViewMapper(ViewMapper& m, Renderer& r) {
  if (!r.ctx || !m.layout) return;
  GpuContext& ctx = *r.ctx;
  vkDeviceWaitIdle(ctx.device);
  for (auto& [k, p] : m.pipelines) vkDestroyPipeline(ctx.device, p, nullptr);
  vkDestroyPipelineLayout(ctx.device, m.layout, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, m.setLayout, nullptr);
  destroyBuffer(ctx, m.results);
  m = ViewMapper{};
}

float floatFromOrdered(uint32_t o) {
  uint32_t bits = (o & 0x80000000u) ? (o & 0x7FFFFFFFu) : ~o;
  float f;
  std::memcpy(&f, &bits, 4);
  return f;
}

static bool isUintSource(const Renderer& r, const ViewSource& s) {
  return s.stencil || r.targets[size_t(s.target)].image.desc.format == VK_FORMAT_R32_UINT;
}

static VkImageView sourceView(const Renderer& r, const ViewSource& s) {
  const Image& img = r.targets[size_t(s.target)].image;
  if (s.stencil) {
    GB_ASSERT(img.stencilView);
    return img.stencilView;
  }
  return isDepthFormat(img.desc.format) ? img.depthView : img.view;
}

ViewImage targetImage(const Renderer& r, const ViewSource& s) {
  const GraphTarget& t = r.targets[size_t(s.target)];
  if (!t.image.image) return {};
  return {sourceView(r, s), t.layout, isUintSource(r, s)};
}

std::optional<ViewSource> nativeSource(const Layout& layout, const ViewDef& view, ViewGpuSource* gpu) {
  // A reference map (quantity -1: the viewer's error maps) or a view of another layout: no target here.
  if (view.quantity < 0 || size_t(view.quantity) >= layout.quantities.size() || view.target >= layout.targets.size())
    return std::nullopt;
  const LayoutTarget& lt = layout.targets[view.target];
  Target t;
  if (!parseTarget(lt.name, t)) return std::nullopt;
  const Quantity& q = layout.quantities[size_t(view.quantity)];
  ViewSource s{t, q.kind == QuantityKind::Stencil && lt.format.depth};
  if (gpu) {
    *gpu = ViewGpuSource{};
    gpu->decoded = false;
    gpu->nativeNormal = q.kind == QuantityKind::Normal;
    // The stencil aspect is an image of its own (channel 0); an encoded normal decodes to x, y, z.
    if (s.stencil || gpu->nativeNormal)
      gpu->channelOf = {0, 1, 2, 3};
    else
      gpu->channelOf.assign(q.channels.begin(), q.channels.end());
    gpu->background = view.background;
  }
  return s;
}

void ensureViewImage(GpuContext& ctx, Image& image, bool integer, uint32_t width, uint32_t height, const std::string& name) {
  const VkFormat format = integer ? VK_FORMAT_R32_UINT : VK_FORMAT_R32G32B32A32_SFLOAT;
  if (image.image && image.desc.format == format && image.desc.width == width && image.desc.height == height) return;
  if (image.image) destroyImage(ctx, image);
  ImageDesc d;
  d.format = format;
  d.width = width;
  d.height = height;
  d.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
            (integer ? VK_IMAGE_USAGE_STORAGE_BIT : 0);
  if (!integer) d.clearFormat = VK_FORMAT_R32G32B32A32_UINT;
  const std::string label = "view " + name;  // RenderDoc / Nsight name it
  d.name = label.c_str();
  image = createImage(ctx, d);
}

// A stream shows a new frame several times a second: the images of the views that keep their size
// are written again in place, through one staging buffer kept between frames, in one submission.
void uploadViewImages(ViewImages& out, GpuContext& ctx, const std::vector<CpuImage>& decoded, const std::vector<bool>& leave) {
  if (!out.images.empty()) vkDeviceWaitIdle(ctx.device);  // the views are sampled by frames in flight
  out.images.resize(std::max(out.images.size(), decoded.size()));
  VkDeviceSize bytes = 0;
  for (size_t i = 0; i < out.images.size(); ++i) {
    if (i < leave.size() && leave[i]) continue;
    const CpuImage* img = i < decoded.size() && !decoded[i].empty() ? &decoded[i] : nullptr;
    Image& gi = out.images[i];
    if (!img) {
      if (gi.image) destroyImage(ctx, gi);
      continue;
    }
    bytes += (img->data.size() + 15) / 16 * 16;
    ensureViewImage(ctx, gi, img->type == PixelType::U32, img->width, img->height, img->name);
  }
  out.images.resize(decoded.size());
  if (bytes == 0) return;
  if (out.staging.size < bytes) {
    destroyBuffer(ctx, out.staging);
    out.staging = createBuffer(ctx, bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload, "view staging");
  }
  std::vector<VkDeviceSize> offsets(decoded.size());
  VkDeviceSize at = 0;
  for (size_t i = 0; i < decoded.size(); ++i) {
    if (decoded[i].empty()) continue;
    offsets[i] = at;
    std::memcpy(static_cast<uint8_t*>(out.staging.mapped) + at, decoded[i].data.data(), decoded[i].data.size());
    at += (decoded[i].data.size() + 15) / 16 * 16;
  }
  submitOnce(ctx, [&](VkCommandBuffer cmd) {
    const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    for (size_t i = 0; i < decoded.size(); ++i) {
      if (decoded[i].empty()) continue;
      const Image& gi = out.images[i];
      // Every texel is written: what the image held before does not matter (UNDEFINED).
      imageBarrier(cmd, gi.image, all, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_PIPELINE_STAGE_2_NONE,
                   0, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
      VkBufferImageCopy copy{};
      copy.bufferOffset = offsets[i];
      copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
      copy.imageExtent = {decoded[i].width, decoded[i].height, 1};
      vkCmdCopyBufferToImage(cmd, out.staging.buffer, gi.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &copy);
      imageBarrier(cmd, gi.image, all, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                   VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
                   VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    }
  });
}

void destroyViewImages(ViewImages& images, GpuContext& ctx) {
  if (!images.images.empty() || images.staging.buffer) vkDeviceWaitIdle(ctx.device);
  for (Image& i : images.images) destroyImage(ctx, i);
  images.images.clear();
  destroyBuffer(ctx, images.staging);
}

ViewImage viewImageOf(const ViewImages& images, size_t view) {
  if (view >= images.images.size() || !images.images[view].image) return {};
  const Image& i = images.images[view];
  return {i.view, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, i.desc.format == VK_FORMAT_R32_UINT};
}

static void pushImages(Renderer& r, VkCommandBuffer cmd, VkPipelineBindPoint bindPoint, VkPipelineLayout layout,
                       std::initializer_list<std::pair<uint32_t, VkDescriptorImageInfo>> images, const Buffer* results) {
  std::vector<VkDescriptorImageInfo> infos;
  infos.reserve(images.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (auto& [binding, info] : images) {
    infos.push_back(info);
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    w.pImageInfo = &infos.back();
    writes.push_back(w);
  }
  VkDescriptorBufferInfo bufferInfo{results ? results->buffer : VK_NULL_HANDLE, 0, VK_WHOLE_SIZE};
  if (results) {
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = 2;
    w.descriptorCount = 1;
    w.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    w.pBufferInfo = &bufferInfo;
    writes.push_back(w);
  }
  vkCmdBindDescriptorSets(cmd, bindPoint, layout, gpu::kSetScene, 1, &frameSlot(r).sceneSet, 0, nullptr);
  r.ctx->cmdPushDescriptorSet(cmd, bindPoint, layout, gpu::kSetPass, uint32_t(writes.size()), writes.data());
}

std::vector<RangeStats> computeRanges(ViewMapper& m, Renderer& r, const std::vector<RangeRequest>& requests,
                                      const std::vector<Target>& handOff) {
  std::vector<RangeStats> out(requests.size());
  if (requests.empty()) return out;
  GB_ASSERT(requests.size() <= kMaxRanges);
  auto* slots = static_cast<gpu::RangeResult*>(m.results.mapped);
  for (size_t i = 0; i < requests.size(); ++i) {
    slots[i].minMax = glm::uvec4(0xFFFFFFFFu, 0u, 0u, 0u);
    slots[i].counts = glm::uvec4(0u);
  }
  std::vector<Use> uses;
  for (const RangeRequest& q : requests)
    if (std::none_of(uses.begin(), uses.end(), [&](const Use& u) { return u.target == q.source.target; }))
      uses.push_back({q.source.target, Access::SampledCompute});
  runAfterFrame(
      r,
      [&](FrameGraph& g) {
        g.addPass("view_ranges", uses, [&](PassContext& pc) {
          for (size_t i = 0; i < requests.size(); ++i) {
            const RangeRequest& q = requests[i];
            bool uintSource = isUintSource(r, q.source);
            const Shader shader = uintSource ? Shader::view_range_uint_comp : Shader::view_range_comp;
            std::vector<SpecConstant> spec = commonSpec(r);
            VkPipeline& p = m.pipelines[{shader, VK_NULL_HANDLE, specValues(spec)}];
            if (!p) p = createComputePipeline(*r.ctx, shader, spec, m.layout);
            vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, p);
            pushImages(r, pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, m.layout,
                       {{0u, {r.samplerPoint, sourceView(r, q.source), pc.layouts[size_t(q.source.target)]}}},
                       &m.results);
            gpu::ViewParams params{};  // RangeParams is the first 16 bytes of the push range
            gpu::RangeParams rp{};
            uint32_t background = 0;
            std::memcpy(&background, &q.background, 4);
            rp.select = glm::uvec4(q.channel, q.predicate, uint32_t(i), background);
            std::memcpy(&params, &rp, sizeof(rp));
            vkCmdPushConstants(pc.cmd, m.layout, VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, 0,
                               sizeof(params), &params);
            const ImageDesc& d = r.targets[size_t(q.source.target)].image.desc;
            vkCmdDispatch(pc.cmd, (d.width + 15) / 16, (d.height + 15) / 16, 1);
          }
          hostReadBarrier(pc.cmd, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
        });
      },
      handOff);
  for (size_t i = 0; i < requests.size(); ++i) {
    const gpu::RangeResult& s = slots[i];
    RangeStats& o = out[i];
    o.count = s.minMax.z;
    o.nan = s.minMax.w;
    o.inf = s.counts.x;
    o.negative = s.counts.y;
    if (o.count) {
      o.lo = floatFromOrdered(s.minMax.x);
      o.hi = floatFromOrdered(s.minMax.y);
    }
  }
  return out;
}

void drawView(ViewMapper& m, Renderer& r, VkCommandBuffer cmd, VkRenderPass renderPass, VkFormat attachmentFormat,
              const ViewImage& source, const gpu::ViewParams& params, VkRect2D viewport, VkRect2D scissor, const ViewImage* b) {
  const bool uintSource = source.uint;
  const bool diff = params.mode.x == gpu::kViewMapDiff;
  GB_ASSERT(source.valid() && (!diff || (b && b->valid())));
  const bool mark = (params.mode.z & gpu::kViewFlagMark) && !uintSource && !diff;
  const bool srgbOut = attachmentFormat == VK_FORMAT_B8G8R8A8_SRGB || attachmentFormat == VK_FORMAT_R8G8B8A8_SRGB;
  const Shader shader = diff ? (uintSource ? Shader::view_map_diff_uint_frag : Shader::view_map_diff_frag)
                        : uintSource ? Shader::view_map_uint_frag
                        : mark       ? Shader::view_map_mark_frag
                                     : Shader::view_map_frag;
  std::vector<SpecConstant> spec = commonSpec(r);
  spec.push_back({gpu::kSpecOutputSrgb, srgbOut ? 1u : 0u});
  spec.push_back({gpu::kSpecViewMapping, params.mode.x});
  VkPipeline& p = m.pipelines[{shader, renderPass, specValues(spec)}];
  if (!p) {
    GraphicsPipelineDesc d;
    d.vertexShader = Shader::view_map_vert;
    d.fragmentShader = shader;
    d.spec = spec;
    d.colorBlend = {BlendState{}};
    d.renderPass = renderPass;
    d.layout = m.layout;
    p = createGraphicsPipeline(*r.ctx, d);
  }
  vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, p);
  if (diff) {
    pushImages(r, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.layout,
               {{0u, {r.samplerPoint, source.view, source.layout}}, {1u, {r.samplerPoint, b->view, b->layout}}}, nullptr);
  } else if (mark) {
    const GraphTarget& depth = r.targets[size_t(Target::Depth)];
    pushImages(r, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.layout,
               {{0u, {r.samplerPoint, source.view, source.layout}}, {1u, {r.samplerPoint, depth.image.view, depth.layout}}},
               nullptr);
  } else {
    pushImages(r, cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, m.layout, {{0u, {r.samplerPoint, source.view, source.layout}}}, nullptr);
  }
  vkCmdPushConstants(cmd, m.layout, VK_SHADER_STAGE_FRAGMENT_BIT | VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(params), &params);
  VkViewport vp{float(viewport.offset.x), float(viewport.offset.y), float(viewport.extent.width),
                float(viewport.extent.height), 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &vp);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
  vkCmdSetCullMode(cmd, VK_CULL_MODE_NONE);
  vkCmdSetFrontFace(cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
  vkCmdSetStencilReference(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);
  vkCmdDraw(cmd, 3, 1, 0, 0);
}

}  // namespace gb
