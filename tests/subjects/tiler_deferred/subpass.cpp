// tiler_deferred --mode subpass: one render pass, two subpasses. Subpass 0 fills the G-buffer (albedo,
// normal, material, depth: DONT_CARE, transient) and id; subpass 1 lights from input attachments into lit.
#include <cstring>

#include "frame.h"
#include "gbuffer_subpass_frag.h"
#include "light_subpass_frag.h"

namespace td {

namespace {

// Render-pass attachment indices (README.md).
enum : uint32_t { a_albedo = 0, a_normal = 1, a_material = 2, a_depth = 3, a_lit = 4, a_id = 5, a_count = 6 };

struct plane {
  const char* name;
  const char* vk_name;
  VkFormat format;
  uint32_t bytes;
};
const plane k_planes[a_count] = {
    {"albedo", "VK_FORMAT_R8G8B8A8_UNORM", VK_FORMAT_R8G8B8A8_UNORM, 4},
    {"normal", "VK_FORMAT_A2B10G10R10_UNORM_PACK32", VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4},
    {"material", "VK_FORMAT_R16G16_SFLOAT", VK_FORMAT_R16G16_SFLOAT, 4},
    {"depth", "VK_FORMAT_D32_SFLOAT", VK_FORMAT_D32_SFLOAT, 4},
    {"lit", "VK_FORMAT_R16G16B16A16_SFLOAT", VK_FORMAT_R16G16B16A16_SFLOAT, 8},
    {"id", "VK_FORMAT_R32_UINT", VK_FORMAT_R32_UINT, 4},
};
// The dump buffer: lit first (8-byte texels at offset 0), then the others in attachment order.
const uint32_t k_dump_order[a_count] = {a_lit, a_albedo, a_normal, a_material, a_depth, a_id};

class subpass_renderer final : public mode_renderer {
 public:
  subpass_renderer(const gpu& g, const shared_gpu& sh, const options& o) : g_(g), sh_(sh), o_(o) {
    const bool dump = !o.dump.empty();
    // --dump keeps the G-buffer: STORE, TRANSFER_SRC, never TRANSIENT (the whole run, so every frame's
    // render pass is the same); the shaders and draws do not change.
    transient_ = o.transient && !dump;
    const VkImageUsageFlags gbuffer = VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT |
                                      (transient_ ? VK_IMAGE_USAGE_TRANSIENT_ATTACHMENT_BIT : 0) |
                                      (dump ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
    for (uint32_t a = 0; a < a_count; ++a) {
      VkImageUsageFlags usage = a == a_depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                             : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
      if (a <= a_depth) usage |= gbuffer;
      if (a == a_lit) usage |= VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      if (a == a_id) usage |= VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
      images_[a] = make_image(g, k_planes[a].format, o.width, o.height, VK_SAMPLE_COUNT_1_BIT, usage,
                              a <= a_depth && transient_);
    }
    make_pass(dump);
    std::vector<VkImageView> views;
    for (const image& i : images_) views.push_back(i.view);
    framebuffer_ = make_framebuffer(g, pass_, views, o.width, o.height);
    make_pipelines();
    if (dump) {
      VkDeviceSize bytes = 0;
      for (uint32_t a : k_dump_order) bytes += VkDeviceSize(o.width) * o.height * k_planes[a].bytes;
      readback_ = make_buffer(g, bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
    }
  }

  ~subpass_renderer() override {
    if (readback_.handle) drop_buffer(g_, readback_);
    vkDestroyPipeline(g_.device, geometry_, nullptr);
    vkDestroyPipeline(g_.device, light_, nullptr);
    vkDestroyPipelineLayout(g_.device, light_layout_, nullptr);
    vkDestroyDescriptorSetLayout(g_.device, input_layout_, nullptr);
    vkDestroyFramebuffer(g_.device, framebuffer_, nullptr);
    vkDestroyRenderPass(g_.device, pass_, nullptr);
    for (image& i : images_) drop_image(g_, i);
  }

  void record(VkCommandBuffer cmd, const frame_input& in) override {
    VkClearValue clears[a_count]{};
    clears[a_depth].depthStencil = {0.0f, 0};  // reverse-Z: nothing drawn is 0
    clears[a_id].color.uint32[0] = 0xF0000000u | in.frame;
    VkRenderPassBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    begin.renderPass = pass_;
    begin.framebuffer = framebuffer_;
    begin.renderArea = {{0, 0}, {o_.width, o_.height}};
    begin.clearValueCount = a_count;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    draw_objects(cmd, sh_, geometry_, in);
    vkCmdNextSubpass(cmd, VK_SUBPASS_CONTENTS_INLINE);
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, light_);
    bind_frame_set(cmd, light_layout_, sh_, in);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_GRAPHICS, light_layout_, 1, 1, &input_set_, 0, nullptr);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRenderPass(cmd);
    if (in.dump) record_readback(cmd);
  }

  std::vector<target_info> targets() const override {
    std::vector<target_info> list;
    for (uint32_t a = 0; a < a_count; ++a) {
      target_info t;
      t.name = k_planes[a].name;
      t.vk_format = k_planes[a].vk_name;
      t.bytes_per_texel = k_planes[a].bytes;
      t.render_pass = 0;
      t.subpass = a == a_lit ? 1 : 0;
      t.attachment = int(a);
      const int colors[a_count] = {2, 1, 3, -1, 0, 0};  // subpass 0: id, normal, albedo, material
      t.color = colors[a];
      t.files = {t.name + ".bin"};
      t.store = a >= a_lit || !o_.dump.empty();
      t.transient = a <= a_depth && transient_;
      if (a <= a_depth) t.input_of_subpass = {1};
      list.push_back(t);
    }
    return list;
  }

  std::vector<std::pair<std::string, std::vector<uint8_t>>> dumped_files() const override {
    std::vector<std::pair<std::string, std::vector<uint8_t>>> files;
    const uint8_t* at = static_cast<const uint8_t*>(readback_.mapped);
    for (uint32_t a : k_dump_order) {
      const size_t bytes = size_t(o_.width) * o_.height * k_planes[a].bytes;
      files.push_back({std::string(k_planes[a].name) + ".bin", std::vector<uint8_t>(at, at + bytes)});
      at += bytes;
    }
    return files;
  }

 private:
  void make_pass(bool dump) {
    const VkAttachmentStoreOp gstore = dump ? VK_ATTACHMENT_STORE_OP_STORE : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    const VkSampleCountFlagBits one = VK_SAMPLE_COUNT_1_BIT;
    const VkAttachmentLoadOp clear = VK_ATTACHMENT_LOAD_OP_CLEAR;
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    const VkAttachmentDescription attachments[a_count] = {
        attachment(k_planes[a_albedo].format, one, clear, gstore, read),
        attachment(k_planes[a_normal].format, one, clear, gstore, read),
        attachment(k_planes[a_material].format, one, clear, gstore, read),
        attachment(k_planes[a_depth].format, one, clear, gstore, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL),
        attachment(k_planes[a_lit].format, one, VK_ATTACHMENT_LOAD_OP_DONT_CARE, VK_ATTACHMENT_STORE_OP_STORE,
                   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL),
        attachment(k_planes[a_id].format, one, clear, VK_ATTACHMENT_STORE_OP_STORE, read),
    };
    const VkImageLayout color = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    const VkAttachmentReference gcolors[4] = {{a_id, color}, {a_normal, color}, {a_albedo, color}, {a_material, color}};
    const VkAttachmentReference gdepth{a_depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    const VkAttachmentReference inputs[4] = {
        {a_normal, read}, {a_albedo, read}, {a_material, read}, {a_depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL}};
    const VkAttachmentReference lit{a_lit, color};
    const uint32_t preserve = a_id;
    VkSubpassDescription subpasses[2]{};
    subpasses[0].pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpasses[0].colorAttachmentCount = 4;
    subpasses[0].pColorAttachments = gcolors;
    subpasses[0].pDepthStencilAttachment = &gdepth;
    subpasses[1].pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    subpasses[1].inputAttachmentCount = 4;
    subpasses[1].pInputAttachments = inputs;
    subpasses[1].colorAttachmentCount = 1;
    subpasses[1].pColorAttachments = &lit;
    subpasses[1].preserveAttachmentCount = 1;
    subpasses[1].pPreserveAttachments = &preserve;
    const VkPipelineStageFlags attach = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                        VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    const VkAccessFlags writes = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    const VkAccessFlags attach_rw = writes | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT |
                                    VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    const VkSubpassDependency deps[4] = {
        // The previous frame's attachment use and read-back before this frame's clears.
        {VK_SUBPASS_EXTERNAL, 0, attach | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
         attach, writes, attach_rw, 0},
        // The G-buffer written in subpass 0, read as input attachments in subpass 1 (per region).
        {0, 1, attach, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, writes, VK_ACCESS_INPUT_ATTACHMENT_READ_BIT,
         VK_DEPENDENCY_BY_REGION_BIT},
        // id (subpass 0) and lit (subpass 1) before the read-back copies.
        {0, VK_SUBPASS_EXTERNAL, attach, VK_PIPELINE_STAGE_TRANSFER_BIT, writes, VK_ACCESS_TRANSFER_READ_BIT, 0},
        {1, VK_SUBPASS_EXTERNAL, attach | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT,
         writes, VK_ACCESS_TRANSFER_READ_BIT, 0},
    };
    VkRenderPassCreateInfo info{};
    info.sType = VK_STRUCTURE_TYPE_RENDER_PASS_CREATE_INFO;
    info.attachmentCount = a_count;
    info.pAttachments = attachments;
    info.subpassCount = 2;
    info.pSubpasses = subpasses;
    info.dependencyCount = 4;
    info.pDependencies = deps;
    TD_CHECK(vkCreateRenderPass(g_.device, &info, nullptr, &pass_));
  }

  void make_pipelines() {
    VkShaderModule gfrag = make_shader(g_, td_gbuffer_subpass_frag, sizeof(td_gbuffer_subpass_frag));
    VkShaderModule lfrag = make_shader(g_, td_light_subpass_frag, sizeof(td_light_subpass_frag));
    raster_desc d;
    d.vert = sh_.geometry_vert;
    d.frag = gfrag;
    d.layout = sh_.geometry_layout;
    d.pass = pass_;
    d.subpass = 0;
    d.colors = 4;
    d.depth = true;
    d.vertices = true;
    d.width = o_.width;
    d.height = o_.height;
    geometry_ = make_raster_pipeline(g_, d);
    input_layout_ = make_set_layout(g_, std::vector<VkDescriptorType>(4, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT),
                                    VK_SHADER_STAGE_FRAGMENT_BIT);
    light_layout_ = make_pipeline_layout(g_, {sh_.frame_layout, input_layout_}, 0, 0);
    d.vert = sh_.fullscreen_vert;
    d.frag = lfrag;
    d.layout = light_layout_;
    d.subpass = 1;
    d.colors = 1;
    d.depth = false;
    d.vertices = false;
    light_ = make_raster_pipeline(g_, d);
    vkDestroyShaderModule(g_.device, gfrag, nullptr);
    vkDestroyShaderModule(g_.device, lfrag, nullptr);
    input_set_ = allocate_set(g_, sh_.pool, input_layout_);
    const uint32_t order[4] = {a_normal, a_albedo, a_material, a_depth};  // input_attachment_index 0..3
    VkDescriptorImageInfo infos[4];
    VkWriteDescriptorSet writes[4];
    for (uint32_t i = 0; i < 4; ++i) {
      infos[i] = {VK_NULL_HANDLE, images_[order[i]].view,
                  order[i] == a_depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                      : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      writes[i] = VkWriteDescriptorSet{};
      writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
      writes[i].dstSet = input_set_;
      writes[i].dstBinding = i;
      writes[i].descriptorCount = 1;
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
      writes[i].pImageInfo = &infos[i];
    }
    vkUpdateDescriptorSets(g_.device, 4, writes, 0, nullptr);
  }

  // After the render pass: every attachment to TRANSFER_SRC, copied into readback_, made visible to the host.
  void record_readback(VkCommandBuffer cmd) {
    // The layout transitions are writes: their first scope holds the attachment writes themselves.
    std::vector<VkImageMemoryBarrier> to_copy;
    for (uint32_t a : {a_albedo, a_normal, a_material, a_id})
      to_copy.push_back(image_barrier(images_[a], VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                                      VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
    to_copy.push_back(image_barrier(images_[a_depth], VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
                                    VK_ACCESS_TRANSFER_READ_BIT, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL,
                                    VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL));
    const VkPipelineStageFlags written = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                         VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                         VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                                         VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT;
    vkCmdPipelineBarrier(cmd, written, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         uint32_t(to_copy.size()), to_copy.data());
    VkDeviceSize offset = 0;
    for (uint32_t a : k_dump_order) {
      VkBufferImageCopy region{};
      region.bufferOffset = offset;
      region.imageSubresource = {images_[a].aspect, 0, 0, 1};
      region.imageExtent = {o_.width, o_.height, 1};
      vkCmdCopyImageToBuffer(cmd, images_[a].handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle, 1,
                             &region);
      offset += VkDeviceSize(o_.width) * o_.height * k_planes[a].bytes;
    }
    VkBufferMemoryBarrier host{};
    host.sType = VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER;
    host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    host.srcQueueFamilyIndex = host.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    host.buffer = readback_.handle;
    host.size = VK_WHOLE_SIZE;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 0, nullptr, 1, &host, 0,
                         nullptr);
  }

  const gpu& g_;
  const shared_gpu& sh_;
  options o_;
  bool transient_ = false;
  image images_[a_count];
  VkRenderPass pass_ = VK_NULL_HANDLE;
  VkFramebuffer framebuffer_ = VK_NULL_HANDLE;
  VkPipeline geometry_ = VK_NULL_HANDLE, light_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout input_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout light_layout_ = VK_NULL_HANDLE;
  VkDescriptorSet input_set_ = VK_NULL_HANDLE;
  buffer readback_;
};

}  // namespace

std::unique_ptr<mode_renderer> make_subpass_renderer(const gpu& g, const shared_gpu& sh, const options& o) {
  return std::make_unique<subpass_renderer>(g, sh, o);
}

}  // namespace td
