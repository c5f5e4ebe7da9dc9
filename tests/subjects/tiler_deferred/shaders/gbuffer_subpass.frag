#version 450
#extension GL_GOOGLE_include_directive : require
// tiler_deferred, mode subpass, subpass 0: colour 0 = id, 1 = normal, 2 = albedo, 3 = material.
#include "object.glsl"
layout(location = 0) in vec3 in_normal_world;
layout(location = 1) in float in_view_depth;
layout(location = 0) out uint out_id;
layout(location = 1) out vec4 out_normal;
layout(location = 2) out vec4 out_albedo;
layout(location = 3) out vec2 out_material;
void main() {
  out_id = object.id;
  out_normal = vec4(normalize(in_normal_world) * 0.5 + 0.5, object.material.y / 3.0);
  out_albedo = object.albedo_roughness;
  out_material = vec2(object.material.x, in_view_depth);
}
