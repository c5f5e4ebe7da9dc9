// CPU mirror of the G-buffer encodings.
#include "renderer/core/codec.h"

#include <cmath>

namespace gb {

glm::dvec2 octEncode(glm::dvec3 n) {
  n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  glm::dvec2 p(n.x, n.y);
  if (n.z < 0.0)
    p = (1.0 - glm::abs(glm::dvec2(n.y, n.x))) * glm::dvec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
  return p;
}

glm::dvec3 octDecode(glm::dvec2 p) {
  glm::dvec3 n(p, 1.0 - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0) {
    glm::dvec2 xy = (1.0 - glm::abs(glm::dvec2(n.y, n.x))) * glm::dvec2(n.x >= 0.0 ? 1.0 : -1.0, n.y >= 0.0 ? 1.0 : -1.0);
    n.x = xy.x;
    n.y = xy.y;
  }
  return glm::normalize(n);
}

// The shader's octEncode/octDecode in float (shaders/octahedral.glsl), operation for operation.
static glm::vec2 octEncodeFloat(glm::vec3 n) {
  n /= std::abs(n.x) + std::abs(n.y) + std::abs(n.z);
  glm::vec2 p(n.x, n.y);
  if (n.z < 0.0f)
    p = (1.0f - glm::abs(glm::vec2(n.y, n.x))) * glm::vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
  return p;
}
static glm::vec3 octDecodeFloat(glm::vec2 p) {
  glm::vec3 n(p, 1.0f - std::abs(p.x) - std::abs(p.y));
  if (n.z < 0.0f) {
    glm::vec2 xy = (1.0f - glm::abs(glm::vec2(n.y, n.x))) * glm::vec2(n.x >= 0.0f ? 1.0f : -1.0f, n.y >= 0.0f ? 1.0f : -1.0f);
    n.x = xy.x;
    n.y = xy.y;
  }
  return glm::normalize(n);
}

glm::ivec2 octQuantize(glm::vec3 n, int bits, OctEncoding encoding) {
  const float scale = float(octCodeScale(bits));
  glm::vec2 p = octEncodeFloat(n) * scale;
  if (encoding == OctEncoding::Nearest) return glm::ivec2(glm::round(p));  // the attachment's rounding
  // octEncodePrecise in the shader: the four codes around p, the best decoded direction wins
  // (the first of equals, in the order (0,0), (1,0), (0,1), (1,1)).
  glm::vec2 base = glm::floor(p), best = base;
  float bestDistance = 8.0f;
  for (int i = 0; i < 4; ++i) {
    glm::vec2 c = glm::clamp(base + glm::vec2(float(i & 1), float(i >> 1)), -scale, scale);
    glm::vec3 e = octDecodeFloat(c / scale) - n;
    float distance = glm::dot(e, e);  // the squared chord: see the shader for why not the cosine
    if (distance < bestDistance) {
      bestDistance = distance;
      best = c;
    }
  }
  return glm::ivec2(best);
}

glm::dvec3 octDequantize(glm::ivec2 code, int bits) { return octDecode(glm::dvec2(code) / double(octCodeScale(bits))); }

DecodedNormal decodeNormalTexel(const CpuImage& img, uint32_t x, uint32_t y, NormalFormat format) {
  DecodedNormal d;
  glm::dvec4 v(img.value(x, y, 0), img.value(x, y, 1), img.value(x, y, 2), img.value(x, y, 3));
  d.shadow = v.w;
  switch (format) {
    case NormalFormat::OctRg16: d.stored = octDecode(glm::dvec2(v)); break;
    case NormalFormat::Rgb10a2: d.stored = glm::dvec3(v) * 2.0 - 1.0; break;
    default: d.stored = glm::dvec3(v); break;
  }
  double len = glm::length(d.stored);
  d.unit = len > 0.0 ? d.stored / len : glm::dvec3(0.0);
  return d;
}

bool unlitTexel(const CpuImage& img, uint32_t x, uint32_t y, NormalFormat format) {
  glm::dvec3 v(img.value(x, y, 0), img.value(x, y, 1), img.value(x, y, 2));
  if (format == NormalFormat::OctRg16) return v.z > 0.5;
  if (format == NormalFormat::Rgb10a2) v = v * 2.0 - 1.0;
  return glm::dot(v, v) < 0.0625;
}

static glm::vec2 shaderNdc(const gpu::FrameData& f, uint32_t x, uint32_t y) {
  glm::vec2 fragCoord(float(x) + 0.5f, float(y) + 0.5f);
  return fragCoord * glm::vec2(f.viewport.z, f.viewport.w) * 2.0f - 1.0f;
}

glm::vec3 shaderEyeFromEyeDepth(const gpu::FrameData& f, uint32_t x, uint32_t y, float stored) {
  glm::vec2 ndc = shaderNdc(f, x, y);
  glm::vec2 xy = stored * (ndc + glm::vec2(f.eyeRay.z, f.eyeRay.w)) * glm::vec2(f.eyeRay.x, f.eyeRay.y);
  return {xy, -stored};
}

glm::vec3 shaderEyeFromHardwareDepth(const gpu::FrameData& f, uint32_t x, uint32_t y, float depth) {
  glm::vec4 e = f.eyeFromClip * glm::vec4(shaderNdc(f, x, y), depth, 1.0f);
  return glm::vec3(e) / e.w;
}

glm::vec3 shaderEyeFromStoredPosition(const gpu::FrameData& f, glm::vec3 stored, PositionSpace space) {
  glm::mat3 eyeFromWorld = glm::transpose(glm::mat3(f.worldFromEye));
  return eyeFromWorld * (space == PositionSpace::World ? stored - glm::vec3(f.worldFromEye[3]) : stored);
}

}  // namespace gb
