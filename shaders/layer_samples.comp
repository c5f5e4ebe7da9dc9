// gblens attach's layer (app/layer/samples.cpp): every sample of a multisampled attachment, as the
// bits it stores, into the ring. A multisampled image cannot be copied to a buffer, so the layer
// copies it into an image of its own and this shader reads each sample (texelFetch) and writes its
// bits, plane after plane, where a single-sampled copy would have put them. Built for Vulkan 1.0
// (the layer runs in applications of any version); DEPTH: a depth aspect, else colour bits read
// through an unsigned-integer format of the same size.
#version 450
layout(local_size_x = 64) in;
#ifdef DEPTH
layout(set = 0, binding = 0) uniform sampler2DMS src;
#else
layout(set = 0, binding = 0) uniform usampler2DMS src;
#endif
layout(set = 0, binding = 1, std430) writeonly buffer Ring { uint words[]; };
layout(push_constant) uniform Params {
  uint width, height, samples;
  uint texelBytes;   // 1, 2, 4, 8 or 16
  uint depthKind;    // DEPTH: 0 float32 bits, 1 unorm16, 2 unorm24
  uint firstWord;    // the target's offset in the ring, in words
  uint planeWords;   // one sample's plane, in words (its bytes rounded up to 4)
} p;

// Texel `t`'s word `c` (texelBytes >= 4) or its whole value (texelBytes < 4) in sample `s`.
uint stored(uint t, uint c, int s) {
  const ivec2 xy = ivec2(t % p.width, t / p.width);
#ifdef DEPTH
  const float z = texelFetch(src, xy, s).r;
  if (p.depthKind == 1u) return uint(round(z * 65535.0));
  if (p.depthKind == 2u) return uint(round(z * 16777215.0));
  return floatBitsToUint(z);
#else
  return texelFetch(src, xy, s)[c];
#endif
}

void main() {
  // x and z together count a plane's words (a 4K plane has more groups than x alone may), y the sample.
  const uint w = gl_GlobalInvocationID.x + gl_GlobalInvocationID.z * gl_NumWorkGroups.x * 64u;
  const uint s = gl_GlobalInvocationID.y;
  if (w >= p.planeWords || s >= p.samples) return;
  const uint texels = p.width * p.height;
  uint word = 0u;
  if (p.texelBytes >= 4u) {
    const uint per = p.texelBytes / 4u;
    word = stored(w / per, w % per, int(s));
  } else {  // several texels in one word, the first in its low bytes (as a copy to a buffer packs them)
    const uint per = 4u / p.texelBytes, bits = 8u * p.texelBytes;
    const uint mask = (1u << bits) - 1u;
    for (uint k = 0u; k < per; ++k) {
      const uint t = w * per + k;
      if (t < texels) word |= (stored(t, 0u, int(s)) & mask) << (k * bits);
    }
  }
  words[p.firstWord + s * p.planeWords + w] = word;
}
