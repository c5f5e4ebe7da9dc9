// tiler_deferred's lighting (needs frame.glsl): a sun and three point lights, Lambert diffuse plus a
// Blinn-Phong highlight whose exponent follows roughness; metals tint the highlight by albedo.
const vec3 k_sky = vec3(0.30, 0.42, 0.62);

vec3 world_position(vec2 pixel_centre, float depth) {
  const vec2 ndc = pixel_centre * frame.viewport.zw * 2.0 - 1.0;  // y down, as the projection makes it
  const vec4 w = frame.world_from_clip * vec4(ndc, depth, 1.0);
  return w.xyz / w.w;
}

vec3 shade(vec3 albedo, float roughness, float metalness, vec3 n, vec3 p) {
  const vec3 v = normalize(frame.eye_world.xyz - p);
  const vec3 diffuse = albedo * (1.0 - metalness);
  const vec3 f0 = mix(vec3(0.04), albedo, metalness);
  const float shininess = mix(96.0, 4.0, roughness);
  vec3 sum = frame.ambient.rgb * albedo;
  {
    const vec3 l = frame.sun_toward.xyz;
    const float nl = max(dot(n, l), 0.0);
    const float spec = pow(max(dot(n, normalize(l + v)), 0.0), shininess) * nl;
    sum += frame.sun_color.rgb * (diffuse * nl + f0 * spec);
  }
  for (int i = 0; i < 3; ++i) {
    const vec3 d = frame.point_position[i].xyz - p;
    const float dist = length(d);
    const vec3 l = d / max(dist, 1e-4);
    const float fall = clamp(1.0 - dist / frame.point_position[i].w, 0.0, 1.0);
    const float nl = max(dot(n, l), 0.0);
    const float spec = pow(max(dot(n, normalize(l + v)), 0.0), shininess) * nl;
    sum += frame.point_color[i].rgb * (fall * fall) * (diffuse * nl + f0 * spec);
  }
  return sum;
}
