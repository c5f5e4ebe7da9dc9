// gbuffer_zoo: a headless Vulkan test subject with seven G-buffer designs (--mode, README.md). Renders
// frames 0..N-1 offscreen, brackets --capture-frame for an injected RenderDoc, dumps the last frame.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "dump.h"
#include "rdoc.h"

namespace {

struct Options {
  zoo::Mode mode = zoo::Mode::world_tbn;
  bool have_mode = false;
  uint32_t width = 192, height = 108, frames = 3;
  long capture = -1;  // -1: the last frame
  std::string dump;
};

[[noreturn]] void bad(const std::string& why) {
  std::fprintf(stderr, "gbuffer_zoo: %s (usage: gbuffer_zoo --mode MODE [--size WxH] [--frames N] "
               "[--capture-frame K] [--dump DIR])\n", why.c_str());
  std::exit(2);
}

bool number(const std::string& s, long lo, long hi, long& out) {
  if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos || s.size() > 6) return false;
  out = std::stol(s);
  return out >= lo && out <= hi;
}

void parse_size(const std::string& v, Options& o) {
  const size_t x = v.find('x');
  long w = 0, h = 0;
  if (x == std::string::npos || !number(v.substr(0, x), 1, 8192, w) || !number(v.substr(x + 1), 1, 8192, h))
    bad("--size " + v + ": expected WxH, e.g. 192x108");
  o.width = uint32_t(w), o.height = uint32_t(h);
}

Options parse(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (i + 1 >= argc) bad(a == "--mode" || a == "--size" || a == "--frames" || a == "--capture-frame" ||
                                   a == "--dump"
                               ? a + " needs a value"
                               : "unknown argument " + a);
    const std::string v = argv[++i];
    long n = 0;
    if (a == "--mode") {
      if (!zoo::parse_mode(v, o.mode))
        bad("--mode " + v + ": one of world_tbn forward lighting_depth stencil_dontcare linear_depth view_oct y_down");
      o.have_mode = true;
    } else if (a == "--size") {
      parse_size(v, o);
    } else if (a == "--frames") {
      if (!number(v, 1, 100000, n)) bad("--frames " + v + ": expected a count of at least 1");
      o.frames = uint32_t(n);
    } else if (a == "--capture-frame") {
      if (!number(v, 0, 100000, n)) bad("--capture-frame " + v + ": expected a frame index");
      o.capture = n;
    } else if (a == "--dump") {
      if (v.empty()) bad("--dump needs a directory");
      o.dump = v;
    } else {
      bad("unknown argument " + a);
    }
  }
  if (!o.have_mode) bad("--mode is required");
  if (o.capture < 0) o.capture = long(o.frames) - 1;
  if (o.capture >= long(o.frames))
    bad("--capture-frame " + std::to_string(o.capture) + ": frames are 0.." + std::to_string(o.frames - 1));
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse(argc, argv);
  zoo::Gpu gpu = zoo::open_gpu();
  zoo::Renderer r = zoo::make_renderer(gpu, o.mode, o.width, o.height);
  zoo::Camera cam;
  bool captured = false;
  for (uint32_t k = 0; k < o.frames; ++k) {
    cam = zoo::make_camera(o.mode, k, o.width, o.height);
    zoo::upload_frame(r, cam, k);
    const bool capture = long(k) == o.capture && zoo::rdoc_attached();
    if (capture) zoo::rdoc_start(gpu.instance);
    VkCommandBuffer cmd = zoo::start_commands(gpu);
    zoo::record_frame(r, cmd);
    zoo::finish_commands(gpu, cmd);
    if (capture && !zoo::rdoc_end(gpu.instance)) {
      std::fprintf(stderr, "gbuffer_zoo: RenderDoc wrote no capture of frame %u\n", k);
      return 1;
    }
    captured = captured || capture;
  }
  zoo::DumpInfo info{o.frames - 1, o.frames, &cam, gpu.name};
  const bool dumped = o.dump.empty() || zoo::write_dump(gpu, r, info, o.dump);
  ZOO_VK(vkDeviceWaitIdle(gpu.device));
  zoo::free_renderer(gpu, r);
  zoo::close_gpu(gpu);
  if (zoo::validation_count() > 0) {
    std::fprintf(stderr, "gbuffer_zoo: %d validation message(s)\n", zoo::validation_count());
    return 1;
  }
  if (!dumped) return 1;
  std::printf("gbuffer_zoo %s: rendered %u frames, captured %s, dumped %s\n", zoo::mode_name(o.mode), o.frames,
              captured ? ("frame " + std::to_string(o.capture)).c_str() : "none",
              o.dump.empty() ? "none" : ("frame " + std::to_string(o.frames - 1)).c_str());
  return 0;
}
