// What lights a frame: the sun, the sky's ambient term and point lights, as scenes, frame
// snapshots, captures and the reference describe them (world space, double).
#pragma once
#include <glm/glm.hpp>

namespace gb {

struct Sun {
  bool enabled = true;
  glm::dvec3 toSun{0.3, 0.8, 0.5};  // world space, unit vector toward the sun
  glm::vec3 color{3.0f, 2.8f, 2.5f};  // radiance (rgb * intensity)
};

struct Sky {
  glm::vec3 zenith{0.20f, 0.38f, 0.85f};
  glm::vec3 horizon{0.75f, 0.82f, 0.95f};
  glm::vec3 ground{0.30f, 0.27f, 0.24f};
  glm::vec3 ambient{0.10f, 0.11f, 0.14f};  // ambient light on geometry
};

// A point light. Generated lights orbit `center` (orbitRadius > 0); file lights are static.
struct PointLightDesc {
  glm::dvec3 center{0.0};
  double orbitRadius = 0.0;
  double orbitSpeed = 0.0;  // radians per second
  double phase = 0.0;
  double bob = 0.0;         // vertical amplitude
  double radius = 1.0;      // attenuation reaches exactly zero here
  glm::vec3 color{1.0f};
  double intensity = 1.0;
};

// World-space position of a light at animation time `time` (seconds).
glm::dvec3 lightPosition(const PointLightDesc& light, double time);

}  // namespace gb
