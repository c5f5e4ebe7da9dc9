// `--dump DIR` (see dump.h): the read-back and the files. Rows top to bottom, texels tightly packed,
// exactly the bytes vkCmdCopyImageToBuffer wrote (for D32_SFLOAT: the depth aspect, 4 bytes a texel).
#include "dump.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace fd {

namespace {

namespace fs = std::filesystem;

struct target_meta {
  const char* name;
  const char* vk_format;
  int render_pass, attachment;
  std::vector<float> clear;
};

// What README.md documents per target: RenderDoc's render-pass ordinal (1-based, in frame order)
// and the attachment index inside that render pass.
const target_meta& meta(target_id t) {
  static const target_meta table[t_count] = {
      {"position", "VK_FORMAT_R32G32B32A32_SFLOAT", 1, 0, {0, 0, 0, 1}},
      {"normal", "VK_FORMAT_R8G8B8A8_UNORM", 1, 1, {0, 0, 0, 0}},
      {"albedo", "VK_FORMAT_R8G8B8A8_SRGB", 1, 2, {0, 0, 0, 0}},
      {"depth", "VK_FORMAT_D32_SFLOAT", 1, 3, {1}},
      {"occlusion", "VK_FORMAT_R8_UNORM", 2, 0, {1}},
      {"hdr", "VK_FORMAT_R16G16B16A16_SFLOAT", 3, 0, {0, 0, 0, 0}},
      {"final", "VK_FORMAT_R8G8B8A8_UNORM", 4, 0, {0, 0, 0, 0}},
  };
  return table[t];
}

nlohmann::json matrix(const glm::mat4& m) {
  nlohmann::json j = nlohmann::json::array();
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) j.push_back(m[c][r]);
  return j;
}

nlohmann::json vec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

nlohmann::json uniform_layout() {
  const std::pair<const char*, int> members[] = {
      {"clip_from_view", 0},          {"view_from_world", 64}, {"clip_from_world", 128}, {"view_from_clip", 192},
      {"sun_direction_view", 256},    {"sun_color", 272},      {"ambient", 288},         {"depth_params", 304},
      {"light_position_view", 320},   {"light_color", 384},    {"viewport", 448},
  };
  nlohmann::json list = nlohmann::json::array();
  for (auto [name, offset] : members) {
    const bool mat = offset < 256;
    const bool array = offset == 320 || offset == 384;
    list.push_back({{"name", name}, {"offset", offset}, {"type", mat ? "mat4" : array ? "vec4[4]" : "vec4"},
                    {"bytes", mat ? 64 : array ? 64 : 16}});
  }
  return {{"set", 0}, {"binding", 0}, {"bytes", sizeof(frame_uniforms)}, {"file", "uniforms.bin"}, {"members", list}};
}

nlohmann::json camera_json(const renderer& r, const dump_info& info) {
  const camera& c = info.cam;
  nlohmann::json j = {
      {"producer", "foreign_deferred"},
      {"gpu", info.gpu},
      {"sub_pixel_precision_bits", info.sub_pixel_bits},
      {"frame", info.frame},
      {"frames", info.frames},
      {"width", r.width},
      {"height", r.height},
      {"projection", c.orthographic ? "orthographic" : "perspective"},
      {"near", k_near},
      {"far", k_far},
      {"eye_world", vec3(c.eye)},
      {"target_world", vec3(c.target)},
      {"up_world", vec3(c.up)},
      {"matrix_storage", "column_major"},
      {"clip_from_view", matrix(info.uniforms.clip_from_view)},
      {"view_from_world", matrix(info.uniforms.view_from_world)},
      {"clip_from_world", matrix(info.uniforms.clip_from_world)},
      {"view_from_clip", matrix(info.uniforms.view_from_clip)},
      {"uniform_buffer", uniform_layout()},
  };
  if (c.orthographic)
    j["half_height"] = k_ortho_half_height;
  else
    j["fovy_radians"] = k_fovy;
  nlohmann::json targets = nlohmann::json::array();
  for (int t = 0; t < t_count; ++t) {
    const target_meta& m = meta(target_id(t));
    targets.push_back({{"name", m.name}, {"file", describe(target_id(t)).file}, {"vk_format", m.vk_format},
                       {"bytes_per_texel", describe(target_id(t)).bytes_per_texel}, {"render_pass", m.render_pass},
                       {"attachment", m.attachment}, {"clear", m.clear}});
  }
  j["targets"] = targets;
  return j;
}

bool write_file(const fs::path& path, const void* data, size_t bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(static_cast<const char*>(data), std::streamsize(bytes));
  if (!f) {
    std::fprintf(stderr, "foreign_deferred: --dump: cannot write %s\n", path.c_str());
    return false;
  }
  return true;
}

}  // namespace

bool write_dump(const device_t& d, const renderer& r, const dump_info& info, const std::string& dir) {
  const size_t texels = size_t(r.width) * r.height;
  size_t offsets[t_count], total = 0;
  for (int t = 0; t < t_count; ++t) {
    offsets[t] = total;
    total += texels * describe(target_id(t)).bytes_per_texel;
  }
  buffer_t staging = create_host_buffer(d, total, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  VkCommandBuffer cmd = begin_commands(d);
  for (int t = 0; t < t_count; ++t) {
    const image_t& img = r.targets[t];
    const bool depth = t == t_depth;
    VkImageMemoryBarrier to_copy{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    to_copy.srcAccessMask = depth ? VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT : VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT;
    to_copy.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    to_copy.oldLayout = depth ? VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL : VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
    to_copy.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    to_copy.srcQueueFamilyIndex = to_copy.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    to_copy.image = img.image;
    to_copy.subresourceRange = {img.aspect, 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd,
                         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT |
                             VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &to_copy);
    VkBufferImageCopy region{};
    region.bufferOffset = offsets[t];
    region.imageSubresource = {img.aspect, 0, 0, 1};
    region.imageExtent = {r.width, r.height, 1};
    vkCmdCopyImageToBuffer(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, staging.buffer, 1, &region);
  }
  VkMemoryBarrier to_host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  to_host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  to_host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &to_host, 0, nullptr, 0,
                       nullptr);
  submit_and_wait(d, cmd);

  const fs::path final_dir(dir), partial(dir + ".partial");
  std::error_code ec;
  fs::remove_all(partial, ec);
  fs::create_directories(partial, ec);
  if (ec) {
    std::fprintf(stderr, "foreign_deferred: --dump: cannot create %s: %s\n", partial.c_str(), ec.message().c_str());
    destroy_buffer(d, staging);
    return false;
  }
  bool ok = true;
  const auto* bytes = static_cast<const uint8_t*>(staging.mapped);
  for (int t = 0; t < t_count && ok; ++t)
    ok = write_file(partial / describe(target_id(t)).file, bytes + offsets[t],
                    texels * describe(target_id(t)).bytes_per_texel);
  destroy_buffer(d, staging);
  ok = ok && write_file(partial / "uniforms.bin", &info.uniforms, sizeof(frame_uniforms));
  const std::string text = camera_json(r, info).dump(2) + "\n";
  ok = ok && write_file(partial / "camera.json", text.data(), text.size());
  if (!ok) return false;
  fs::remove_all(final_dir, ec);
  fs::rename(partial, final_dir, ec);
  if (ec) {
    std::fprintf(stderr, "foreign_deferred: --dump: cannot rename %s to %s: %s\n", partial.c_str(), dir.c_str(),
                 ec.message().c_str());
    return false;
  }
  return true;
}

}  // namespace fd
