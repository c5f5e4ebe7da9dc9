// `--dump DIR`: the last frame's ground truth (README.md "Dump"): every stored attachment as raw texels,
// the camera, objects and lights buffers' bytes, and dump.json. Written to DIR.partial, then renamed.
#pragma once
#include <string>

#include "frame.h"

namespace zoo {

struct DumpInfo {
  uint32_t frame = 0, frames = 0;
  const Camera* camera = nullptr;
  std::string gpu;
};

// False (with a message on stderr) when a file cannot be written.
bool write_dump(const Gpu& g, const Renderer& r, const DumpInfo& info, const std::string& dir);

}  // namespace zoo
