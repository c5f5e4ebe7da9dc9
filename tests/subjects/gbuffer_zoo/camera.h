// Each mode's camera: its conventions (world, view handedness, clip space, reversed Z) and the bytes
// of its camera uniform block (set 0 binding 0), whose layout differs per mode (README.md).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "modes.h"

namespace zoo {

struct Member {
  std::string name, type;
  uint32_t offset;
};

struct Camera {
  std::vector<uint8_t> block;  // the uniform buffer's bytes
  std::vector<Member> members;
  bool row_major = false;  // how the block (and the objects buffer) store matrices
  // The truth, as glm matrices (m[column][row]); y_down's view/projection exist only here.
  glm::mat4 view_from_world{1}, clip_from_view{1}, clip_from_world{1};
  glm::mat4 to_world{1};  // canonical scene world -> this mode's world
  glm::vec3 eye{0}, target{0}, up{0};
  float fovy = 0, near_plane = 0, far_plane = 0;
};

Camera make_camera(Mode mode, uint32_t frame, uint32_t width, uint32_t height);

}  // namespace zoo
