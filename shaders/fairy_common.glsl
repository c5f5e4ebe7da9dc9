// A fairy sprite as fairy.vert places it: a camera-facing quad of half-size radius * params.y at
// the light, in screen space (fairy_bins, fairy_splat). The quad lies at one depth, so the
// rasterizer's interpolation of its local coordinates is affine in screen space.
layout(set = 1, binding = kBindingFairyBits, std430) buffer FairyBitsBlock { uint fairyBits[]; };

struct Sprite {
  vec2 lo, hi;    // screen positions of local (-1, -1) and (1, 1)
  float depth;    // its depth-buffer value (clip z / w)
  bool drawn;     // not clipped by the near or far plane
  vec3 color;
};

// (A rasterizer that interpolates from vertices snapped to its sub-pixel grid differs from this by
// that rounding: under 1% of a sprite's value for sprites a pixel wide, test_fairies.cpp.)
vec2 spriteScreen(vec4 clip) { return (clip.xy / clip.w * 0.5 + 0.5) * frame.viewport.xy; }

Sprite spriteAt(vec4 eyePositionRadius, vec3 color) {
  float size = eyePositionRadius.w * frame.params.y;
  vec4 a = frame.clipFromEye * vec4(eyePositionRadius.xyz + vec3(-size, -size, 0.0), 1.0);
  vec4 b = frame.clipFromEye * vec4(eyePositionRadius.xyz + vec3(size, size, 0.0), 1.0);
  Sprite s;
  s.lo = spriteScreen(a);
  s.hi = spriteScreen(b);
  s.depth = a.z / a.w;
  s.drawn = a.w > 0.0 && a.z >= 0.0 && a.z <= a.w;  // the clip volume (no depth clamp)
  s.color = color;
  return s;
}
Sprite sprite(PointLight l) { return spriteAt(l.eyePositionRadius, l.color.rgb); }

// The pixel-centre range a sprite can cover (widened by a pixel), as integer pixel bounds.
void spritePixels(Sprite s, out ivec2 p0, out ivec2 p1) {
  vec2 lo = min(s.lo, s.hi), hi = max(s.lo, s.hi);
  p0 = ivec2(floor(lo)) - 1;
  p1 = ivec2(ceil(hi)) + 1;
}
