// Material evaluation shared by the G-buffer, shadow and forward passes. The material's textures
// are pushed per draw (a white / flat texture stands in when the material has none). `uvs` are
// the vertex stage's materialUvs() (common.glsl): xy base colour, zw normal texture.
layout(set = 1, binding = kBindingBaseColorTexture) uniform sampler2D baseColorTexture;
layout(set = 1, binding = kBindingNormalTexture) uniform sampler2D normalTexture;

// Without a base-colour texture (the BASE_TEXTURE 0 variant) the white stand-in would multiply by
// exactly 1: it is not sampled, which a CPU device's filtering makes costly (docs/performance.md).
vec4 baseColor(Material m, vec4 uvs) {
  return BASE_TEXTURE != 0 ? m.baseColor * texture(baseColorTexture, uvs.xy) : m.baseColor;
}

// Unit eye-space normal: interpolated, flipped for back faces of double-sided materials,
// perturbed by the normal texture in the NORMAL_MAP pipeline variant. A normal without a
// direction (zero-length vertex normals, or opposite ones cancelling where they are
// interpolated) is replaced by the face's normal toward the camera: normalize(0) is NaN, and
// it would reach every lighting pass (found by gblens stress, degenerate-geometry).
vec3 surfaceNormal(Material m, vec3 normal, vec4 tangent, vec4 uvs, bool frontFacing, vec3 eyePosition) {
  vec3 g = cross(dFdx(eyePosition), dFdy(eyePosition));  // outside the branch: derivatives need the whole quad
  vec3 N;
  if (dot(normal, normal) > 1e-24) {
    N = normalize(normal);
    if (!frontFacing) N = -N;
  } else {
    N = dot(g, g) > 0.0 ? normalize(dot(g, eyePosition) < 0.0 ? g : -g) : vec3(0.0, 0.0, 1.0);
  }
  if (NORMAL_MAP != 0) {
    vec3 t = tangent.xyz - N * dot(N, tangent.xyz);
    if (dot(t, t) > 1e-20) {
      vec3 T = normalize(t);
      vec3 B = cross(N, T) * (tangent.w < 0.0 ? -1.0 : 1.0);
      vec3 tn = texture(normalTexture, uvs.zw).xyz * 2.0 - 1.0;
      tn.xy *= m.params.z;
      vec3 n = T * tn.x + B * tn.y + N * tn.z;
      if (dot(n, n) > 1e-20) N = normalize(n);
    }
  }
  return N;
}
