// Light animation (see lights.h).
#include "renderer/core/lights.h"

#include <cmath>

namespace gb {

glm::dvec3 lightPosition(const PointLightDesc& l, double time) {
  if (l.orbitRadius <= 0.0 && l.bob == 0.0) return l.center;
  double a = l.phase + l.orbitSpeed * time;
  return l.center + glm::dvec3(std::cos(a) * l.orbitRadius, std::sin(a * 1.7 + l.phase) * l.bob,
                               std::sin(a) * l.orbitRadius);
}

}  // namespace gb
