// The G-buffer's normal encoder run on the device (codec_probe.cpp), for testing its CPU mirror.
#pragma once
#include <glm/glm.hpp>

#include <vector>

#include "renderer/gpu/renderer_state.h"

namespace gb {

// encodeNormalShadow (shaders/gbuffer_codec.glsl) of each unit vector under this format and
// octahedral encoding, as the G-buffer pass's shader writes it (shadow term 1), before the
// attachment converts it to its storage format.
std::vector<glm::vec4> encodeNormalsOnDevice(Renderer& r, const std::vector<glm::vec3>& normals, NormalFormat format,
                                             OctEncoding encoding);

}  // namespace gb
