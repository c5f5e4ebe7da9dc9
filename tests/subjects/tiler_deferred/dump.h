// tiler_deferred --dump DIR: the dumped frame's attachments as the GPU stores them, uniforms.bin and
// frame.json, written to DIR.partial and renamed to DIR (README.md, "Dump format").
#pragma once
#include <string>
#include <utility>
#include <vector>

#include "frame.h"

namespace td {

struct dump_frame {
  const options* opts = nullptr;
  std::string gpu_name;
  uint32_t frame = 0;
  camera cam{};
  frame_block block{};
  uint32_t uniform_offset = 0;  // the dynamic offset the frame's set 0 was bound with
  std::vector<target_info> targets;
  std::vector<std::pair<std::string, std::vector<uint8_t>>> files;
};

// False (after one line on stderr) when the folder could not be written.
bool write_dump(const dump_frame& d);

}  // namespace td
