#version 450
// forward: lit colour straight from the geometry, world space; a = 1 where something was drawn.
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "surface.glsl"
#include "shading.glsl"

layout(location = 0) out vec4 o_radiance;  // RGBA16F linear radiance

void main() {
  const Surface s = zoo_surface();
  const vec3 c = zoo_shade(v_world, s.normal, cam.eye_world.xyz, s.albedo, s.roughness, s.metallic, s.occlusion,
                           mat4(1.0));
  o_radiance = vec4(c, 1.0);
}
