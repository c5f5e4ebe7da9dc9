// tiler_deferred --mode msaa: render pass 0 fills a 4x G-buffer (albedo, normal, id, depth; STORE); render
// pass 1 lights each sample via texelFetch and averages into lit. --dump: a compute pass copies every sample.
#include "frame.h"
// The SPIR-V arrays (after frame.h, which brings <cstdint>).
#include "dump_samples_comp.h"
#include "gbuffer_msaa_frag.h"
#include "light_msaa_frag.h"

namespace td {

namespace {

enum : uint32_t { a_albedo = 0, a_normal = 1, a_id = 2, a_depth = 3, a_gcount = 4 };

struct plane {
  const char* name;
  const char* vk_name;
  VkFormat format;
};
const plane k_gplanes[a_gcount] = {
    {"albedo", "VK_FORMAT_R8G8B8A8_UNORM", VK_FORMAT_R8G8B8A8_UNORM},
    {"normal", "VK_FORMAT_A2B10G10R10_UNORM_PACK32", VK_FORMAT_A2B10G10R10_UNORM_PACK32},
    {"id", "VK_FORMAT_R32_UINT", VK_FORMAT_R32_UINT},
    {"depth", "VK_FORMAT_D32_SFLOAT", VK_FORMAT_D32_SFLOAT},
};

class msaa_renderer final : public mode_renderer {
 public:
  msaa_renderer(const gpu& g, const shared_gpu& sh, const options& o) : g_(g), sh_(sh), o_(o) {
    const VkSampleCountFlagBits four = VK_SAMPLE_COUNT_4_BIT;
    for (uint32_t a = 0; a < a_gcount; ++a)
      g_images_[a] = make_image(g, k_gplanes[a].format, o.width, o.height, four,
                                VK_IMAGE_USAGE_SAMPLED_BIT | (a == a_depth ? VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT
                                                                           : VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT),
                                false);
    lit_ = make_image(g, VK_FORMAT_R16G16B16A16_SFLOAT, o.width, o.height, VK_SAMPLE_COUNT_1_BIT,
                      VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT, false);
    make_passes();
    framebuffer_a_ = make_framebuffer(g, pass_a_, {g_images_[0].view, g_images_[1].view, g_images_[2].view,
                                                   g_images_[3].view}, o.width, o.height);
    framebuffer_b_ = make_framebuffer(g, pass_b_, {lit_.view}, o.width, o.height);
    sampler_ = make_nearest_sampler(g);
    make_pipelines();
    if (!o.dump.empty()) {
      plane_bytes_ = VkDeviceSize(o.width) * o.height * 4;
      samples_ = make_buffer(g, plane_bytes_ * a_gcount * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT);
      readback_ = make_buffer(g, VkDeviceSize(o.width) * o.height * 8, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
      make_dump_pipeline();
    }
  }

  ~msaa_renderer() override {
    if (samples_.handle) {
      drop_buffer(g_, samples_);
      drop_buffer(g_, readback_);
      vkDestroyPipeline(g_.device, dump_, nullptr);
      vkDestroyPipelineLayout(g_.device, dump_layout_, nullptr);
      vkDestroyDescriptorSetLayout(g_.device, dump_set_layout_, nullptr);
    }
    vkDestroyPipeline(g_.device, geometry_, nullptr);
    vkDestroyPipeline(g_.device, light_, nullptr);
    vkDestroyPipelineLayout(g_.device, light_layout_, nullptr);
    vkDestroyDescriptorSetLayout(g_.device, sampler_layout_, nullptr);
    vkDestroySampler(g_.device, sampler_, nullptr);
    vkDestroyFramebuffer(g_.device, framebuffer_a_, nullptr);
    vkDestroyFramebuffer(g_.device, framebuffer_b_, nullptr);
    vkDestroyRenderPass(g_.device, pass_a_, nullptr);
    vkDestroyRenderPass(g_.device, pass_b_, nullptr);
    for (image& i : g_images_) drop_image(g_, i);
    drop_image(g_, lit_);
  }

  void record(VkCommandBuffer cmd, const frame_input& in) override {
    VkClearValue clears[a_gcount]{};
    clears[a_id].color.uint32[0] = 0xF0000000u | in.frame;
    clears[a_depth].depthStencil = {0.0f, 0};
    VkRenderPassBeginInfo begin{};
    begin.sType = VK_STRUCTURE_TYPE_RENDER_PASS_BEGIN_INFO;
    begin.renderPass = pass_a_;
    begin.framebuffer = framebuffer_a_;
    begin.renderArea = {{0, 0}, {o_.width, o_.height}};
    begin.clearValueCount = a_gcount;
    begin.pClearValues = clears;
    vkCmdBeginRenderPass(cmd, &begin, VK_SUBPASS_CONTENTS_INLINE);
    draw_objects(cmd, sh_, geometry_, in);
    vkCmdEndRenderPass(cmd);
    draw_lit(cmd, pass_b_, framebuffer_b_, light_, light_layout_, sampler_set_, sh_, in, o_.width, o_.height);
    if (in.dump) record_dump(cmd);
  }

  std::vector<target_info> targets() const override {
    std::vector<target_info> list;
    const int colors[a_gcount] = {2, 0, 1, -1};  // colour 0 = normal, 1 = id, 2 = albedo
    for (uint32_t a = 0; a < a_gcount; ++a) {
      target_info t;
      t.name = k_gplanes[a].name;
      t.vk_format = k_gplanes[a].vk_name;
      t.attachment = int(a);
      t.color = colors[a];
      t.samples = 4;
      for (int s = 0; s < 4; ++s) t.files.push_back(t.name + ".s" + std::to_string(s) + ".bin");
      list.push_back(t);
    }
    list.push_back(lit_target());
    return list;
  }

  std::vector<std::pair<std::string, std::vector<uint8_t>>> dumped_files() const override {
    std::vector<std::pair<std::string, std::vector<uint8_t>>> files;
    const uint8_t* words = static_cast<const uint8_t*>(samples_.mapped);
    for (uint32_t a = 0; a < a_gcount; ++a)
      for (uint32_t s = 0; s < 4; ++s) {
        const uint8_t* at = words + (a * 4 + s) * plane_bytes_;
        files.push_back({std::string(k_gplanes[a].name) + ".s" + std::to_string(s) + ".bin",
                         std::vector<uint8_t>(at, at + plane_bytes_)});
      }
    const uint8_t* lit = static_cast<const uint8_t*>(readback_.mapped);
    files.push_back({"lit.bin", std::vector<uint8_t>(lit, lit + readback_.size)});
    return files;
  }

 private:
  void make_passes() {
    const VkSampleCountFlagBits four = VK_SAMPLE_COUNT_4_BIT;
    const VkAttachmentLoadOp clear = VK_ATTACHMENT_LOAD_OP_CLEAR;
    const VkAttachmentStoreOp store = VK_ATTACHMENT_STORE_OP_STORE;
    const VkImageLayout read = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, color = VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL;
    const VkPipelineStageFlags attach = VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT |
                                        VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                                        VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT;
    const VkPipelineStageFlags readers = VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT | VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT;
    const VkAccessFlags writes = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    const VkAccessFlags rw = writes | VK_ACCESS_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_READ_BIT;
    const VkAttachmentReference colors[3] = {{a_normal, color}, {a_id, color}, {a_albedo, color}};
    const VkAttachmentReference depth{a_depth, VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL};
    VkSubpassDescription sub{};
    sub.pipelineBindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS;
    sub.colorAttachmentCount = 3;
    sub.pColorAttachments = colors;
    sub.pDepthStencilAttachment = &depth;
    pass_a_ = make_pass(g_,
                        {attachment(k_gplanes[0].format, four, clear, store, read),
                         attachment(k_gplanes[1].format, four, clear, store, read),
                         attachment(k_gplanes[2].format, four, clear, store, read),
                         attachment(k_gplanes[3].format, four, clear, store, VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL)},
                        sub,
                        {{VK_SUBPASS_EXTERNAL, 0, attach | readers, attach, writes, rw, 0},
                         {0, VK_SUBPASS_EXTERNAL, attach, readers, writes, VK_ACCESS_SHADER_READ_BIT, 0}});
    pass_b_ = make_lit_pass(g_);
  }

  // Bindings 0..3 of `set`: the G-buffer images in `order`, through the nearest sampler.
  void write_images(VkDescriptorSet set, const uint32_t order[4]) {
    VkDescriptorImageInfo infos[4];
    VkWriteDescriptorSet writes[4];
    for (uint32_t i = 0; i < 4; ++i) {
      infos[i] = {sampler_, g_images_[order[i]].view,
                  order[i] == a_depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL
                                      : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL};
      writes[i] = VkWriteDescriptorSet{};
      writes[i].sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
      writes[i].dstSet = set;
      writes[i].dstBinding = i;
      writes[i].descriptorCount = 1;
      writes[i].descriptorType = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
      writes[i].pImageInfo = &infos[i];
    }
    vkUpdateDescriptorSets(g_.device, 4, writes, 0, nullptr);
  }

  void make_pipelines() {
    VkShaderModule gfrag = make_shader(g_, td_gbuffer_msaa_frag, sizeof(td_gbuffer_msaa_frag));
    VkShaderModule lfrag = make_shader(g_, td_light_msaa_frag, sizeof(td_light_msaa_frag));
    raster_desc d;
    d.vert = sh_.geometry_vert;
    d.frag = gfrag;
    d.layout = sh_.geometry_layout;
    d.pass = pass_a_;
    d.colors = 3;
    d.samples = VK_SAMPLE_COUNT_4_BIT;
    d.depth = true;
    d.vertices = true;
    d.width = o_.width;
    d.height = o_.height;
    geometry_ = make_raster_pipeline(g_, d);
    sampler_layout_ = make_set_layout(g_, std::vector<VkDescriptorType>(4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER),
                                      VK_SHADER_STAGE_FRAGMENT_BIT);
    light_layout_ = make_pipeline_layout(g_, {sh_.frame_layout, sampler_layout_}, 0, 0);
    d.vert = sh_.fullscreen_vert;
    d.frag = lfrag;
    d.layout = light_layout_;
    d.pass = pass_b_;
    d.colors = 1;
    d.samples = VK_SAMPLE_COUNT_1_BIT;
    d.depth = false;
    d.vertices = false;
    light_ = make_raster_pipeline(g_, d);
    vkDestroyShaderModule(g_.device, gfrag, nullptr);
    vkDestroyShaderModule(g_.device, lfrag, nullptr);
    sampler_set_ = allocate_set(g_, sh_.pool, sampler_layout_);
    const uint32_t order[4] = {a_normal, a_albedo, a_depth, a_id};  // light_msaa.frag's bindings
    write_images(sampler_set_, order);
  }

  void make_dump_pipeline() {
    std::vector<VkDescriptorType> types(4, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER);
    types.push_back(VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    dump_set_layout_ = make_set_layout(g_, types, VK_SHADER_STAGE_COMPUTE_BIT);
    dump_layout_ = make_pipeline_layout(g_, {dump_set_layout_}, 8, VK_SHADER_STAGE_COMPUTE_BIT);
    VkShaderModule comp = make_shader(g_, td_dump_samples_comp, sizeof(td_dump_samples_comp));
    dump_ = make_compute_pipeline(g_, comp, dump_layout_);
    vkDestroyShaderModule(g_.device, comp, nullptr);
    dump_set_ = allocate_set(g_, sh_.pool, dump_set_layout_);
    const uint32_t order[4] = {a_albedo, a_normal, a_id, a_depth};  // dump_samples.comp's bindings
    write_images(dump_set_, order);
    const VkDescriptorBufferInfo range{samples_.handle, 0, VK_WHOLE_SIZE};
    VkWriteDescriptorSet write{};
    write.sType = VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET;
    write.dstSet = dump_set_;
    write.dstBinding = 4;
    write.descriptorCount = 1;
    write.descriptorType = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    write.pBufferInfo = &range;
    vkUpdateDescriptorSets(g_.device, 1, &write, 0, nullptr);
  }

  // After render pass 1: every sample into samples_ (compute), lit into readback_ (copy), both to the host.
  void record_dump(VkCommandBuffer cmd) {
    vkCmdBindPipeline(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, dump_);
    vkCmdBindDescriptorSets(cmd, VK_PIPELINE_BIND_POINT_COMPUTE, dump_layout_, 0, 1, &dump_set_, 0, nullptr);
    const uint32_t size[2] = {o_.width, o_.height};
    vkCmdPushConstants(cmd, dump_layout_, VK_SHADER_STAGE_COMPUTE_BIT, 0, sizeof(size), size);
    vkCmdDispatch(cmd, (o_.width + 7) / 8, (o_.height + 7) / 8, 1);
    VkBufferImageCopy region{};
    region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.imageExtent = {o_.width, o_.height, 1};
    vkCmdCopyImageToBuffer(cmd, lit_.handle, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, readback_.handle, 1, &region);
    VkMemoryBarrier host{};
    host.sType = VK_STRUCTURE_TYPE_MEMORY_BARRIER;
    host.srcAccessMask = VK_ACCESS_SHADER_WRITE_BIT | VK_ACCESS_TRANSFER_WRITE_BIT;
    host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
    vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_TRANSFER_BIT,
                         VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host, 0, nullptr, 0, nullptr);
  }

  const gpu& g_;
  const shared_gpu& sh_;
  options o_;
  image g_images_[a_gcount], lit_;
  VkRenderPass pass_a_ = VK_NULL_HANDLE, pass_b_ = VK_NULL_HANDLE;
  VkFramebuffer framebuffer_a_ = VK_NULL_HANDLE, framebuffer_b_ = VK_NULL_HANDLE;
  VkSampler sampler_ = VK_NULL_HANDLE;
  VkPipeline geometry_ = VK_NULL_HANDLE, light_ = VK_NULL_HANDLE, dump_ = VK_NULL_HANDLE;
  VkDescriptorSetLayout sampler_layout_ = VK_NULL_HANDLE, dump_set_layout_ = VK_NULL_HANDLE;
  VkPipelineLayout light_layout_ = VK_NULL_HANDLE, dump_layout_ = VK_NULL_HANDLE;
  VkDescriptorSet sampler_set_ = VK_NULL_HANDLE, dump_set_ = VK_NULL_HANDLE;
  buffer samples_, readback_;
  VkDeviceSize plane_bytes_ = 0;
};

}  // namespace

std::unique_ptr<mode_renderer> make_msaa_renderer(const gpu& g, const shared_gpu& sh, const options& o) {
  return std::make_unique<msaa_renderer>(g, sh, o);
}

}  // namespace td
