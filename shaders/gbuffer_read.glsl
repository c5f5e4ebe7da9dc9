// Reading the G-buffer in lighting passes: textures (two-pass) or subpass inputs (single-pass,
// GB_INPUT_ATTACHMENTS), and the eye-space position from either depth source.
#include "gbuffer_codec.glsl"

#ifdef GB_INPUT_ATTACHMENTS
layout(input_attachment_index = kInputAlbedo, set = 1, binding = kBindingAlbedo) uniform subpassInput gAlbedo;
layout(input_attachment_index = kInputNormal, set = 1, binding = kBindingNormal) uniform subpassInput gNormal;
layout(input_attachment_index = kInputDepth, set = 1, binding = kBindingDepth) uniform subpassInput gDepth;
#define GB_FETCH(t, p) subpassLoad(t)
#else
layout(set = 1, binding = kBindingAlbedo) uniform sampler2D gAlbedo;
layout(set = 1, binding = kBindingNormal) uniform sampler2D gNormal;
layout(set = 1, binding = kBindingDepth) uniform sampler2D gDepth;
#define GB_FETCH(t, p) texelFetch(t, p, 0)
#endif

struct Surface {
  bool geometry;  // false where nothing was drawn (sky)
  vec3 albedo;
  float specular;
  vec3 N;         // eye space, unit
  float shadow;   // 1 lit, 0 shadowed
  bool unlit;     // KHR_materials_unlit: albedo is the colour, N is not stored
  vec3 P;         // eye-space position
};

// Eye-space position of a pixel centre: from eye depth (USE_EYE_DEPTH) or hardware depth.
vec3 eyePosition(vec2 fragCoord, float stored) {
  vec2 ndc = fragCoord * frame.viewport.zw * 2.0 - 1.0;
  if (EYE_DEPTH != 0) return vec3(stored * (ndc + frame.eyeRay.zw) * frame.eyeRay.xy, -stored);
  vec4 e = frame.eyeFromClip * vec4(ndc, stored, 1.0);
  return e.xyz / e.w;
}

// Eye-space position from the position target: world space, or world axes around the camera.
vec3 eyeFromStoredPosition(vec3 stored) {
  mat3 eyeFromWorld = transpose(mat3(frame.worldFromEye));  // a rotation: its inverse is its transpose
  return eyeFromWorld * (POSITION == kPositionWorld ? stored - frame.worldFromEye[3].xyz : stored);
}

// Only the position (cluster bounds): false where nothing was drawn. The same values readSurface
// gives, so a shaded point always lies in the box its cluster was given.
bool readPosition(vec2 fragCoord, out vec3 P) {
  ivec2 p = ivec2(fragCoord);
  vec4 position = GB_FETCH(gDepth, p);
  float stored = position.r;
  bool geometry = POSITION != kPositionDepth ? position.w > 0.0 : (EYE_DEPTH != 0 ? stored > 0.0 : stored != farDepth());
  P = POSITION != kPositionDepth ? eyeFromStoredPosition(position.xyz) : eyePosition(fragCoord, stored);
  return geometry;
}

Surface readSurface(vec2 fragCoord) {
  ivec2 p = ivec2(fragCoord);
  Surface s;
  vec4 position = GB_FETCH(gDepth, p);
  float stored = position.r;
  if (POSITION != kPositionDepth)
    s.geometry = position.w > 0.0;
  else
    s.geometry = EYE_DEPTH != 0 ? stored > 0.0 : stored != farDepth();
  vec4 a = GB_FETCH(gAlbedo, p);
  vec4 n = GB_FETCH(gNormal, p);
  s.albedo = a.rgb;
  s.specular = a.a;
  s.N = decodeNormal(n);
  s.unlit = unlitTexel(n);
  s.shadow = n.w;
  s.P = POSITION != kPositionDepth ? eyeFromStoredPosition(position.xyz) : eyePosition(fragCoord, stored);
  return s;
}
