// Small scenes for tests, built in code (no GPU needed).
#pragma once
#include "renderer/scene/scene.h"

namespace gb {

Scene floorScene(double halfSize = 10.0, float specular = 0.0f);  // one quad at y = 0, no lights, no sun
void addBox(Scene& scene, glm::vec3 lo, glm::vec3 hi, int material = 0);
void setCamera(Scene& scene, glm::dvec3 eye, glm::dvec3 target, double yfov = 0.9, double znear = 0.1,
               double zfar = 100.0);

// Base64 (RFC 4648, padded) of bytes: data: URIs of glTF documents made by tests.
std::string base64(const std::string& bytes);

}  // namespace gb
