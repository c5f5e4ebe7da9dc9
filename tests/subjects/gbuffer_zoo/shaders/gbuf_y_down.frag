#version 450
// y_down G-buffer (Y-down left-handed world): world position in RGBA32F (w 1), world normal
// octahedral remapped to [0, 1] in RG16_UNORM, albedo (SRGB) + roughness, object id in R8_UINT.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "surface.glsl"
#include "codecs.glsl"

layout(location = 0) out vec4 o_position;  // xyz world, w 1
layout(location = 1) out vec2 o_normal;    // octahedral * 0.5 + 0.5
layout(location = 2) out vec4 o_albedo;    // rgb albedo, a roughness
layout(location = 3) out uint o_id;        // object index + 1

void main() {
  const Surface s = zoo_surface();
  o_position = vec4(v_world, 1.0);
  o_normal = zoo_oct_encode(s.normal) * 0.5 + 0.5;
  o_albedo = vec4(s.albedo, s.roughness);
  o_id = s.id;
}
