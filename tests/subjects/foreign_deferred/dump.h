// The app's own ground truth for tests (`--dump DIR`): every target's texels as the GPU stores them,
// read back with vkCmdCopyImageToBuffer, the uniform buffer's bytes, and camera.json (README.md).
#pragma once
#include <string>

#include "passes.h"

namespace fd {

struct dump_info {
  uint32_t frame = 0, frames = 0;
  camera cam;
  frame_uniforms uniforms{};
  std::string gpu;
  uint32_t sub_pixel_bits = 0;
};

// Writes DIR atomically (DIR.partial, then renamed over DIR). Returns false, with a message printed,
// when a file cannot be written.
bool write_dump(const device_t& d, const renderer& r, const dump_info& info, const std::string& dir);

}  // namespace fd
