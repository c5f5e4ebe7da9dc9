// The sky's colour by normalized device coordinates: a procedural gradient by world-space view
// direction plus the sun's disc. One function for the skybox pass (sky.frag) and the compute
// lighting passes, which write the sky where no geometry was drawn (no raster pass for it).
vec3 skyColor(vec2 ndc) {
  vec4 e = frame.eyeFromClip * vec4(ndc, 0.5, 1.0);
  vec3 dir = normalize(mat3(frame.worldFromEye) * (e.xyz / e.w));
  float h = dir.y;
  // One pow and one mix per pixel (a CPU device evaluates both sides of a per-pixel branch).
  const bool up = h >= 0.0;
  vec3 c = mix(frame.skyHorizon.rgb, up ? frame.skyZenith.rgb : frame.skyGround.rgb, pow(abs(h), up ? 0.6 : 0.4));
  // The sun's disc, so shadows have a visible cause.
  if (frame.sunEyeDirection.w > 0.0) {
    vec3 toSun = normalize(mat3(frame.worldFromEye) * frame.sunEyeDirection.xyz);
    float d = dot(dir, toSun);
    // The glow: d^256 as eight squarings (a CPU device's pow is an exp2 and a log2 per pixel).
    float glow = max(d, 0.0);
    for (int i = 0; i < 8; ++i) glow *= glow;
    c += frame.sunColor.rgb * (smoothstep(0.9995, 0.9998, d) * 4.0 + glow * 0.3);
  }
  return c;
}

// Whether the frame draws a sky (frame.skyHorizon.w, from RenderOptions::sky).
bool skyEnabled() { return frame.skyHorizon.w > 0.0; }
