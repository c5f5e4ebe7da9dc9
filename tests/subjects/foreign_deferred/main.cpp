// foreign_deferred: a headless Vulkan deferred renderer written for gblens's tests (README.md). It
// renders --frames frames offscreen, brackets --capture-frame for RenderDoc when RenderDoc runs it,
// and writes the last frame's targets and camera with --dump.
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "dump.h"
#include "renderdoc_hook.h"

namespace {

struct options {
  uint32_t width = 320, height = 180, frames = 3;
  int64_t capture_frame = -1;  // -1: the last frame
  bool orthographic = false;
  std::string dump;
};

const char* k_usage =
    "usage: foreign_deferred [--size WxH] [--frames N] [--ortho] [--capture-frame K] [--dump DIR]\n"
    "  --size WxH         target size (default 320x180)\n"
    "  --frames N         frames to render, 0..N-1 (default 3)\n"
    "  --ortho            orthographic camera instead of perspective\n"
    "  --capture-frame K  the frame RenderDoc captures when it runs this program (default: the last)\n"
    "  --dump DIR         write the last frame's targets, uniform buffer and camera.json to DIR\n"
    "  GBLENS_VALIDATE=1  Vulkan validation on: any warning or error makes the exit status 1\n";

[[noreturn]] void usage_error(const std::string& message) {
  std::fprintf(stderr, "foreign_deferred: %s\n%s", message.c_str(), k_usage);
  std::exit(2);
}

bool parse_count(const char* text, uint32_t& out) {
  char* end = nullptr;
  const unsigned long v = std::strtoul(text, &end, 10);
  if (end == text || *end || v == 0 || v > 16384) return false;
  out = uint32_t(v);
  return true;
}

options parse(int argc, char** argv) {
  options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) usage_error(a + ": needs a value");
      return argv[++i];
    };
    if (a == "--help" || a == "-h") {
      std::fputs(k_usage, stdout);
      std::exit(0);
    } else if (a == "--size") {
      const std::string v = value();
      const size_t x = v.find('x');
      if (x == std::string::npos || !parse_count(v.substr(0, x).c_str(), o.width) ||
          !parse_count(v.substr(x + 1).c_str(), o.height))
        usage_error("--size " + v + ": expected WxH, e.g. 320x180");
    } else if (a == "--frames") {
      const char* v = value();
      if (!parse_count(v, o.frames)) usage_error(std::string("--frames ") + v + ": expected a count of at least 1");
    } else if (a == "--capture-frame") {
      const char* v = value();
      uint32_t k = 0;
      if (std::strcmp(v, "0") == 0)
        o.capture_frame = 0;
      else if (parse_count(v, k))
        o.capture_frame = k;
      else
        usage_error(std::string("--capture-frame ") + v + ": expected a frame index");
    } else if (a == "--ortho") {
      o.orthographic = true;
    } else if (a == "--dump") {
      o.dump = value();
    } else {
      usage_error("unknown argument " + a);
    }
  }
  if (o.capture_frame < 0) o.capture_frame = int64_t(o.frames) - 1;
  if (o.capture_frame >= int64_t(o.frames))
    usage_error("--capture-frame " + std::to_string(o.capture_frame) + ": the frames are 0.." +
                std::to_string(o.frames - 1));
  return o;
}

}  // namespace

int main(int argc, char** argv) {
  const options o = parse(argc, argv);
  fd::device_t d = fd::create_device();
  fd::renderer r = fd::create_renderer(d, o.width, o.height, fd::build_scene(0));
  fd::dump_info info;
  info.frames = o.frames;
  info.gpu = d.gpu_name;
  info.sub_pixel_bits = d.sub_pixel_bits;
  bool captured = false;
  for (uint32_t k = 0; k < o.frames; ++k) {
    const bool capture = k == uint64_t(o.capture_frame) && fd::renderdoc_present();
    if (capture) fd::renderdoc_begin(d.instance);
    const fd::scene s = fd::build_scene(k);
    info.frame = k;
    info.cam = fd::build_camera(k, o.width, o.height, o.orthographic);
    info.uniforms = fd::build_uniforms(info.cam, o.width, o.height);
    std::memcpy(r.uniforms.mapped, &info.uniforms, sizeof(info.uniforms));
    VkCommandBuffer cmd = fd::begin_commands(d);
    fd::record_frame(r, cmd, s);
    fd::submit_and_wait(d, cmd);
    if (capture && !fd::renderdoc_end(d.instance)) {
      std::fprintf(stderr, "foreign_deferred: RenderDoc wrote no capture of frame %u (EndFrameCapture failed)\n", k);
      return 1;
    }
    captured = captured || capture;
  }
  const bool dumped = o.dump.empty() || fd::write_dump(d, r, info, o.dump);
  FD_CHECK(vkDeviceWaitIdle(d.device));
  fd::destroy_renderer(d, r);
  fd::destroy_device(d);
  if (fd::validation_messages()) {
    std::fprintf(stderr, "foreign_deferred: %d validation message(s)\n", fd::validation_messages());
    return 1;
  }
  if (!dumped) return 1;
  std::printf("foreign_deferred: rendered %u frame(s) at %ux%u, %s camera%s%s%s\n", o.frames, o.width, o.height,
              o.orthographic ? "orthographic" : "perspective",
              captured ? (", RenderDoc captured frame " + std::to_string(o.capture_frame)).c_str() : "",
              o.dump.empty() ? "" : ", dumped frame ", o.dump.empty() ? "" : (std::to_string(info.frame) + " to " + o.dump).c_str());
  return 0;
}
