// CPU decoding of stored G-buffer texels: the mirror of shaders/gbuffer_codec.glsl.
#pragma once
#include <glm/glm.hpp>

#include "renderer/core/image.h"
#include "renderer/core/options.h"
#include "shaders/shared.h"

namespace gb {

glm::dvec2 octEncode(glm::dvec3 n);
glm::dvec3 octDecode(glm::dvec2 p);

// ---- encoding: what the G-buffer pass stores (shaders/gbuffer_codec.glsl, in float as it computes) ----
// The largest code of a snorm coordinate with `bits` bits (16: 32767); code c stores c / this.
inline int octCodeScale(int bits) { return (1 << (bits - 1)) - 1; }
// The octahedral code of the unit normal n with `bits` per coordinate: each coordinate rounded to
// the nearest code (what the snorm attachment does with the projection), or precise: of the four
// codes around the projection (floor/ceil of each coordinate), the one whose decoded direction
// makes the smallest angle with n (Cigolle et al., "A Survey of Efficient Representations for
// Independent Unit Vectors", JCGT 2014). Same storage, same decoding; a lower largest error.
glm::ivec2 octQuantize(glm::vec3 n, int bits, OctEncoding encoding);
// The unit vector a code decodes to (in double: the exact direction the code stands for).
glm::dvec3 octDequantize(glm::ivec2 code, int bits);

// The stored normal as the shaders decode it (unit length) and before normalization.
struct DecodedNormal {
  glm::dvec3 unit{0.0};
  glm::dvec3 stored{0.0};  // the vector as stored (for the length error)
  double shadow = 1.0;
};
DecodedNormal decodeNormalTexel(const CpuImage& normalShadow, uint32_t x, uint32_t y, NormalFormat format);
// The texel marks an unlit surface (KHR_materials_unlit): no normal stored (unlitTexel in the shader).
bool unlitTexel(const CpuImage& normalShadow, uint32_t x, uint32_t y, NormalFormat format);

// The lighting shaders' position reconstructions (shaders/gbuffer_read.glsl), in float as they
// compute them, from the frame's uniform data: what the lighting passes actually used.
glm::vec3 shaderEyeFromEyeDepth(const gpu::FrameData& frame, uint32_t x, uint32_t y, float eyeDepth);
glm::vec3 shaderEyeFromHardwareDepth(const gpu::FrameData& frame, uint32_t x, uint32_t y, float depth);
glm::vec3 shaderEyeFromStoredPosition(const gpu::FrameData& frame, glm::vec3 stored, PositionSpace space);

}  // namespace gb
