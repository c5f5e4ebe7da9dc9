#version 450
// view_oct G-buffer: albedo (SRGB), view-space normal octahedral in RG16_SNORM, material RGBA8
// (roughness, metallic, occlusion, 0); reversed-Z depth.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "surface.glsl"
#include "codecs.glsl"

layout(location = 0) out vec4 o_albedo;    // rgb albedo, a 1
layout(location = 1) out vec2 o_normal;    // signed octahedral view normal
layout(location = 2) out vec4 o_material;  // roughness, metallic, occlusion, 0

void main() {
  const Surface s = zoo_surface();
  o_albedo = vec4(s.albedo, 1.0 + 0.0 * v_world.x);
  o_normal = zoo_oct_encode(normalize(mat3(zoo_view()) * s.normal));
  o_material = vec4(s.roughness, s.metallic, s.occlusion, 0.0);
}
