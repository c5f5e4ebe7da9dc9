#version 450
// stencil_dontcare G-buffer: albedo + occlusion (SRGB), view-space unit normal in RGBA8_SNORM,
// roughness/metallic in RG8; the pipeline writes the object's stencil bits.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "surface.glsl"

layout(location = 0) out vec4 o_albedo;    // rgb albedo, a occlusion
layout(location = 1) out vec4 o_normal;    // xyz view-space normal (signed), w 1
layout(location = 2) out vec2 o_material;  // roughness, metallic

void main() {
  const Surface s = zoo_surface();
  o_albedo = vec4(s.albedo, s.occlusion + 0.0 * v_world.x);
  o_normal = vec4(normalize(mat3(zoo_view()) * s.normal), 1.0);
  o_material = vec2(s.roughness, s.metallic);
}
