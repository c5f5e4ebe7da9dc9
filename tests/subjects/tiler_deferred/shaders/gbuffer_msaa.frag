#version 450
#extension GL_GOOGLE_include_directive : require
// tiler_deferred, mode msaa, render pass 0: colour 0 = normal, 1 = id, 2 = albedo (4 samples each).
#include "object.glsl"
layout(location = 0) in vec3 in_normal_world;
layout(location = 1) in float in_view_depth;
layout(location = 0) out vec4 out_normal;
layout(location = 1) out uint out_id;
layout(location = 2) out vec4 out_albedo;
void main() {
  out_normal = vec4(normalize(in_normal_world) * 0.5 + 0.5, object.material.y / 3.0);
  out_id = object.id;
  out_albedo = object.albedo_roughness;
}
