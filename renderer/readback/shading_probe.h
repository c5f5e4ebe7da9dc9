// The point-light formula run on the device (shading_probe.cpp), for testing it against the
// double-precision reference of the same formula (shaders/shading.h).
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "renderer/gpu/renderer_state.h"

namespace gb {

// One surface point and one light, eye space: unit normal N, position P, the light's position and radius.
struct ShadingCase {
  glm::vec3 normal, position, light;
  float radius = 1.0f;
};

// shadePoint (shaders/shading.h) of each case in float on the device, with albedo, specular and
// the light's colour 1: the light's diffuse + specular contribution, rgb.
std::vector<glm::vec3> shadePointsOnDevice(Renderer& r, const std::vector<ShadingCase>& cases);

}  // namespace gb
