#version 450
// world_tbn G-buffer: world position + object id, the TBN-mapped world normal exactly as the matrix
// product gives it (no normalisation anywhere) + roughness, linear albedo + metallic.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "surface.glsl"

layout(location = 0) out vec4 o_position;  // RGBA16F: xyz world, w object id (index + 1)
layout(location = 1) out vec4 o_normal;    // RGBA16F: xyz world normal (not unit), w roughness
layout(location = 2) out vec4 o_albedo;    // RGBA8_UNORM: rgb linear albedo, a metallic

void main() {
  const Surface s = zoo_surface();
  o_position = vec4(v_world, float(s.id));
  o_normal = vec4(s.normal_raw, s.roughness);
  o_albedo = vec4(s.albedo, s.metallic);
}
