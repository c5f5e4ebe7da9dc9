#version 450
// tiler_deferred --dump, mode msaa: every sample of the 4x G-buffer as the bits the GPU stores, into one
// storage buffer: plane (image * 4 + sample), images albedo, normal, id, depth; rows top to bottom.
layout(local_size_x = 8, local_size_y = 8) in;
layout(set = 0, binding = 0) uniform sampler2DMS s_albedo;
layout(set = 0, binding = 1) uniform sampler2DMS s_normal;
layout(set = 0, binding = 2) uniform usampler2DMS s_id;
layout(set = 0, binding = 3) uniform sampler2DMS s_depth;  // the depth aspect
layout(std430, set = 0, binding = 4) writeonly buffer samples_out { uint words[]; };
layout(push_constant) uniform size_data { uvec2 size; } extent;
void main() {
  const uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= extent.size.x || p.y >= extent.size.y) return;
  const uint plane = extent.size.x * extent.size.y, i = p.y * extent.size.x + p.x;
  for (int s = 0; s < 4; ++s) {
    const uvec4 a = uvec4(round(texelFetch(s_albedo, ivec2(p), s) * 255.0));
    words[(0u * 4u + uint(s)) * plane + i] = a.r | (a.g << 8) | (a.b << 16) | (a.a << 24);
    const uvec4 n = uvec4(round(texelFetch(s_normal, ivec2(p), s) * vec4(1023.0, 1023.0, 1023.0, 3.0)));
    words[(1u * 4u + uint(s)) * plane + i] = n.r | (n.g << 10) | (n.b << 20) | (n.a << 30);
    words[(2u * 4u + uint(s)) * plane + i] = texelFetch(s_id, ivec2(p), s).r;
    words[(3u * 4u + uint(s)) * plane + i] = floatBitsToUint(texelFetch(s_depth, ivec2(p), s).r);
  }
}
