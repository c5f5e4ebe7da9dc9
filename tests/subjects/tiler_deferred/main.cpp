// tiler_deferred: a headless, tile-style deferred renderer (Vulkan 1.0, no extensions) written for gblens's
// tests as "another renderer" (README.md). Renders --frames frames, one submission each; --dump writes one.
#include <cstring>
#include <string>

#include "dump.h"
#include "renderdoc.h"

namespace {

using td::options;

const char* k_usage =
    "usage: tiler_deferred [--mode subpass|msaa|compute] [--size WxH] [--frames N] [--dump DIR] [--dump-frame K]\n"
    "                      [--transient on|off] [--capture-frame K]\n"
    "  --mode subpass|msaa|compute  one render pass with two subpasses and input attachments (default), a 4x\n"
    "                       G-buffer lit per sample and averaged in the shader, or albedo and normal written\n"
    "                       by a compute dispatch into storage images named tiler.albedo / tiler.normal\n"
    "  --size WxH           target size (default 320x180)\n"
    "  --frames N           frames 0..N-1 (default 3)\n"
    "  --dump DIR           write frame --dump-frame's attachments and frame.json to DIR (atomically)\n"
    "  --dump-frame K       the frame --dump writes (default: the last)\n"
    "  --transient on|off   subpass mode: G-buffer images TRANSIENT + lazily allocated (default on)\n"
    "  --capture-frame K    under renderdoccmd capture: RenderDoc captures frame K (its one submission)\n"
    "  GBLENS_VALIDATE=1    validation layer on; any warning or error makes the exit status 1\n";

[[noreturn]] void bad(const std::string& line) {
  std::fprintf(stderr, "tiler_deferred: %s\n", line.c_str());
  std::exit(2);
}

bool parse_number(const std::string& text, uint32_t low, uint32_t high, uint32_t& out) {
  if (text.empty() || text.size() > 9 || text.find_first_not_of("0123456789") != std::string::npos) return false;
  const unsigned long v = std::stoul(text);
  if (v < low || v > high) return false;
  out = uint32_t(v);
  return true;
}

options parse(int argc, char** argv) {
  options o;
  for (int i = 1; i < argc; ++i) {
    const std::string flag = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) bad(flag + ": needs a value");
      return argv[++i];
    };
    if (flag == "--help" || flag == "-h") {
      std::fputs(k_usage, stdout);
      std::exit(0);
    } else if (flag == "--mode") {
      const std::string v = value();
      if (v == "subpass") o.mode = td::mode_kind::subpass;
      else if (v == "msaa") o.mode = td::mode_kind::msaa;
      else if (v == "compute") o.mode = td::mode_kind::compute;
      else bad("--mode " + v + ": expected subpass, msaa or compute");
    } else if (flag == "--size") {
      const std::string v = value();
      const size_t x = v.find('x');
      if (x == std::string::npos || !parse_number(v.substr(0, x), 1, 8192, o.width) ||
          !parse_number(v.substr(x + 1), 1, 8192, o.height))
        bad("--size " + v + ": expected WxH, each 1..8192, e.g. 320x180");
    } else if (flag == "--frames") {
      const std::string v = value();
      if (!parse_number(v, 1, 1000000, o.frames)) bad("--frames " + v + ": expected a count of at least 1");
    } else if (flag == "--dump") {
      o.dump = value();
      if (o.dump.empty()) bad("--dump: needs a folder name");
    } else if (flag == "--dump-frame") {
      const std::string v = value();
      uint32_t k = 0;
      if (!parse_number(v, 0, 999999, k)) bad("--dump-frame " + v + ": expected a frame index");
      o.dump_frame = k;
    } else if (flag == "--capture-frame") {
      const std::string v = value();
      uint32_t k = 0;
      if (!parse_number(v, 0, 999999, k)) bad("--capture-frame " + v + ": expected a frame index");
      o.capture_frame = k;
    } else if (flag == "--transient") {
      const std::string v = value();
      if (v == "on") o.transient = true;
      else if (v == "off") o.transient = false;
      else bad("--transient " + v + ": expected on or off");
    } else {
      bad("unknown argument " + flag + " (--help lists the flags)");
    }
  }
  if (o.dump_frame >= 0 && o.dump.empty()) bad("--dump-frame: needs --dump DIR");
  if (o.dump_frame < 0) o.dump_frame = int64_t(o.frames) - 1;
  if (o.capture_frame >= int64_t(o.frames))
    bad("--capture-frame " + std::to_string(o.capture_frame) + ": the frames are 0.." + std::to_string(o.frames - 1));
  if (o.dump_frame >= int64_t(o.frames))
    bad("--dump-frame " + std::to_string(o.dump_frame) + ": the frames are 0.." + std::to_string(o.frames - 1));
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const options o = parse(argc, argv);
  td::gpu g = td::open_gpu(o.mode == td::mode_kind::compute);
  td::shared_gpu sh = td::make_shared(g, td::build_scene(0));
  std::unique_ptr<td::mode_renderer> r = o.mode == td::mode_kind::subpass ? td::make_subpass_renderer(g, sh, o)
                                         : o.mode == td::mode_kind::msaa  ? td::make_msaa_renderer(g, sh, o)
                                                                          : td::make_compute_renderer(g, sh, o);
  const uint32_t mode = uint32_t(o.mode);  // 0 subpass, 1 msaa, 2 compute
  td::dump_frame dump;
  dump.opts = &o;
  dump.gpu_name = g.name;
  for (uint32_t k = 0; k < o.frames; ++k) {
    const td::scene s = td::build_scene(k);
    const td::camera cam = td::build_camera(k, o.width, o.height);
    const td::frame_block block = td::build_block(cam, k, o.width, o.height, mode);
    td::frame_input in;
    in.frame = k;
    in.uniform_offset = (k % 2) * sh.slot_bytes;
    in.objects = &s;
    in.dump = !o.dump.empty() && int64_t(k) == o.dump_frame;
    std::memcpy(static_cast<char*>(sh.uniforms.mapped) + in.uniform_offset, &block, sizeof(block));
    const bool captured = int64_t(k) == o.capture_frame && td::renderdoc_present();
    if (captured) td::renderdoc_frame_begin(g.instance);
    VkCommandBuffer cmd = td::begin_frame_commands(g);
    r->record(cmd, in);
    td::submit_and_wait(g, cmd);
    if (captured && !td::renderdoc_frame_end(g.instance)) {
      std::fprintf(stderr, "tiler_deferred: RenderDoc wrote no capture of frame %u\n", k);
      return 1;
    }
    if (in.dump) {
      dump.frame = k;
      dump.cam = cam;
      dump.block = block;
      dump.uniform_offset = in.uniform_offset;
    }
  }
  bool dumped = true;
  if (!o.dump.empty()) {
    dump.targets = r->targets();
    dump.files = r->dumped_files();  // only the dumped frame's command buffer copied into them
    dumped = td::write_dump(dump);
  }
  TD_CHECK(vkDeviceWaitIdle(g.device));
  r.reset();
  td::drop_shared(g, sh);
  td::close_gpu(g);
  if (td::validation_count()) {
    std::fprintf(stderr, "tiler_deferred: %d validation message(s)\n", td::validation_count());
    return 1;
  }
  if (!dumped) return 1;
  const bool rdc = o.capture_frame >= 0 && td::renderdoc_present();
  std::printf("tiler_deferred: rendered %u frame(s) at %ux%u, mode %s%s%s\n", o.frames, o.width, o.height,
              td::mode_name(o.mode), rdc ? (", RenderDoc captured frame " + std::to_string(o.capture_frame)).c_str() : "",
              o.dump.empty() ? "" : (", dumped frame " + std::to_string(dump.frame) + " to " + o.dump).c_str());
  return 0;
}
