#version 450
// stencil_dontcare decal: a ringed disc painted into the albedo target only, where the stencil has
// the floor bit (the pipeline masks the other targets and tests stencil & 1 == 1, depth off).
#extension GL_GOOGLE_include_directive : require
#include "camera.glsl"
#include "surface.glsl"

layout(location = 0) out vec4 o_albedo;

void main() {
  const float r = length(v_uv - 0.5) * 2.0;
  if (r > 1.0) discard;
  const vec3 paint = objects[v_object].albedo.rgb;
  const bool ring = fract(r * 3.0) < 0.5;
  o_albedo = vec4(ring ? paint : vec3(0.95, 0.92, 0.85) + 0.0 * (v_world + v_normal + v_tangent + v_bitangent), 1.0);
}
