// tiler_deferred --mode compute: a compute-deferred G-buffer. Render pass 0 rasterises raw targets (normal,
// id, albedo, depth); a compute dispatch writes the G-buffer's albedo and normal into storage images no
// render pass holds (bound with vkUpdateDescriptorSets + vkCmdBindDescriptorSets, named with
// VK_EXT_debug_utils: "tiler.albedo", "tiler.normal"); render pass 1 lights from them. --dump copies them.
#include "frame.h"
// The SPIR-V arrays (after frame.h, which brings <cstdint>).
#include "gbuffer_msaa_frag.h"
#include "light_compute_frag.h"
#include "resolve_compute_comp.h"

namespace td {

namespace {

enum : uint32_t { r_normal = 0, r_id = 1, r_albedo = 2, r_depth = 3, r_count = 4 };  // render pass 0's attachments
enum : uint32_t { s_albedo = 0, s_normal = 1, s_count = 2 };                       // the compute-written targets

struct plane {
  const char* name;
  const char* vk_name;
  VkFormat format;
  uint32_t bytes;
};
const plane k_raw[r_count] = {
    {"raw_normal", "VK_FORMAT_A2B10G10R10_UNORM_PACK32", VK_FORMAT_A2B10G10R10_UNORM_PACK32, 4},
    {"id", "VK_FORMAT_R32_UINT", VK_FORMAT_R32_UINT, 4},
    {"raw_albedo", "VK_FORMAT_R8G8B8A8_UNORM", VK_FORMAT_R8G8B8A8_UNORM, 4},
    {"depth", "VK_FORMAT_D32_SFLOAT", VK_FORMAT_D32_SFLOAT, 4},
};
const plane k_storage[s_count] = {
    {"albedo", "VK_FORMAT_R8G8B8A8_UNORM", VK_FORMAT_R8G8B8A8_UNORM, 4},
    {"normal", "VK_FORMAT_R16G16B16A16_SFLOAT", VK_FORMAT_R16G16B16A16_SFLOAT, 8},
};
const char* const k_debug_names[s_count] = {"tiler.albedo", "tiler.normal"};

VkBufferImageCopy whole(VkImageAspectFlags aspect, uint32_t w, uint32_t h, VkDeviceSize at) {
  VkBufferImageCopy r{};
  r.bufferOffset = at;
  r.imageSubresource = {aspect, 0, 0, 1};
  r.imageExtent = {w, h, 1};
  return r;
}

class compute_renderer final : public mode_renderer {
 public:
  compute_renderer(const gpu& g, const shared_gpu& sh, const options& o) : g_(g), sh_(sh), o_(o) {
    const VkImageUsageFlags read = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    for (uint32_t a = 0; a < r_count; ++a)
      raw_[a] = make_image(g, k_raw[a].format, o.width, o.height, VK_SAMPLE_COUNT_1_BIT,
                           read | (a == r_depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT),
                           false);
    for (uint32_t s = 0; s < s_count; ++s) {
      storage_[s] = make_image(g, k_storage[s].format, o.width, o.height, VK_SAMPLE_COUNT_1_BIT,
                               read | VK_IMAGE_USAGE_STORAGE_BIT, false);
      name_image(g, storage_[s].handle, k_debug_names[s]);
    }
    lit_ = make_image(g, VK_FORMAT_R16G16B16A16_SFLOAT, o.width, o.height, VK_SAMPLE_COUNT_1_BIT,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, false);
    make_passes();
    framebuffer_a_ = make_framebuffer(g, pass_a_, {raw_[0].view, raw_[1].view, raw_[2].view, raw_[3].view}, o.width, o.height);
    framebuffer_b_ = make_framebuffer(g, pass_b_, {lit_.view}, o.width, o.height);
    sampler_ = make_nearest_sampler(g);
    make_pipelines();
    if (!o.dump.empty()) readback_ = make_buffer(g, plane_at(files().size()), VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  }

  ~compute_renderer() override {
    if (readback_.handle) drop_buffer(g_, readback_);
    for (VkPipeline p : {geometry_, resolve_, light_}) vkDestroyPipeline(g_.device, p, nullptr);
    for (VkPipelineLayout l : {resolve_layout_, light_layout_}) vkDestroyPipelineLayout(g_.device, l, nullptr);
    for (VkDescriptorSetLayout l : {resolve_set_layout_, light_set_layout_}) vkDestroyDescriptorSetLayout(g_.device, l, nullptr);
    vkDestroySampler(g_.device, sampler_, nullptr);
    vkDestroyFramebuffer(g_.device, framebuffer_a_, nullptr);
    vkDestroyFramebuffer(g_.device, framebuffer_b_, nullptr);
    vkDestroyRenderPass(g_.device, pass_a_, nullptr);
    vkDestroyRenderPass(g_.device, pass_b_, nullptr);
    for (image& i : raw_) drop_image(g_, i);
    for (image& i : storage_) drop_image(g_, i);
    drop_image(g_, lit_);
  }

  void record(VkCommandBuffer cmd, const frame_input& in) override {
    // The storage targets' last contents are not needed: UNDEFINED -> GENERAL for the dispatch.
    VkImageMemoryBarrier to_general[s_count];
    for (uint32_t s = 0; s < s_count; ++s)
      to_general[s] = image_barrier(storage_[s], VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT,
                                    VK_ACCESS_SHADER_WRITE_BIT, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_GENERAL);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, 0, 0, nullptr, 0, nullptr, s_count, to_general);
    VkClearValue clears[r_count]{};
    clears[r_id].color.uint32[0] = 0xF0000000u | in.frame;
    clears[r_depth].depthStencil = {0.0f, 0};
    VkRenderPassBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    begin.renderPass = pass_a_;
    begin.framebuffer = framebuffer_a_;
    begin.renderArea = {{0, 0}, {o_.width, o_.height}};
    begin.clearValueCount = r_count;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    draw_objects(cmd, sh_, geometry_, in);
    vkCmdEndRenderPass(cmd);
    // The resolve: the G-buffer's albedo and normal written by compute.
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resolve_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, resolve_layout_, 0, 1, &resolve_set_, 0, nullptr);
    const uint32_t size[2] = {o_.width, o_.height};
    vkCmdPushConstants(cmd, resolve_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(size), size);
    vkCmdDispatch(cmd, (o_.width + 7) / 8, (o_.height + 7) / 8, 1);
    VkImageMemoryBarrier to_read[s_count];
    for (uint32_t s = 0; s < s_count; ++s)
      to_read[s] = image_barrier(storage_[s], VK_ACCESS_SHADER_WRITE_BIT, VK_ACCESS_SHADER_READ_BIT, VK_IMAGE_LAYOUT_GENERAL,
                                 VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, 0, 0, nullptr, 0,
                         nullptr, s_count, to_read);
    draw_lit(cmd, pass_b_, framebuffer_b_, light_, light_layout_, light_set_, sh_, in, o_.width, o_.height);
    if (in.dump) record_dump(cmd);
  }

  std::vector<target_info> targets() const override {
    std::vector<target_info> list;
    for (uint32_t s = 0; s < s_count; ++s) {
      target_info t;
      t.name = k_storage[s].name;
      t.vk_format = k_storage[s].vk_name;
      t.bytes_per_texel = k_storage[s].bytes;
      t.render_pass = t.attachment = -1;  // written by the resolve dispatch, by no render pass
      t.debug_name = k_debug_names[s];
      t.files = {t.name + ".bin"};
      list.push_back(t);
    }
    for (uint32_t a : {r_id, r_depth}) {
      target_info t;
      t.name = k_raw[a].name;
      t.vk_format = k_raw[a].vk_name;
      t.attachment = int(a);
      t.color = a == r_depth ? -1 : int(a);
      t.files = {t.name + ".bin"};
      list.push_back(t);
    }
    list.push_back(lit_target());
    return list;
  }

  std::vector<std::pair<std::string, std::vector<uint8_t>>> dumped_files() const override {
    std::vector<std::pair<std::string, std::vector<uint8_t>>> out;
    const uint8_t* bytes = static_cast<const uint8_t*>(readback_.mapped);
    const std::vector<std::pair<std::string, uint32_t>> list = files();
    for (size_t k = 0; k < list.size(); ++k)
      out.push_back({list[k].first + ".bin", std::vector<uint8_t>(bytes + plane_at(k), bytes + plane_at(k + 1))});
    return out;
  }

 private:
  // The dumped planes in readback_ order, each with its bytes per texel.
  std::vector<std::pair<std::string, uint32_t>> files() const {
    return {{"albedo", 4}, {"normal", 8}, {"id", 4}, {"depth", 4}, {"lit", 8}};
  }
  VkDeviceSize plane_at(size_t k) const {
    VkDeviceSize at = 0;
    const std::vector<std::pair<std::string, uint32_t>> list = files();
    for (size_t i = 0; i < k && i < list.size(); ++i) at += VkDeviceSize(o_.width) * o_.height * list[i].second;
    return at;
  }

  void make_passes() {
    const VkAttachmentLoadOp clear = VK_ATTACHMENT_LOAD_OP_CLEAR;
    const VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_STORE;
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, color = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    const VkPipelineStageFlags attach = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    const VkPipelineStageFlags readers = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT |
                                         VK_PIPELINE_STAGE_TRANSFER_BIT;
    const VkAccessFlags writes = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    const VkAccessFlags rw = writes | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    const VkAttachmentReference colors[3] = {{r_normal, color}, {r_id, color}, {r_albedo, color}};
    const VkAttachmentReference depth{r_depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 3;
    sub.pColorAttachments = colors;
    sub.pDepthStencilAttachment = &depth;
    const VkSampleCountFlagBits one = VK_SAMPLE_COUNT_1_BIT;
    pass_a_ = make_pass(g_,
                        {attachment(k_raw[0].format, one, clear, store, read), attachment(k_raw[1].format, one, clear, store, read),
                         attachment(k_raw[2].format, one, clear, store, read),
                         attachment(k_raw[3].format, one, clear, store, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)},
                        sub,
                        {{VK_SUBPASS_EXTERNAL, 0, attach | readers, attach, writes | VK_ACCESS_TRANSFER_READ_BIT, rw, 0},
                         {0, VK_SUBPASS_EXTERNAL, attach, readers, writes, VK_ACCESS_SHADER_READ_BIT | VK_ACCESS_TRANSFER_READ_BIT, 0}});
    pass_b_ = make_lit_pass(g_);
  }

  void write(VkDescriptorSet set, uint32_t binding, VkDescriptorType type, VkImageView view, VkImageLayout layout) {
    const VkDescriptorImageInfo info{type == VK_DESCRIPTOR_TYPE_STORAGE_IMAGE ? VK_NULL_HANDLE : sampler_, view, layout};
    VkWriteDescriptorSet w{};
    w.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    w.dstSet = set;
    w.dstBinding = binding;
    w.descriptorCount = 1;
    w.descriptorType = type;
    w.pImageInfo = &info;
    vkUpdateDescriptorSets(g_.device, 1, &w, 0, nullptr);
  }

  void make_pipelines() {
    VkShaderModule gfrag = make_shader(g_, td_gbuffer_msaa_frag, sizeof(td_gbuffer_msaa_frag));
    VkShaderModule lfrag = make_shader(g_, td_light_compute_frag, sizeof(td_light_compute_frag));
    VkShaderModule comp = make_shader(g_, td_resolve_compute_comp, sizeof(td_resolve_compute_comp));
    raster_desc d;
    d.vert = sh_.geometry_vert;
    d.frag = gfrag;
    d.layout = sh_.geometry_layout;
    d.pass = pass_a_;
    d.colors = 3;
    d.depth = true;
    d.vertices = true;
    d.width = o_.width;
    d.height = o_.height;
    geometry_ = make_raster_pipeline(g_, d);
    const VkDescriptorType sampled = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, storage = VK_DESCRIPTOR_TYPE_STORAGE_IMAGE;
    resolve_set_layout_ = make_set_layout(g_, {sampled, sampled, storage, storage}, VK_SHADER_STAGE_COMPUTE_BIT);
    resolve_layout_ = make_pipeline_layout(g_, {resolve_set_layout_}, 8, VK_SHADER_STAGE_COMPUTE_BIT);
    resolve_ = make_compute_pipeline(g_, comp, resolve_layout_);
    light_set_layout_ = make_set_layout(g_, std::vector<VkDescriptorType>(4, sampled), VK_SHADER_STAGE_FRAGMENT_BIT);
    light_layout_ = make_pipeline_layout(g_, {sh_.frame_layout, light_set_layout_}, 0, 0);
    d.vert = sh_.fullscreen_vert;
    d.frag = lfrag;
    d.layout = light_layout_;
    d.pass = pass_b_;
    d.colors = 1;
    d.depth = false;
    d.vertices = false;
    light_ = make_raster_pipeline(g_, d);
    for (VkShaderModule m : {gfrag, lfrag, comp}) vkDestroyShaderModule(g_.device, m, nullptr);
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    resolve_set_ = allocate_set(g_, sh_.pool, resolve_set_layout_);
    write(resolve_set_, 0, sampled, raw_[r_albedo].view, read);
    write(resolve_set_, 1, sampled, raw_[r_normal].view, read);
    write(resolve_set_, 2, storage, storage_[s_albedo].view, VK_IMAGE_LAYOUT_GENERAL);
    write(resolve_set_, 3, storage, storage_[s_normal].view, VK_IMAGE_LAYOUT_GENERAL);
    light_set_ = allocate_set(g_, sh_.pool, light_set_layout_);  // light_compute.frag's bindings
    write(light_set_, 0, sampled, storage_[s_normal].view, read);
    write(light_set_, 1, sampled, storage_[s_albedo].view, read);
    write(light_set_, 2, sampled, raw_[r_depth].view, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL);
    write(light_set_, 3, sampled, raw_[r_id].view, read);
  }

  // After render pass 1: the storage targets, id, depth and lit copied into readback_, then to the host.
  void record_dump(VkCommandBuffer cmd) {
    VkImageMemoryBarrier b[s_count + 2];
    for (uint32_t s = 0; s < s_count; ++s)
      b[s] = image_barrier(storage_[s], VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                           VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    b[s_count] = image_barrier(raw_[r_id], VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                               VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    b[s_count + 1] = image_barrier(raw_[r_depth], VK_ACCESS_SHADER_READ_BIT, VK_ACCESS_TRANSFER_READ_BIT,
                                   VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT, VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr,
                         s_count + 2, b);
    const uint32_t w = o_.width, h = o_.height;
    const VkImageAspectFlags colour = VK_IMAGE_ASPECT_COLOR_BIT;
    const VkImageLayout src = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    const std::pair<VkImage, VkImageAspectFlags> sources[] = {{storage_[s_albedo].handle, colour}, {storage_[s_normal].handle, colour},
                                                              {raw_[r_id].handle, colour}, {raw_[r_depth].handle, VK_IMAGE_ASPECT_DEPTH_BIT},
                                                              {lit_.handle, colour}};
    for (size_t k = 0; k < 5; ++k) {
      const VkBufferImageCopy region = whole(sources[k].second, w, h, plane_at(k));
      vkCmdCopyImageToBuffer(cmd, sources[k].first, src, readback_.handle, 1, &region);
    }
    VkImageMemoryBarrier back[2] = {
        image_barrier(raw_[r_id], VK_ACCESS_TRANSFER_READ_BIT, 0, src, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL),
        image_barrier(raw_[r_depth], VK_ACCESS_TRANSFER_READ_BIT, 0, src, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)};
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_TOP_OF_PIPE_BIT, 0, 0, nullptr, 0, nullptr, 2, back);
    VkMemoryBarrier host{};
    host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host, 0, nullptr, 0, nullptr);
  }

  const gpu& g_;
  const shared_gpu& sh_;
  options o_;
  image raw_[r_count], storage_[s_count], lit_;
  VkRenderPass pass_a_ = VK_NULL_HANDLE, pass_b_ = VK_NULL_HANDLE;
  VkFramebuffer framebuffer_a_ = VK_NULL_HANDLE, framebuffer_b_ = VK_NULL_HANDLE;
  VkSampler sampler_ = VK_NULL_HANDLE;
  VkPipeline geometry_ = VK_NULL_HANDLE, resolve_ = VK_NULL_HANDLE, light_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout resolve_set_layout_ = VK_NULL_HANDLE, light_set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout resolve_layout_ = VK_NULL_HANDLE, light_layout_ = VK_NULL_HANDLE;
  VkDescriptorSet resolve_set_ = VK_NULL_HANDLE, light_set_ = VK_NULL_HANDLE;
  buffer readback_;
};

}  // namespace

std::unique_ptr<mode_renderer> make_compute_renderer(const gpu& g, const shared_gpu& sh, const options& o) {
  return std::make_unique<compute_renderer>(g, sh, o);
}

}  // namespace td
