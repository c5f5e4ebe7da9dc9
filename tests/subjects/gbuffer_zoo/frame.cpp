// See frame.h. Every pass clears all its attachments (loadOp CLEAR from UNDEFINED); one external
// dependency in and one out per render pass order the passes of a frame and successive frames.
#include "frame.h"

#include <cstring>

namespace zoo {

namespace {

constexpr VkPipelineStageFlags k_attachment_stages = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                                     VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                                     VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
constexpr VkAccessFlags k_attachment_writes =
    VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
constexpr VkAccessFlags k_attachment_access = k_attachment_writes | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                                              VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;

VkRenderPass make_render_pass(const Gpu& g, const ModeDesc& m, int p) {
  const Pass& pass = m.passes[size_t(p)];
  std::vector<VkAttachmentDescription> atts;
  std::vector<VkAttachmentReference> colours;
  VkAttachmentReference depth{VK_ATTACHMENT_UNUSED, VK_IMAGE_LAYOUT_UNDEFINED};
  for (size_t a = 0; a < pass.attachments.size(); ++a) {
    const Attachment& at = pass.attachments[a];
    VkAttachmentDescription d{};
    d.format = at.format;
    d.samples = VK_SAMPLE_COUNT_1_BIT;
    d.loadOp = VK_ATTACHMENT_LOAD_OP_CLEAR;
    d.storeOp = at.store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    d.stencilLoadOp = has_stencil(at.format) ? VK_ATTACHMENT_LOAD_OP_CLEAR : VK_ATTACHMENT_LOAD_OP_DONT_CARE;
    d.stencilStoreOp = at.stencil_store ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    d.initialLayout = VK_IMAGE_LAYOUT_UNDEFINED;
    d.finalLayout = final_layout(m, p, int(a));
    atts.push_back(d);
    if (is_depth(at.format))
      depth = {uint32_t(a), VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    else
      colours.push_back({uint32_t(a), VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL});
  }
  VkSubpassDescription sub{};
  sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
  sub.colorAttachmentCount = uint32_t(colours.size());
  sub.pColorAttachments = colours.data();
  sub.pDepthStencilAttachment = depth.attachment == VK_ATTACHMENT_UNUSED ? nullptr : &depth;
  VkSubpassDependency deps[2] = {};
  deps[0].srcSubpass = VK_SUBPASS_EXTERNAL;
  deps[0].dstSubpass = 0;
  deps[0].srcStageMask = k_attachment_stages | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  deps[0].dstStageMask = k_attachment_stages | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT;
  deps[0].srcAccessMask = k_attachment_writes;
  deps[0].dstAccessMask = k_attachment_access | VK_ACCESS_SHADER_READ_BIT;
  deps[1].srcSubpass = 0;
  deps[1].dstSubpass = VK_SUBPASS_EXTERNAL;
  deps[1].srcStageMask = k_attachment_stages;
  deps[1].dstStageMask = k_attachment_stages | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
  deps[1].srcAccessMask = k_attachment_writes;
  deps[1].dstAccessMask = k_attachment_access | VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT;
  VkRenderPassCreateInfo ci{VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO};
  ci.attachmentCount = uint32_t(atts.size());
  ci.pAttachments = atts.data();
  ci.subpassCount = 1;
  ci.pSubpasses = &sub;
  ci.dependencyCount = 2;
  ci.pDependencies = deps;
  VkRenderPass rp;
  ZOO_VK(vkCreateRenderPass(g.device, &ci, nullptr, &rp));
  return rp;
}

void make_set_layout(const Gpu& g, const Pass& pass, PassGpu& pg) {
  std::vector<VkDescriptorSetLayoutBinding> b;
  const VkShaderStageFlags stages = VK_SHADER_STAGE_VERTEX_BIT | VK_SHADER_STAGE_FRAGMENT_BIT;
  b.push_back({0, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stages, nullptr});
  b.push_back({1, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, 1, stages, nullptr});
  b.push_back({2, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 1, stages, nullptr});
  for (size_t i = 0; i < pass.samples.size(); ++i)
    b.push_back({uint32_t(3 + i), VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 1, stages, nullptr});
  VkDescriptorSetLayoutCreateInfo ci{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_LAYOUT_CREATE_INFO};
  ci.bindingCount = uint32_t(b.size());
  ci.pBindings = b.data();
  ZOO_VK(vkCreateDescriptorSetLayout(g.device, &ci, nullptr, &pg.set_layout));
  VkPipelineLayoutCreateInfo li{VK_STRUCTURE_TYPE_PIPELINE_LAYOUT_CREATE_INFO};
  li.setLayoutCount = 1;
  li.pSetLayouts = &pg.set_layout;
  ZOO_VK(vkCreatePipelineLayout(g.device, &li, nullptr, &pg.layout));
}

void write_set(const Gpu& g, const Renderer& r, const Pass& pass, PassGpu& pg) {
  VkDescriptorSetAllocateInfo ai{VK_STRUCTURE_TYPE_DESCRIPTOR_SET_ALLOCATE_INFO};
  ai.descriptorPool = r.pool;
  ai.descriptorSetCount = 1;
  ai.pSetLayouts = &pg.set_layout;
  ZOO_VK(vkAllocateDescriptorSets(g.device, &ai, &pg.set));
  const VkDescriptorBufferInfo bufs[3] = {
      {r.camera.buffer, 0, r.camera.size}, {r.objects.buffer, 0, r.objects.size}, {r.lights.buffer, 0, r.lights.size}};
  std::vector<VkDescriptorImageInfo> imgs;
  for (auto [p, a] : pass.samples) {
    const Image& img = r.passes[size_t(p)].images[size_t(a)];
    imgs.push_back({r.sampler, img.sample_view, final_layout(*r.desc, p, a)});
  }
  std::vector<VkWriteDescriptorSet> w;
  for (uint32_t i = 0; i < 3 + imgs.size(); ++i) {
    VkWriteDescriptorSet x{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    x.dstSet = pg.set;
    x.dstBinding = i;
    x.descriptorCount = 1;
    if (i < 3) {
      x.descriptorType = i == 1 ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
      x.pBufferInfo = &bufs[i];
    } else {
      x.descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      x.pImageInfo = &imgs[i - 3];
    }
    w.push_back(x);
  }
  vkUpdateDescriptorSets(g.device, uint32_t(w.size()), w.data(), 0, nullptr);
}

void make_pass(const Gpu& g, Renderer& r, int p) {
  const Pass& pass = r.desc->passes[size_t(p)];
  PassGpu& pg = r.passes[size_t(p)];
  std::vector<VkImageView> views;
  for (size_t a = 0; a < pass.attachments.size(); ++a) {
    const VkFormat f = pass.attachments[a].format;
    VkImageUsageFlags usage = VK_IMAGE_USAGE_TRANSFER_SRC_BIT | (sampled_later(*r.desc, p, int(a)) ? VK_IMAGE_USAGE_SAMPLED_BIT : 0);
    usage |= is_depth(f) ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
    pg.images.push_back(make_image(g, f, r.width, r.height, usage));
    views.push_back(pg.images.back().view);
  }
  pg.render_pass = make_render_pass(g, *r.desc, p);
  VkFramebufferCreateInfo fi{VK_STRUCTURE_TYPE_FRAMEBUFFER_CREATE_INFO};
  fi.renderPass = pg.render_pass;
  fi.attachmentCount = uint32_t(views.size());
  fi.pAttachments = views.data();
  fi.width = r.width, fi.height = r.height, fi.layers = 1;
  ZOO_VK(vkCreateFramebuffer(g.device, &fi, nullptr, &pg.framebuffer));
  make_set_layout(g, pass, pg);
  write_set(g, r, pass, pg);
  for (const Draw& d : pass.draws) pg.pipelines.push_back(make_pipeline(g, pass, d, pg.render_pass, pg.layout));
}

void make_shared(const Gpu& g, Renderer& r, Mode mode) {
  r.geometry = build_geometry();
  const size_t vb = r.geometry.vertices.size() * sizeof(Vertex), ib = r.geometry.indices.size() * sizeof(uint32_t);
  r.vertices = make_buffer(g, vb, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT);
  r.indices = make_buffer(g, ib, VK_BUFFER_USAGE_INDEX_BUFFER_BIT);
  std::memcpy(r.vertices.mapped, r.geometry.vertices.data(), vb);
  std::memcpy(r.indices.mapped, r.geometry.indices.data(), ib);
  r.camera = make_buffer(g, make_camera(mode, 0, r.width, r.height).block.size(), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  r.objects = make_buffer(g, scene_objects(0).size() * sizeof(ObjectGpu), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
  r.lights = make_buffer(g, sizeof(LightsGpu), VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  VkSamplerCreateInfo si{VK_STRUCTURE_TYPE_SAMPLER_CREATE_INFO};
  si.magFilter = si.minFilter = VK_FILTER_NEAREST;
  si.addressModeU = si.addressModeV = si.addressModeW = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  si.maxLod = 0;
  ZOO_VK(vkCreateSampler(g.device, &si, nullptr, &r.sampler));
  const uint32_t n = uint32_t(r.desc->passes.size());
  const VkDescriptorPoolSize sizes[3] = {{VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER, 2 * n},
                                         {VK_DESCRIPTOR_TYPE_STORAGE_BUFFER, n},
                                         {VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, 8 * n}};
  VkDescriptorPoolCreateInfo pi{VK_STRUCTURE_TYPE_DESCRIPTOR_POOL_CREATE_INFO};
  pi.maxSets = n;
  pi.poolSizeCount = 3;
  pi.pPoolSizes = sizes;
  ZOO_VK(vkCreateDescriptorPool(g.device, &pi, nullptr, &r.pool));
}

void draw_objects(const Renderer& r, const Draw& d, VkCommandBuffer cmd) {
  const std::vector<SceneObject> objects = scene_objects(0);
  for (size_t i = 0; i < objects.size(); ++i) {
    const SceneObject& o = objects[i];
    if (o.decal != (d.kind == DrawKind::decal)) continue;
    if (d.stencil != StencilUse::none) {
      const uint32_t ref = d.stencil == StencilUse::write_id ? uint32_t(i + 1) : o.decal ? k_stencil_floor : o.stencil;
      vkCmdSetStencilReference(cmd, VK_STENCIL_FACE_FRONT_AND_BACK, ref);
    }
    const MeshRange& m = r.geometry.meshes[o.mesh];
    vkCmdDrawIndexed(cmd, m.index_count, 1, m.first_index, m.vertex_offset, uint32_t(i));
  }
}

}  // namespace

bool sampled_later(const ModeDesc& m, int p, int a) {
  for (size_t q = size_t(p) + 1; q < m.passes.size(); ++q)
    for (auto [sp, sa] : m.passes[q].samples)
      if (sp == p && sa == a) return true;
  return false;
}

VkImageLayout final_layout(const ModeDesc& m, int p, int a) {
  const bool depth = is_depth(m.passes[size_t(p)].attachments[size_t(a)].format);
  if (sampled_later(m, p, a))
    return depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  return depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
}

Renderer make_renderer(const Gpu& g, Mode mode, uint32_t width, uint32_t height) {
  Renderer r;
  r.desc = &describe(mode);
  r.width = width, r.height = height;
  make_shared(g, r, mode);
  r.passes.resize(r.desc->passes.size());
  for (size_t p = 0; p < r.passes.size(); ++p) make_pass(g, r, int(p));
  return r;
}

void upload_frame(Renderer& r, const Camera& cam, uint32_t frame) {
  std::memcpy(r.camera.mapped, cam.block.data(), cam.block.size());
  const std::vector<ObjectGpu> objects = pack_objects(frame, cam.to_world, cam.row_major);
  std::memcpy(r.objects.mapped, objects.data(), objects.size() * sizeof(ObjectGpu));
  const LightsGpu lights = pack_lights(cam.to_world);
  std::memcpy(r.lights.mapped, &lights, sizeof lights);
}

void record_frame(const Renderer& r, VkCommandBuffer cmd) {
  for (size_t p = 0; p < r.passes.size(); ++p) {
    const Pass& pass = r.desc->passes[p];
    const PassGpu& pg = r.passes[p];
    std::vector<VkClearValue> clears;
    for (const Attachment& a : pass.attachments) clears.push_back(a.clear);
    VkRenderPassBeginInfo bi{VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO};
    bi.renderPass = pg.render_pass;
    bi.framebuffer = pg.framebuffer;
    bi.renderArea = {{0, 0}, {r.width, r.height}};
    bi.clearValueCount = uint32_t(clears.size());
    bi.pClearValues = clears.data();
    vkCmdBeginRenderPass(cmd, &bi, VK_SUBPASS_CONTENTS_INLINE);
    const float h = float(r.height);
    const VkViewport vp = pass.flip_viewport ? VkViewport{0, h, float(r.width), -h, 0, 1}
                                             : VkViewport{0, 0, float(r.width), h, 0, 1};
    const VkRect2D scissor{{0, 0}, {r.width, r.height}};
    vkCmdSetViewport(cmd, 0, 1, &vp);
    vkCmdSetScissor(cmd, 0, 1, &scissor);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pg.layout, 0, 1, &pg.set, 0, nullptr);
    const VkDeviceSize zero = 0;
    vkCmdBindVertexBuffers(cmd, 0, 1, &r.vertices.buffer, &zero);
    vkCmdBindIndexBuffer(cmd, r.indices.buffer, 0, VK_INDEX_TYPE_UINT32);
    for (size_t d = 0; d < pass.draws.size(); ++d) {
      const Draw& draw = pass.draws[d];
      vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, pg.pipelines[d]);
      if (draw.kind == DrawKind::fullscreen) {
        vkCmdDraw(cmd, 3, 1, 0, 0);
      } else if (draw.kind == DrawKind::markers) {
        const MeshRange& m = r.geometry.meshes[mesh_marker];
        vkCmdDrawIndexed(cmd, m.index_count, 4, m.first_index, m.vertex_offset, 0);
      } else {
        draw_objects(r, draw, cmd);
      }
    }
    vkCmdEndRenderPass(cmd);
  }
}

void free_renderer(const Gpu& g, Renderer& r) {
  for (PassGpu& pg : r.passes) {
    for (VkPipeline p : pg.pipelines) vkDestroyPipeline(g.device, p, nullptr);
    vkDestroyPipelineLayout(g.device, pg.layout, nullptr);
    vkDestroyDescriptorSetLayout(g.device, pg.set_layout, nullptr);
    vkDestroyFramebuffer(g.device, pg.framebuffer, nullptr);
    vkDestroyRenderPass(g.device, pg.render_pass, nullptr);
    for (Image& i : pg.images) free_image(g, i);
  }
  vkDestroyDescriptorPool(g.device, r.pool, nullptr);
  vkDestroySampler(g.device, r.sampler, nullptr);
  for (Buffer* b : {&r.vertices, &r.indices, &r.camera, &r.objects, &r.lights}) free_buffer(g, *b);
  r = Renderer{};
}

}  // namespace zoo
