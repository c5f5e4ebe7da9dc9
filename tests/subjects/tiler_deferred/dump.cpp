// tiler_deferred --dump (dump.h): the files and frame.json. Matrices are written as the uniform buffer holds
// them (row-major, 16 floats); uniforms.bin is the 448 bytes of the frame's bound range.
#include "dump.h"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

namespace td {

namespace {

namespace fs = std::filesystem;

nlohmann::ordered_json floats(const float* v, int n) {
  nlohmann::ordered_json j = nlohmann::ordered_json::array();
  for (int i = 0; i < n; ++i) j.push_back(v[i]);
  return j;
}

nlohmann::ordered_json vec3(const glm::vec3& v) { return {v.x, v.y, v.z}; }

nlohmann::ordered_json camera_json(const dump_frame& d) {
  const frame_block& b = d.block;
  const std::pair<const char*, int> members[] = {
      {"eye_world", 0},         {"view_from_world", 16}, {"clip_from_view", 80}, {"clip_from_world", 144},
      {"world_from_clip", 208}, {"sun_toward", 272},     {"sun_color", 288},     {"ambient", 304},
      {"point_position", 320},  {"point_color", 368},    {"viewport", 416},      {"frame_info", 432}};
  nlohmann::ordered_json list = nlohmann::ordered_json::array();
  for (auto [name, offset] : members) {
    const bool mat = offset >= 16 && offset < 272, array = offset == 320 || offset == 368;
    list.push_back({{"name", name}, {"offset", offset},
                    {"type", mat ? "mat4 (row_major)" : array ? "vec4[3]" : offset == 432 ? "uvec4" : "vec4"},
                    {"bytes", mat ? 64 : array ? 48 : 16}});
  }
  const bool msaa = d.opts->mode == mode_kind::msaa;
  return {
      {"uniform_buffer",
       {{"set", 0}, {"binding", 0}, {"descriptor_type", "VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER_DYNAMIC"},
        {"range_bytes", sizeof(frame_block)}, {"dynamic_offset", d.uniform_offset},
        {"bound_in_render_passes", msaa ? nlohmann::ordered_json{0, 1} : nlohmann::ordered_json{0}}, {"file", "uniforms.bin"},
        {"members", list}}},
      {"matrix_order", "row_major"},
      {"order", {"view_from_world", "clip_from_view", "clip_from_world", "world_from_clip"}},
      {"offsets", {{"view_from_world", 16}, {"clip_from_view", 80}, {"clip_from_world", 144}, {"world_from_clip", 208}}},
      {"view_from_world", floats(b.view_from_world, 16)},
      {"clip_from_view", floats(b.clip_from_view, 16)},
      {"clip_from_world", floats(b.clip_from_world, 16)},
      {"world_from_clip", floats(b.world_from_clip, 16)},
      {"convention", "vulkan"},
      {"projection", "perspective"},
      {"depth", "reverse_z_infinite"},
      {"fovy_radians", d.cam.fovy},
      {"near", d.cam.near},
      {"far", nullptr},
      {"view_handedness", "left"},
      {"world_handedness", "left"},
      {"up", "z"},
      {"image_origin", "top"},
      {"eye_world", vec3(d.cam.eye)},
      {"target_world", vec3(d.cam.target)},
      {"up_world", vec3(d.cam.up)},
  };
}

nlohmann::ordered_json target_json(const target_info& t) {
  return {{"name", t.name},
          {"vk_format", t.vk_format},
          {"bytes_per_texel", t.bytes_per_texel},
          {"render_pass", t.render_pass},
          {"subpass", t.subpass},
          {"attachment", t.attachment},
          {"color", t.color < 0 ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(t.color)},
          {"samples", t.samples},
          {"files", t.files},
          {"store", t.store ? "store" : "dont_care"},
          {"transient", t.transient},
          {"input_of_subpass", t.input_of_subpass},
          {"debug_name", t.debug_name.empty() ? nlohmann::ordered_json(nullptr) : nlohmann::ordered_json(t.debug_name)}};
}

bool write_file(const fs::path& path, const void* data, size_t bytes) {
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out.write(static_cast<const char*>(data), std::streamsize(bytes));
  out.close();
  if (!out) std::fprintf(stderr, "tiler_deferred: --dump: cannot write %s\n", path.c_str());
  return bool(out);
}

}  // namespace

bool write_dump(const dump_frame& d) {
  const fs::path dir = d.opts->dump, partial = d.opts->dump + ".partial";
  std::error_code ec;
  fs::remove_all(partial, ec);
  if (!fs::create_directories(partial, ec) || ec) {
    std::fprintf(stderr, "tiler_deferred: --dump: cannot create %s\n", partial.c_str());
    return false;
  }
  for (const auto& [name, bytes] : d.files)
    if (!write_file(partial / name, bytes.data(), bytes.size())) return false;
  if (!write_file(partial / "uniforms.bin", &d.block, sizeof(d.block))) return false;
  const bool msaa = d.opts->mode == mode_kind::msaa;
  nlohmann::ordered_json targets = nlohmann::ordered_json::array();
  for (const target_info& t : d.targets) targets.push_back(target_json(t));
  const nlohmann::ordered_json frame = {
      {"producer", "tiler_deferred"},
      {"gpu", d.gpu_name},
      {"mode", mode_name(d.opts->mode)},
      {"frame", d.frame},
      {"frames", d.opts->frames},
      {"width", d.opts->width},
      {"height", d.opts->height},
      {"samples", msaa ? 4 : 1},
      {"transient_option", d.opts->transient ? "on" : "off"},
      {"id_clear", 0xF0000000u | d.frame},
      {"rows", "top_to_bottom"},
      {"camera", camera_json(d)},
      {"targets", targets},
  };
  const std::string text = frame.dump(2) + "\n";
  if (!write_file(partial / "frame.json", text.data(), text.size())) return false;
  fs::remove_all(dir, ec);
  fs::rename(partial, dir, ec);
  if (ec) {
    std::fprintf(stderr, "tiler_deferred: --dump: cannot rename %s to %s: %s\n", partial.c_str(), dir.c_str(),
                 ec.message().c_str());
    return false;
  }
  return true;
}

}  // namespace td
