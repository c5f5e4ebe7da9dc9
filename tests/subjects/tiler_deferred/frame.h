// tiler_deferred's frame: the options, what both modes share (meshes, the uniform ring, set 0) and the
// interface each mode (subpass.cpp, msaa.cpp) implements: record one frame, describe and read its targets.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "scene.h"
#include "vk.h"

namespace td {

enum class mode_kind { subpass, msaa, compute };
inline const char* mode_name(mode_kind m) { return m == mode_kind::subpass ? "subpass" : m == mode_kind::msaa ? "msaa" : "compute"; }

struct options {
  mode_kind mode = mode_kind::subpass;
  uint32_t width = 320, height = 180, frames = 3;
  int64_t dump_frame = -1;  // -1: the last frame
  int64_t capture_frame = -1;  // under renderdoccmd: the frame RenderDoc captures (-1: none)
  bool transient = true;
  std::string dump;  // empty: no dump
};

// What frame.json says of one attachment (README.md, "Dump format").
struct target_info {
  std::string name, vk_format;
  uint32_t bytes_per_texel = 4;
  int render_pass = 0, subpass = 0, attachment = 0;
  int color = -1;  // -1: depth (null in frame.json)
  uint32_t samples = 1;
  std::vector<std::string> files;
  bool store = true, transient = false;
  std::vector<int> input_of_subpass;
  std::string debug_name;  // VK_EXT_debug_utils name ("" : none; only the compute mode names images)
};

// The resources both modes use. The uniform buffer holds two 512-byte slots (frame k uses slot k % 2);
// set 0 binds it as UNIFORM_BUFFER_DYNAMIC with the slot's offset as the dynamic offset.
struct shared_gpu {
  buffer vertices, indices, uniforms;
  uint32_t slot_bytes = 0;
  VkDescriptorSetLayout frame_layout = VK_NULL_HANDLE;
  VkDescriptorPool pool = VK_NULL_HANDLE;
  VkDescriptorSet frame_set = VK_NULL_HANDLE;
  VkPipelineLayout geometry_layout = VK_NULL_HANDLE;  // set 0 + object_push (vertex + fragment)
  VkShaderModule geometry_vert = VK_NULL_HANDLE, fullscreen_vert = VK_NULL_HANDLE;
};
shared_gpu make_shared(const gpu& g, const scene& s);
void drop_shared(const gpu& g, shared_gpu& sh);

struct frame_input {
  uint32_t frame = 0;
  uint32_t uniform_offset = 0;  // dynamic offset of this frame's slot
  const scene* objects = nullptr;
  bool dump = false;  // record the read-back of this frame
};

// Binds the geometry pipeline's set 0, the meshes, and draws every object with its push constants.
void draw_objects(VkCommandBuffer cmd, const shared_gpu& sh, VkPipeline pipeline, const frame_input& in);
void bind_frame_set(VkCommandBuffer cmd, VkPipelineLayout layout, const shared_gpu& sh, const frame_input& in);

class mode_renderer {
 public:
  virtual ~mode_renderer() = default;
  virtual void record(VkCommandBuffer cmd, const frame_input& in) = 0;
  virtual std::vector<target_info> targets() const = 0;
  // After the dumped frame's fence: each file name with its bytes.
  virtual std::vector<std::pair<std::string, std::vector<uint8_t>>> dumped_files() const = 0;
};

std::unique_ptr<mode_renderer> make_subpass_renderer(const gpu& g, const shared_gpu& sh, const options& o);
std::unique_ptr<mode_renderer> make_msaa_renderer(const gpu& g, const shared_gpu& sh, const options& o);
std::unique_ptr<mode_renderer> make_compute_renderer(const gpu& g, const shared_gpu& sh, const options& o);

// Image memory barrier on one whole image.
VkImageMemoryBarrier image_barrier(const image& i, VkAccessFlags src, VkAccessFlags dst, VkImageLayout from,
                                   VkImageLayout to);
VkAttachmentDescription attachment(VkFormat format, VkSampleCountFlagBits samples, VkAttachmentLoadOp load,
                                   VkAttachmentStoreOp store, VkImageLayout final_layout);
VkFramebuffer make_framebuffer(const gpu& g, VkRenderPass pass, const std::vector<VkImageView>& views,
                               uint32_t width, uint32_t height);

VkDescriptorSet allocate_set(const gpu& g, VkDescriptorPool pool, VkDescriptorSetLayout layout);
// The msaa and compute modes' render pass 1: lit (R16G16B16A16_SFLOAT, DONT_CARE / STORE, final
// TRANSFER_SRC), and its target_info.
VkRenderPass make_lit_pass(const gpu& g);
target_info lit_target();
// Render pass 1 of those modes: a full-screen triangle of `pipeline` with set 0 and the G-buffer's
// images at set 1 (`images`).
void draw_lit(VkCommandBuffer cmd, VkRenderPass pass, VkFramebuffer framebuffer, VkPipeline pipeline, VkPipelineLayout layout,
              VkDescriptorSet images, const shared_gpu& sh, const frame_input& in, uint32_t width, uint32_t height);
// Nearest filtering, clamped: the lighting passes' texelFetch-like reads.
VkSampler make_nearest_sampler(const gpu& g);
// A render pass of one subpass (msaa mode's two passes).
VkRenderPass make_pass(const gpu& g, const std::vector<VkAttachmentDescription>& attachments,
                       const VkSubpassDescription& subpass, const std::vector<VkSubpassDependency>& deps);

}  // namespace td
