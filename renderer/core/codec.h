// CPU decoding of stored G-buffer texels: the mirror of shaders/gbuffer_codec.glsl.
#pragma once
#include <glm/glm.hpp>

#include "renderer/core/image.h"
#include "renderer/core/options.h"
#include "shaders/shared.h"

namespace gb {

glm::dvec2 octEncode(glm::dvec3 n);
glm::dvec3 octDecode(glm::dvec2 p);

// The stored normal as the shaders decode it (unit length) and before normalization.
struct DecodedNormal {
  glm::dvec3 unit{0.0};
  glm::dvec3 stored{0.0};  // the vector as stored (for the length error)
  double shadow = 1.0;
};
DecodedNormal decodeNormalTexel(const CpuImage& normalShadow, uint32_t x, uint32_t y, NormalFormat format);

// The lighting shaders' position reconstructions (shaders/gbuffer_read.glsl), in float as they
// compute them, from the frame's uniform data: what the lighting passes actually used.
glm::vec3 shaderEyeFromEyeDepth(const gpu::FrameData& frame, uint32_t x, uint32_t y, float eyeDepth);
glm::vec3 shaderEyeFromHardwareDepth(const gpu::FrameData& frame, uint32_t x, uint32_t y, float depth);
glm::vec3 shaderEyeFromStoredPosition(const gpu::FrameData& frame, glm::vec3 stored, PositionSpace space);

}  // namespace gb
