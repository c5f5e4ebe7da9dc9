#version 450
// tiler_deferred, mode compute, the resolve dispatch: the G-buffer's albedo and normal are written here,
// into storage images no render pass holds (a compute-deferred engine's way), from the raster pass's raw
// targets: albedo as stored (rgba8), the normal decoded from its 10-bit unorm storage to a unit float xyz
// (rgba16f, renormalised: the 10-bit codes leave it up to 0.2 % off unit; w = the material code) so that
// the lighting reads floats.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2D raw_albedo;
layout(set = 0, binding = 1) uniform sampler2D raw_normal;
layout(set = 0, binding = 2, rgba8) uniform writeonly image2D out_albedo;
layout(set = 0, binding = 3, rgba16f) uniform writeonly image2D out_normal;
layout(push_constant) uniform size_block { uvec2 size; } pc;
void main() {
  const ivec2 t = ivec2(gl_GlobalInvocationID.xy);
  if (t.x >= int(pc.size.x) || t.y >= int(pc.size.y)) return;
  imageStore(out_albedo, t, texelFetch(raw_albedo, t, 0));
  const vec4 n = texelFetch(raw_normal, t, 0);
  imageStore(out_normal, t, vec4(normalize(n.xyz * 2.0 - 1.0), n.w));
}
