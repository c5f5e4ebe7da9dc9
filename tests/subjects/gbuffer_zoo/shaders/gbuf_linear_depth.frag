#version 450
// linear_depth G-buffer: distance along the view axis in metres (R32F), view-space unit normal +
// roughness (RGBA16F), albedo sRGB-encoded by this shader into UNORM + metallic.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "surface.glsl"
#include "codecs.glsl"

layout(location = 0) out float o_depth;   // -z_view, metres
layout(location = 1) out vec4 o_normal;   // xyz view normal, w roughness
layout(location = 2) out vec4 o_albedo;   // rgb sRGB-encoded albedo, a metallic

void main() {
  const Surface s = zoo_surface();
  o_depth = -(zoo_view() * vec4(v_world, 1.0)).z;
  o_normal = vec4(normalize(mat3(zoo_view()) * s.normal), s.roughness);
  o_albedo = vec4(zoo_srgb_encode(s.albedo), s.metallic);
}
