// Shading shared by the lighting passes and the forward pass: Lambert + normalised Blinn-Phong, a sun
// and four point lights with a windowed inverse-square falloff, ambient scaled by occlusion. Positions
// and vectors are in one space; `space_from_world` takes the lights (world) there. Also the sky, the
// screen-space helpers and the tone maps.
vec3 zoo_term(vec3 n, vec3 v, vec3 l, vec3 diffuse, vec3 f0, float shininess) {
  const float nl = max(dot(n, l), 0.0);
  const vec3 h = normalize(l + v);
  const float spec = pow(max(dot(n, h), 0.0), shininess) * (shininess + 8.0) / 25.1327;
  return nl * (diffuse + f0 * spec);
}

vec3 zoo_shade(vec3 p, vec3 n, vec3 eye, vec3 albedo, float roughness, float metallic, float occlusion,
               mat4 space_from_world) {
  const vec3 v = normalize(eye - p);
  const vec3 diffuse = albedo * (1.0 - metallic), f0 = mix(vec3(0.04), albedo, metallic);
  const float shininess = mix(200.0, 6.0, roughness);
  vec3 sum = lights.ambient.rgb * albedo * occlusion;
  const vec3 sun = normalize(mat3(space_from_world) * lights.sun_dir.xyz);
  sum += lights.sun_color.rgb * zoo_term(n, v, sun, diffuse, f0, shininess);
  for (int i = 0; i < 4; ++i) {
    const vec3 d = (space_from_world * vec4(lights.point_pos[i].xyz, 1.0)).xyz - p;
    const float dist = length(d), w = clamp(1.0 - pow(dist / lights.point_pos[i].w, 4.0), 0.0, 1.0);
    sum += lights.point_color[i].rgb * (w * w / (1.0 + dist * dist)) * zoo_term(n, v, d / dist, diffuse, f0, shininess);
  }
  return sum;
}

// The sky where no surface was drawn: row 0 (the top) zenith blue, the bottom row pale.
vec3 zoo_sky(float height) {
  return mix(vec3(0.22, 0.34, 0.62), vec3(0.62, 0.70, 0.82), gl_FragCoord.y / height);
}

// Vulkan NDC xy of this pixel's centre (y down, as the image rows).
vec2 zoo_ndc(vec2 size) { return gl_FragCoord.xy / size * 2.0 - 1.0; }

vec3 zoo_aces(vec3 x) { return clamp(x * (2.51 * x + 0.03) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0); }
vec3 zoo_reinhard(vec3 x) {
  const float l = dot(x, vec3(0.2126, 0.7152, 0.0722));
  return clamp(x / (1.0 + l), 0.0, 1.0);
}
vec3 zoo_expo(vec3 x) { return 1.0 - exp(-1.4 * x); }
