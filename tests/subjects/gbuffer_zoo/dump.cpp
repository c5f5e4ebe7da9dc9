// See dump.h. Read-back with vkCmdCopyImageToBuffer after the frames (outside any RenderDoc bracket).
// Depth/stencil files: the depth plane as copied (D16: 2 bytes, D32: float, D24: uint32 with depth in
// the low 24 bits, the unused top byte zeroed here), then one stencil byte a texel if stencil is stored.
#include "dump.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace zoo {

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

struct FormatInfo {
  VkFormat format;
  const char* name;
  uint32_t bytes;  // colour texel, or the depth plane's texel
};

const FormatInfo& info_of(VkFormat f) {
  static const FormatInfo table[] = {
      {VK_FORMAT_R16G16B16A16_SFLOAT, "VK_FORMAT_R16G16B16A16_SFLOAT", 8},
      {VK_FORMAT_R32G32B32A32_SFLOAT, "VK_FORMAT_R32G32B32A32_SFLOAT", 16},
      {VK_FORMAT_R8G8B8A8_UNORM, "VK_FORMAT_R8G8B8A8_UNORM", 4},
      {VK_FORMAT_R8G8B8A8_SRGB, "VK_FORMAT_R8G8B8A8_SRGB", 4},
      {VK_FORMAT_R8G8B8A8_SNORM, "VK_FORMAT_R8G8B8A8_SNORM", 4},
      {VK_FORMAT_B8G8R8A8_UNORM, "VK_FORMAT_B8G8R8A8_UNORM", 4},
      {VK_FORMAT_B8G8R8A8_SRGB, "VK_FORMAT_B8G8R8A8_SRGB", 4},
      {VK_FORMAT_A2B10G10R10_UNORM_PACK32, "VK_FORMAT_A2B10G10R10_UNORM_PACK32", 4},
      {VK_FORMAT_R16G16_SNORM, "VK_FORMAT_R16G16_SNORM", 4},
      {VK_FORMAT_R16G16_UNORM, "VK_FORMAT_R16G16_UNORM", 4},
      {VK_FORMAT_R8G8_UNORM, "VK_FORMAT_R8G8_UNORM", 2},
      {VK_FORMAT_R32_SFLOAT, "VK_FORMAT_R32_SFLOAT", 4},
      {VK_FORMAT_R8_UINT, "VK_FORMAT_R8_UINT", 1},
      {VK_FORMAT_D16_UNORM, "VK_FORMAT_D16_UNORM", 2},
      {VK_FORMAT_D32_SFLOAT, "VK_FORMAT_D32_SFLOAT", 4},
      {VK_FORMAT_D24_UNORM_S8_UINT, "VK_FORMAT_D24_UNORM_S8_UINT", 4},
      {VK_FORMAT_D32_SFLOAT_S8_UINT, "VK_FORMAT_D32_SFLOAT_S8_UINT", 4},
  };
  for (const FormatInfo& i : table)
    if (i.format == f) return i;
  std::fprintf(stderr, "gbuffer_zoo: dump: format %d missing from the table\n", int(f));
  std::exit(1);
}

struct Slot {  // one dumped attachment
  int pass, attachment;
  size_t offset, depth_bytes, stencil_bytes;  // stencil_bytes 0: no stencil plane in the file
};

std::vector<Slot> plan(const Renderer& r, size_t& total) {
  std::vector<Slot> slots;
  const size_t texels = size_t(r.width) * r.height;
  total = 0;
  for (size_t p = 0; p < r.desc->passes.size(); ++p)
    for (size_t a = 0; a < r.desc->passes[p].attachments.size(); ++a) {
      const Attachment& at = r.desc->passes[p].attachments[a];
      if (!at.store) continue;  // DONT_CARE: not dumped (a depth format's depth aspect decides)
      total = (total + 15) & ~size_t(15);  // copy offsets: a multiple of the texel size (16 at most), 4 for depth
      Slot s{int(p), int(a), total, texels * info_of(at.format).bytes, at.stencil_store ? texels : 0};
      total += s.depth_bytes + s.stencil_bytes;
      slots.push_back(s);
    }
  return slots;
}

void record_copies(const Renderer& r, const std::vector<Slot>& slots, VkBuffer dst, VkCommandBuffer cmd) {
  for (const Slot& s : slots) {
    const Image& img = r.passes[size_t(s.pass)].images[size_t(s.attachment)];
    VkImageMemoryBarrier b{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER};
    b.srcAccessMask = VK_ACCESS_COLOR_ATTACHMENT_WRITE_BIT | VK_ACCESS_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT;
    b.dstAccessMask = VK_ACCESS_TRANSFER_READ_BIT;
    b.oldLayout = final_layout(*r.desc, s.pass, s.attachment);
    b.newLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;
    b.srcQueueFamilyIndex = b.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
    b.image = img.image;
    b.subresourceRange = {all_aspects(img.format), 0, 1, 0, 1};
    vkCmdPipelineBarrier(cmd,
                         VK_PIPELINE_STAGE_COLOR_ATTACHMENT_OUTPUT_BIT | VK_PIPELINE_STAGE_EARLY_FRAGMENT_TESTS_BIT |
                             VK_PIPELINE_STAGE_LATE_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_FRAGMENT_SHADER_BIT,
                         VK_PIPELINE_STAGE_TRANSFER_BIT, 0, 0, nullptr, 0, nullptr, 1, &b);
    VkBufferImageCopy c{};
    c.bufferOffset = s.offset;
    c.imageSubresource = {is_depth(img.format) ? VkImageAspectFlags(VK_IMAGE_ASPECT_DEPTH_BIT)
                                               : VkImageAspectFlags(VK_IMAGE_ASPECT_COLOR_BIT),
                          0, 0, 1};
    c.imageExtent = {r.width, r.height, 1};
    vkCmdCopyImageToBuffer(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, 1, &c);
    if (s.stencil_bytes) {
      c.bufferOffset = s.offset + s.depth_bytes;
      c.imageSubresource.aspectMask = VK_IMAGE_ASPECT_STENCIL_BIT;
      vkCmdCopyImageToBuffer(cmd, img.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst, 1, &c);
    }
  }
  VkMemoryBarrier host{VK_STRUCTURE_TYPE_MEMORY_BARRIER};
  host.srcAccessMask = VK_ACCESS_TRANSFER_WRITE_BIT;
  host.dstAccessMask = VK_ACCESS_HOST_READ_BIT;
  vkCmdPipelineBarrier(cmd, VK_PIPELINE_STAGE_TRANSFER_BIT, VK_PIPELINE_STAGE_HOST_BIT, 0, 1, &host, 0, nullptr, 0,
                       nullptr);
}

json matrix(const glm::mat4& m, bool row_major) {
  json j = json::array();
  for (int i = 0; i < 4; ++i)
    for (int k = 0; k < 4; ++k) j.push_back(row_major ? m[k][i] : m[i][k]);
  return j;
}

std::string file_name(const Renderer& r, int p, int a) {
  return "pass" + std::to_string(p) + "_att" + std::to_string(a) + "_" +
         r.desc->passes[size_t(p)].attachments[size_t(a)].name + ".bin";
}

json attachments_json(const Renderer& r) {
  json list = json::array();
  for (size_t p = 0; p < r.desc->passes.size(); ++p)
    for (size_t a = 0; a < r.desc->passes[p].attachments.size(); ++a) {
      const Attachment& at = r.desc->passes[p].attachments[a];
      const FormatInfo& fi = info_of(at.format);
      const bool st = has_stencil(at.format);
      json j = {{"pass", p}, {"attachment", a}, {"name", at.name}, {"vk_format", fi.name},
                {"store", at.store ? "store" : "dont_care"}};
      j["file"] = at.store ? json(file_name(r, int(p), int(a))) : json(nullptr);
      j["bytes_per_texel"] = at.store ? json(fi.bytes + (at.stencil_store ? 1 : 0)) : json(nullptr);
      if (is_depth(at.format)) {
        j["depth_bytes_per_texel"] = fi.bytes;
        j["stencil_store"] = st ? json(at.stencil_store ? "store" : "dont_care") : json(nullptr);
        j["stencil_bytes_per_texel"] = at.store && at.stencil_store ? 1 : 0;
        j["clear"] = {at.clear.depthStencil.depth, at.clear.depthStencil.stencil};
      } else {
        const float* c = at.clear.color.float32;
        j["clear"] = at.format == VK_FORMAT_R8_UINT ? json({0, 0, 0, 0}) : json({c[0], c[1], c[2], c[3]});
      }
      if (!at.store) j["note"] = "storeOp DONT_CARE: not dumped";
      else if (st && !at.stencil_store) j["note"] = "stencilStoreOp DONT_CARE: depth plane only";
      list.push_back(j);
    }
  return list;
}

json dump_json(const Renderer& r, const DumpInfo& info) {
  const Camera& c = *info.camera;
  json members = json::array();
  for (const Member& m : c.members)
    members.push_back({{"name", m.name}, {"offset", m.offset}, {"type", m.type},
                       {"order", m.type == "mat4" ? (c.row_major ? "row_major" : "column_major") : "-"}});
  json passes = json::array();
  for (size_t p = 0; p < r.desc->passes.size(); ++p)
    passes.push_back({{"pass", p}, {"role", r.desc->passes[p].role}, {"samples", r.desc->passes[p].samples}});
  const char* storage = c.row_major ? "row_major" : "column_major";
  json j = {{"producer", "gbuffer_zoo"}, {"mode", mode_name(r.desc->mode)}, {"gpu", info.gpu},
            {"frame", info.frame}, {"frames", info.frames}, {"width", r.width}, {"height", r.height},
            {"near", c.near_plane}, {"far", c.far_plane}, {"fovy_radians", c.fovy},
            {"eye_world", {c.eye.x, c.eye.y, c.eye.z}}, {"target_world", {c.target.x, c.target.y, c.target.z}},
            {"up_world", {c.up.x, c.up.y, c.up.z}}, {"matrix_storage", storage},
            {"view_from_world", matrix(c.view_from_world, c.row_major)},
            {"clip_from_view", matrix(c.clip_from_view, c.row_major)},
            {"clip_from_world", matrix(c.clip_from_world, c.row_major)},
            {"camera_buffer", {{"set", 0}, {"binding", 0}, {"bytes", c.block.size()}, {"file", "camera.bin"},
                               {"members", members}}},
            {"objects_buffer", {{"set", 0}, {"binding", 1}, {"bytes", r.objects.size}, {"stride", sizeof(ObjectGpu)},
                                {"file", "objects.bin"}, {"matrix_storage", storage}}},
            {"lights_buffer", {{"set", 0}, {"binding", 2}, {"bytes", r.lights.size}, {"file", "lights.bin"}}},
            {"push_constants", nullptr}, {"passes", passes}, {"attachments", attachments_json(r)}};
  if (r.desc->mode == Mode::y_down)
    j["matrices_note"] = "view_from_world and clip_from_view are the truth only: no buffer holds them";
  return j;
}

bool write_file(const fs::path& path, const void* data, size_t bytes) {
  std::ofstream f(path, std::ios::binary);
  f.write(static_cast<const char*>(data), std::streamsize(bytes));
  f.close();
  if (!f) std::fprintf(stderr, "gbuffer_zoo: --dump: cannot write %s\n", path.c_str());
  return bool(f);
}

}  // namespace

bool write_dump(const Gpu& g, const Renderer& r, const DumpInfo& info, const std::string& dir) {
  size_t total = 0;
  const std::vector<Slot> slots = plan(r, total);
  Buffer staging = make_buffer(g, total, VK_BUFFER_USAGE_TRANSFER_DST_BIT);
  VkCommandBuffer cmd = start_commands(g);
  record_copies(r, slots, staging.buffer, cmd);
  finish_commands(g, cmd);
  auto* bytes = static_cast<uint8_t*>(staging.mapped);
  const fs::path partial(dir + ".partial");
  std::error_code ec;
  fs::remove_all(partial, ec);
  fs::create_directories(partial, ec);
  bool ok = !ec;
  if (ec) std::fprintf(stderr, "gbuffer_zoo: --dump: cannot create %s: %s\n", partial.c_str(), ec.message().c_str());
  for (const Slot& s : slots) {
    if (!ok) break;
    const VkFormat f = r.desc->passes[size_t(s.pass)].attachments[size_t(s.attachment)].format;
    if (f == VK_FORMAT_D24_UNORM_S8_UINT)
      for (size_t i = 3; i < s.depth_bytes; i += 4) bytes[s.offset + i] = 0;
    ok = write_file(partial / file_name(r, s.pass, s.attachment), bytes + s.offset, s.depth_bytes + s.stencil_bytes);
  }
  free_buffer(g, staging);
  const std::string text = dump_json(r, info).dump(2) + "\n";
  ok = ok && write_file(partial / "camera.bin", r.camera.mapped, size_t(r.camera.size)) &&
       write_file(partial / "objects.bin", r.objects.mapped, size_t(r.objects.size)) &&
       write_file(partial / "lights.bin", r.lights.mapped, size_t(r.lights.size)) &&
       write_file(partial / "dump.json", text.data(), text.size());
  if (!ok) return false;
  fs::remove_all(dir, ec);
  fs::rename(partial, dir, ec);
  if (ec) std::fprintf(stderr, "gbuffer_zoo: --dump: cannot rename %s: %s\n", partial.c_str(), ec.message().c_str());
  return !ec;
}

}  // namespace zoo
