// The vertex layout shared by scenes, the GPU's vertex input and the reference.
#pragma once
#include <glm/glm.hpp>

namespace gb {

struct Vertex {
  glm::vec3 position{0.0f};  // object space
  glm::vec3 normal{0.0f, 0.0f, 1.0f};
  glm::vec2 uv0{0.0f};
  glm::vec2 uv1{0.0f};
  glm::vec4 tangent{1.0f, 0.0f, 0.0f, 1.0f};  // xyz tangent, w bitangent sign
};

}  // namespace gb
