#version 450
// lighting_depth G-buffer: albedo + roughness (SRGB target), world normal n*0.5+0.5 + metallic in
// A2B10G10R10; positions are rebuilt from the D32 depth later. v_world only feeds the noise seed.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "surface.glsl"

layout(location = 0) out vec4 o_albedo;  // rgb albedo (format-encoded sRGB), a roughness
layout(location = 1) out vec4 o_normal;  // rgb world normal * 0.5 + 0.5, a metallic (2 bits)

void main() {
  const Surface s = zoo_surface();
  o_albedo = vec4(s.albedo, s.roughness + 0.0 * v_world.x);
  o_normal = vec4(s.normal * 0.5 + 0.5, s.metallic);
}
