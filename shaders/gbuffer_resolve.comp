#version 460
#extension GL_GOOGLE_include_directive : require
// gbuffer_resolve (--gbuffer visibility): per pixel, the visibility id's draw and triangle
// (renderer/core/visibility.h), its three vertices from the scene's buffers, the pixel centre's
// ray intersected with the triangle's plane (perspective-correct barycentrics), the attributes
// gbuffer.vert would have interpolated there, and the texels gbuffer.frag writes, stored through
// each target's unsigned view (packed here as the attachment's format would convert them).
// Texture LOD from analytic derivatives: the UVs where the rays of the pixel's 2x2 quad neighbours
// meet the same plane (as a rasterizer's helper lanes extrapolate it), through textureGrad.
// One dispatch per texture group (a distinct pair of base-colour and normal textures, bound as
// the G-buffer pass binds them per draw; group 0: no textures, and the pixels without geometry):
// each pixel is resolved by the dispatch of its draw's group (DrawGeometry.textures.z).
// Variants as gbuffer.frag's: GB_PRIMITIVE_ID, GB_POSITION, GB_MOTION.
#include "common.glsl"
#include "gbuffer_codec.glsl"

layout(local_size_x = kResolveGroup, local_size_y = kResolveGroup) in;
layout(constant_id = kSpecVisibilityBits) const uint VISIBILITY_BITS = 1;
layout(constant_id = kSpecResolvePosition32) const uint POSITION32 = 0;  // the position target is rgba32f

layout(set = 1, binding = kResolveBindingShadowMap) uniform sampler2DShadow shadowMap;
layout(set = 1, binding = kResolveBindingVisibility) uniform usampler2D visibility;
layout(set = 1, binding = kResolveBindingAlbedo) writeonly uniform uimage2D outAlbedo;
layout(set = 1, binding = kResolveBindingNormal) writeonly uniform uimage2D outNormal;
layout(set = 1, binding = kResolveBindingDepth) writeonly uniform uimage2D outDepth;
#ifdef GB_PRIMITIVE_ID
layout(set = 1, binding = kResolveBindingPrimitiveId) writeonly uniform uimage2D outPrimitiveId;
#endif
#ifdef GB_POSITION
layout(set = 1, binding = kResolveBindingPosition) writeonly uniform uimage2D outPosition;
#endif
#ifdef GB_MOTION
layout(set = 1, binding = kResolveBindingMotion) writeonly uniform uimage2D outMotion;
#endif

layout(set = 2, binding = kResolveBindingVertices, std430) readonly buffer VertexBlock { float vertexData[]; };
layout(set = 2, binding = kResolveBindingIndices, std430) readonly buffer IndexBlock { uint indexData[]; };
layout(set = 2, binding = kResolveBindingGeometry, std430) readonly buffer GeometryBlock { DrawGeometry geometry[]; };
layout(set = 1, binding = kResolveBindingBaseTexture) uniform sampler2D baseTexture;
layout(set = 1, binding = kResolveBindingNormalTexture) uniform sampler2D normalTexture;
layout(push_constant) uniform ResolvePush { uvec4 group; } push;  // x: this dispatch's texture group

// The sRGB transfer function (IEC 61966-2-1), as tonemap.comp: what an sRGB attachment encodes.
vec3 srgbEncode(vec3 c) {
  return mix(1.055 * pow(c, vec3(1.0 / 2.4)) - 0.055, 12.92 * c, lessThanEqual(c, vec3(0.0031308)));
}

struct Corner {
  vec3 position, normal;
  vec2 uv0, uv1;
  vec4 tangent;
};
Corner corner(uint v) {
  uint b = v * kVertexFloats;
  Corner c;
  c.position = vec3(vertexData[b], vertexData[b + 1], vertexData[b + 2]);
  c.normal = vec3(vertexData[b + 3], vertexData[b + 4], vertexData[b + 5]);
  c.uv0 = vec2(vertexData[b + 6], vertexData[b + 7]);
  c.uv1 = vec2(vertexData[b + 8], vertexData[b + 9]);
  c.tangent = vec4(vertexData[b + 10], vertexData[b + 11], vertexData[b + 12], vertexData[b + 13]);
  return c;
}

// The triangle in eye space (the vertex stage's eye positions) and its plane's normal.
struct Triangle {
  vec3 e0, e1, e2, n;
};
// The eye ray through framebuffer point `f` (pixels), as the lighting passes reconstruct
// positions (gbuffer_read.glsl eyePosition): its point at eye depth 1.
vec3 eyeRay(vec2 f) {
  vec2 ndc = f * frame.viewport.zw * 2.0 - 1.0;
  return vec3((ndc + frame.eyeRay.zw) * frame.eyeRay.xy, -1.0);
}
// Where that ray meets the triangle's plane: the eye-space point (xyz) is the surface point
// itself (depth and position are not interpolated), and its barycentrics (sub-triangle areas over
// the whole, perspective-correct by construction) interpolate the attributes.
vec3 onPlane(Triangle t, vec2 f, out vec3 l) {
  const vec3 d = eyeRay(f);
  const vec3 p = d * (dot(t.e0, t.n) / dot(d, t.n));
  l = vec3(dot(t.n, cross(t.e1 - p, t.e2 - p)), dot(t.n, cross(t.e2 - p, t.e0 - p)), dot(t.n, cross(t.e0 - p, t.e1 - p)));
  l /= l.x + l.y + l.z;
  return p;
}

// Texel packing of the unsigned views (what the attachment's format conversion stores).
uint packUnorm10x3_2(vec4 v) {
  uvec4 q = uvec4(round(clamp(v, 0.0, 1.0) * vec4(1023.0, 1023.0, 1023.0, 3.0)));
  return q.x | (q.y << 10) | (q.z << 20) | (q.w << 30);
}
uvec4 packNormalTexel(vec4 v) {
  if (NORMAL_ENCODING == kNormalRgba16f) return uvec4(packHalf2x16(v.xy), packHalf2x16(v.zw), 0u, 0u);
  if (NORMAL_ENCODING == kNormalRgba8Snorm) return uvec4(packSnorm4x8(v), 0u, 0u, 0u);
  if (NORMAL_ENCODING == kNormalOctRg16) return uvec4(packSnorm2x16(v.xy), packSnorm2x16(v.zw), 0u, 0u);
  return uvec4(packUnorm10x3_2(v), 0u, 0u, 0u);
}

// surfaceNormal (material.glsl) with the face normal for the degenerate case and the normal
// texture sampled at the analytic gradients.
vec3 resolvedNormal(Material m, bool normalMap, vec3 normal, vec4 tangent, vec2 uv, vec2 dx, vec2 dy,
                    bool frontFacing, vec3 face, vec3 eyePosition) {
  vec3 N;
  if (dot(normal, normal) > 1e-24) {
    N = normalize(normal);
    if (!frontFacing) N = -N;
  } else {
    N = dot(face, face) > 0.0 ? normalize(dot(face, eyePosition) < 0.0 ? face : -face) : vec3(0.0, 0.0, 1.0);
  }
  if (normalMap) {
    vec3 t = tangent.xyz - N * dot(N, tangent.xyz);
    if (dot(t, t) > 1e-20) {
      vec3 T = normalize(t);
      vec3 B = cross(N, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
      vec3 tn = textureGrad(normalTexture, uv, dx, dy).xyz * 2.0 - 1.0;
      tn.xy *= m.params.z;
      vec3 n = T * tn.x + B * tn.y + N * tn.z;
      if (dot(n, n) > 1e-20) N = normalize(n);
    }
  }
  return N;
}

void storeEmpty(ivec2 p) {
  imageStore(outAlbedo, p, uvec4(0u));
  imageStore(outNormal, p, uvec4(0u));
  imageStore(outDepth, p, uvec4(0u));
#ifdef GB_PRIMITIVE_ID
  imageStore(outPrimitiveId, p, uvec4(0u));
#endif
#ifdef GB_POSITION
  imageStore(outPosition, p, uvec4(0u));
#endif
#ifdef GB_MOTION
  imageStore(outMotion, p, uvec4(0u));
#endif
}

void main() {
  const ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, ivec2(frame.viewport.xy)))) return;
  const uint id = texelFetch(visibility, p, 0).x;
  if (id == 0u) {
    if (push.group.x == 0u) storeEmpty(p);  // as the raster pass's clear: 0 where no geometry was drawn
    return;
  }
  const uint draw = (id >> VISIBILITY_BITS) - 1u, triangle = id & ((1u << VISIBILITY_BITS) - 1u);
  const DrawGeometry g = geometry[draw];
  if (uint(g.textures.z) != push.group.x) return;  // another dispatch's pixel
  const DrawData d = draws[draw];
  const Material m = materials[d.info.x];
  const uint first = g.info.x + 3u * triangle;
  Corner c[3];
  vec3 eye[3];
  mat3 xyw;
  for (int k = 0; k < 3; ++k) {
    c[k] = corner(indexData[first + uint(k)] + g.info.y);
    vec4 e = d.eyeFromObject * vec4(c[k].position, 1.0);  // as gbuffer.vert
    vec4 clip = frame.clipFromEye * e;
    eye[k] = e.xyz;
    xyw[k] = clip.xyw;
  }
  Triangle t;
  t.e0 = eye[0];
  t.e1 = eye[1];
  t.e2 = eye[2];
  t.n = cross(eye[1] - eye[0], eye[2] - eye[0]);
  vec3 l;
  const vec3 eyePosition = onPlane(t, vec2(p) + 0.5, l);
  // The quad's neighbours: the pixel and its partner across the 2x2 quad in x (its own row) and
  // in y (its own column), as a rasterizer's fine derivatives difference them (lavapipe: 6.95% of
  // temple's pixels one albedo step off the raster pass's; the quad's top row and left column,
  // coarse derivatives: 7.01%).
  const ivec2 q = p & ~1;
  vec3 lx0, lx1, ly0, ly1;
  onPlane(t, vec2(q.x, p.y) + 0.5, lx0);
  onPlane(t, vec2(q.x + 1, p.y) + 0.5, lx1);
  onPlane(t, vec2(p.x, q.y) + 0.5, ly0);
  onPlane(t, vec2(p.x, q.y + 1) + 0.5, ly1);

  vec4 uv[3];
  for (int k = 0; k < 3; ++k) uv[k] = materialUvs(m, c[k].uv0, c[k].uv1);
  const mat3x4 uvs = mat3x4(uv[0], uv[1], uv[2]);
  const vec4 uvHere = uvs * l, uvDx = uvs * lx1 - uvs * lx0, uvDy = uvs * ly1 - uvs * ly0;

  const mat3 normalFrom = mat3(d.normalEyeFromObject), eyeFrom = mat3(d.eyeFromObject);
  const vec3 normal = normalFrom * (mat3(c[0].normal, c[1].normal, c[2].normal) * l);
  const vec4 tangentObject = mat3x4(c[0].tangent, c[1].tangent, c[2].tangent) * l;
  const vec4 tangent = vec4(eyeFrom * tangentObject.xyz, tangentObject.w);
  // Front facing as the rasterizer decides it: the winding in framebuffer space (the sign of the
  // homogeneous determinant), counter-clockwise front unless the draw's transform mirrors.
  const bool ccw = determinant(xyw) < 0.0;
  const bool frontFacing = d.info.y != 0u ? !ccw : ccw;
  const vec3 face = t.n;

  vec4 base = m.baseColor;
  if (g.textures.x >= 0) base *= textureGrad(baseTexture, uvHere.xy, uvDx.xy, uvDy.xy);
  const vec3 N = resolvedNormal(m, g.textures.y >= 0, normal, tangent, uvHere.zw, uvDx.zw, uvDy.zw, frontFacing, face,
                                eyePosition);
  float shadow = 1.0;
  if (frame.sunEyeDirection.w > 0.0) {
    const vec4 lightClip = d.lightClipFromObject * vec4(mat3(c[0].position, c[1].position, c[2].position) * l, 1.0);
    const vec3 lc = lightClip.xyz / lightClip.w;
    shadow = textureLod(shadowMap, vec3(lc.xy * 0.5 + 0.5, lc.z), 0.0);
  }
  imageStore(outAlbedo, p, uvec4(packUnorm4x8(vec4(srgbEncode(clamp(base.rgb, 0.0, 1.0)), m.params.x)), 0u, 0u, 0u));
  imageStore(outNormal, p, packNormalTexel(m.flags.z != 0u ? encodeUnlit() : encodeNormalShadow(N, shadow)));
  imageStore(outDepth, p, uvec4(floatBitsToUint(-eyePosition.z), 0u, 0u, 0u));
#ifdef GB_PRIMITIVE_ID
  imageStore(outPrimitiveId, p, uvec4(g.info.w + triangle, 0u, 0u, 0u));  // firstPrimitiveIds counts from 1
#endif
#ifdef GB_POSITION
  vec3 relative = mat3(frame.worldFromEye) * eyePosition;
  vec4 position = vec4(POSITION == kPositionWorld ? relative + frame.worldFromEye[3].xyz : relative, 1.0);
  imageStore(outPosition, p, POSITION32 != 0 ? floatBitsToUint(position)
                                             : uvec4(packHalf2x16(position.xy), packHalf2x16(position.zw), 0u, 0u));
#endif
#ifdef GB_MOTION
  vec4 previous = frame.prevClipFromEye * vec4(eyePosition, 1.0);
  vec4 current = frame.unjitteredClipFromEye * vec4(eyePosition, 1.0);
  vec2 ndc = previous.xy / previous.w - current.xy / current.w;
  imageStore(outMotion, p, uvec4(packHalf2x16(previous.w > 0.0 ? ndc * 0.5 * frame.viewport.xy : vec2(0.0)), 0u, 0u, 0u));
#endif
}
