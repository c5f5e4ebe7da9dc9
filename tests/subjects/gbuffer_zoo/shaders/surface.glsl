// Fragment side of geometry.vert: the interpolants and zoo_surface(), the material of the pixel:
// procedural albedo patterns (checker, value noise, stripes) and a procedural tangent-space normal
// map (a sin*sin bump field over uv) taken to world space through the unnormalised TBN.
layout(location = 0) in vec3 v_world;
layout(location = 1) in vec3 v_normal;
layout(location = 2) in vec3 v_tangent;
layout(location = 3) in vec3 v_bitangent;
layout(location = 4) in vec2 v_uv;
layout(location = 5) flat in uint v_object;

struct Surface {
  vec3 albedo;      // linear
  vec3 normal_raw;  // mat3(T, B, N) * n_tangent, nothing normalised
  vec3 normal;      // normalize(normal_raw), world space
  float roughness, metallic, occlusion;
  uint id;          // object index + 1
};

float zoo_hash(ivec2 c) {
  uint h = uint(c.x) * 0x8da6b343u ^ uint(c.y) * 0xd8163841u;
  h ^= h >> 15;
  h *= 0x2c1b3c6du;
  h ^= h >> 12;
  h *= 0x297a2d39u;
  h ^= h >> 15;
  return float(h >> 8) * (1.0 / 16777215.0);
}

float zoo_noise(vec2 p) {
  const ivec2 c = ivec2(floor(p));
  const vec2 f = fract(p), s = f * f * (3.0 - 2.0 * f);
  const float a = zoo_hash(c), b = zoo_hash(c + ivec2(1, 0));
  const float d = zoo_hash(c + ivec2(0, 1)), e = zoo_hash(c + ivec2(1, 1));
  return mix(mix(a, b, s.x), mix(d, e, s.x), s.y);
}

vec3 zoo_albedo(uint pattern, vec3 base, vec2 uv) {
  if (pattern == 1u) return ((int(floor(uv.x)) + int(floor(uv.y))) & 1) == 1 ? base * 0.45 : base;
  if (pattern == 2u) {
    const float n = 0.5 * zoo_noise(uv * 2.0) + 0.3 * zoo_noise(uv * 5.0) + 0.2 * zoo_noise(uv * 11.0);
    return base * (0.35 + 1.1 * n);
  }
  if (pattern == 3u) return fract(uv.x) < 0.5 ? base : vec3(0.92, 0.90, 0.84);
  return base;
}

Surface zoo_surface() {
  const ZooObject o = objects[v_object];
  const vec2 uv = v_uv * o.material.w;
  const float k = 6.2831853;
  const float h = sin(k * uv.x) * sin(k * uv.y);
  const vec2 slope = o.material.z * 0.15 * k * vec2(cos(k * uv.x) * sin(k * uv.y), sin(k * uv.x) * cos(k * uv.y));
  const vec3 n_tangent = normalize(vec3(-slope, 1.0));
  Surface s;
  s.albedo = zoo_albedo(o.info.x, o.albedo.rgb, uv);
  s.normal_raw = mat3(v_tangent, v_bitangent, v_normal) * n_tangent;
  s.normal = normalize(s.normal_raw);
  s.roughness = o.material.x;
  s.metallic = o.material.y;
  s.occlusion = 1.0 - 0.35 * min(o.material.z, 1.0) * (0.5 - 0.5 * h);
  s.id = o.info.z;
  return s;
}
