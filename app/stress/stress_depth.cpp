// Stress cases about where things are: depth ranges per depth option, and a scene far from the
// origin (camera following) per position source.
#include <cmath>
#include <cstdio>

#include "app/stress/stress.h"
#include "renderer/scene/builtin.h"

namespace gb::stress {

static std::string sci(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Positions reconstructed from each depth option against the reference, on builtin:depth-range
// (cards spaced in log over the whole range). Eye depth (R32F) and reversed float Z keep a
// relative error of a few float ulps at any range; standard Z loses precision as far/near grows:
// depth near 1 is stored with ulp 2^-24 and dz/z = (z/near) dd, so the relative error grows as
// z/near, up to far/near at the far plane. Its bound is that estimate with a factor of 4.
void depthRangeCase(Context& c) {
  const uint32_t w = c.quick ? 128 : 480, h = c.quick ? 72 : 270;
  const double ranges[3][2] = {{1e-3, 1e3}, {1e-2, 1e5}, {1.0, 1e7}};
  const double floatBound = 1e-5;  // ~80 float ulps: storage + the reconstruction's float math
  c.state("eye-depth and reversed-Z: max |P - P_ref| / eye depth <= " + sci(floatBound) + " at every range");
  c.state("standard Z (d32s8): max relative error <= 4 * 2^-24 * far/near (the rounding of depth near 1)");
  for (const auto& range : ranges) {
    const double n = range[0], f = range[1];
    Scene s = depthRangeScene(n, f);
    SessionScene sr(*c.session, s);
    ReferenceCache cache(s);
    const std::string label = sci(n) + "/" + sci(f);
    c.progress("near/far " + label);
    struct Variant {
      const char* name;
      bool eyeDepth, reversedZ;
      double bound;
    } variants[] = {{"eye-depth", true, false, floatBound},
                    {"standard-Z", false, false, 4.0 * std::ldexp(1.0, -24) * f / n},
                    {"reversed-Z", false, true, floatBound}};
    for (const Variant& v : variants) {
      RenderOptions o;
      o.width = w;
      o.height = h;
      o.lights = 0;
      o.eyeDepth = v.eyeDepth;
      o.reversedZ = v.reversedZ;
      FrameError e = measure(c, o, cache, label + " " + v.name);
      const PositionError& p = v.eyeDepth ? e.fromEyeDepth : e.fromHardwareDepth;
      char note[96];
      std::snprintf(note, sizeof note, "p99 %.3g, %llu px", p.relative.p99, (unsigned long long)p.relative.count);
      c.check(std::string("position rel. error, ") + v.name + " " + label, p.relative.count ? p.relative.max : NAN, v.bound,
              note);
    }
  }
}

// The whole scene and its camera moved by 1e3, 1e5 and 1e7 units. Transforms are formed relative
// to the camera in double before they reach the GPU, so positions from depth and a stored
// camera-space position do not change with the offset; a stored world-space fp32 position
// cannot hold better than half an ulp of the offset. Measured against the reference of the same
// view at the origin (everything the reference computes is relative to the camera).
void farFromOriginCase(Context& c) {
  const uint32_t w = c.quick ? 96 : 320, h = c.quick ? 64 : 200;
  Scene base = groundScene(12.0, true);
  generateLights(base, 12);
  ReferenceCache cache(base);
  const double offsets[] = {0.0, 1e3, 1e5, 1e7};
  const glm::dvec3 direction = glm::normalize(glm::dvec3(1.0, 0.3, -0.7));
  c.state("depth and camera-space rgba32f: max relative position error <= 1e-5 at every offset");
  c.state("world-space rgba32f: max position error <= ulp(|offset| + scene) (scene units), i.e. fp32 storage");
  c.state("shadow lit/shadowed mismatch (outside the penumbra band) <= 0.5% at every offset");
  c.state("lighting passes alone, max relative error <= 1e-3 (camera-relative sources)");
  for (double d : offsets) {
    Scene s = base;
    translateScene(s, direction * d);
    SessionScene sr(*c.session, s);
    const std::string label = "offset " + sci(d);
    c.progress(label);
    struct Variant {
      const char* name;
      PositionSource source;
      PositionSpace space;
    } variants[] = {{"depth", PositionSource::Depth, PositionSpace::World},
                    {"rgba32f camera", PositionSource::Rgba32f, PositionSpace::Camera},
                    {"rgba32f world", PositionSource::Rgba32f, PositionSpace::World}};
    for (const Variant& v : variants) {
      RenderOptions o;
      o.width = w;
      o.height = h;
      o.position = v.source;
      o.positionSpace = v.space;
      Camera refCamera = makeCamera(base.cameras[0], w, h, o.reversedZ);
      FrameError e = measure(c, o, cache, label + " " + v.name, &refCamera);
      const PositionError& p = e.used;
      if (v.source == PositionSource::Rgba32f && v.space == PositionSpace::World) {
        double far = d + base.bounds.radius() * 2.0 + 10.0;
        double ulp = double(std::nextafter(float(far), INFINITY)) - double(float(far));
        c.check(std::string("position error (units), ") + v.name + " " + label, p.absolute.max, std::max(ulp, 1e-4));
      } else {
        c.check(std::string("position rel. error, ") + v.name + " " + label, p.relative.max, 1e-5);
      }
      if (v.source == PositionSource::Depth) {
        c.check("shadow mismatch fraction, " + label, e.shadow.fraction, 0.005);
        c.check("lighting rel. error, " + label, e.lighting.relative.max, 1e-3);
      }
    }
  }
}

}  // namespace gb::stress
