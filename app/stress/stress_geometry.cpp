// Stress cases about the view and the geometry: grazing sun (shadow acne), extreme FOV and
// aspect, output sizes from 1x1 to the device maximum.
#include <sys/resource.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/stress/stress.h"

namespace gb::stress {

static std::string num(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%g", v);
  return buf;
}

// Sun elevations 90, 10, 1 and 0.1 degrees over a floor with boxes: lit/shadowed disagreements
// with the ray-traced shadow outside the penumbra band. False shadow on a lit face is acne;
// false light next to a caster is peter-panning. Reported for the default bias and for the best
// (constant, slope) pair of a small grid.
void grazingSunCase(Context& c) {
  const uint32_t w = c.quick ? 96 : 320, h = c.quick ? 64 : 200;
  const double elevations[] = {90.0, 10.0, 1.0, 0.1};
  std::vector<float> constants = c.quick ? std::vector<float>{2, 8} : std::vector<float>{0.5f, 2, 8, 32};
  std::vector<float> slopes = c.quick ? std::vector<float>{1, 2.5f, 6} : std::vector<float>{0, 1, 2.5f, 6, 16};
  const std::vector<float> clamps = {0.01f, 0.1f, 0.0f};  // 0: no clamp
  c.state("default bias: acne (false shadow) fraction <= 1% at 90, 10 and 1 degrees; at 0.1 degrees reported");
  c.state("best bias of the search (constant x slope x clamp 0.01, 0.1, none): mismatch fraction <= 1% everywhere");
  for (double elevation : elevations) {
    Scene s = groundScene(12.0, true);
    const double e = elevation * M_PI / 180.0, azimuth = 35.0 * M_PI / 180.0;
    s.sun.toSun = glm::dvec3(std::cos(e) * std::cos(azimuth), std::sin(e), std::cos(e) * std::sin(azimuth));
    SessionScene sr(*c.session, s);
    ReferenceCache cache(s);
    const std::string label = num(elevation) + " deg";
    c.progress("sun " + label);
    RenderOptions o;
    o.width = w;
    o.height = h;
    o.lights = 0;
    FrameError def = measure(c, o, cache, "sun " + label);
    auto acne = [](const FrameError& f) {
      return f.shadow.compared ? double(f.shadow.falseShadow) / f.shadow.compared : 0.0;
    };
    char note[128];
    std::snprintf(note, sizeof note, "mismatch %.4g (false light %llu px) of %llu px", def.shadow.fraction,
                  (unsigned long long)def.shadow.falseLight, (unsigned long long)def.shadow.compared);
    if (elevation >= 1.0)
      c.check("acne fraction, default bias, sun " + label, acne(def), 0.01, note);
    else
      c.info("acne fraction, default bias, sun " + label, acne(def), note);
    double best = def.shadow.fraction;
    float bestC = o.shadowBiasConstant, bestS = o.shadowBiasSlope, bestClamp = o.shadowBiasClamp;
    for (float cl : clamps)
      for (float k : constants)
        for (float sl : slopes) {
          RenderOptions b = o;
          b.shadowBiasConstant = k;
          b.shadowBiasSlope = sl;
          b.shadowBiasClamp = cl;
          FrameError f = measure(c, b, cache, "sun " + label + " bias " + num(k) + "/" + num(sl) + "/" + num(cl));
          if (f.shadow.fraction < best) {
            best = f.shadow.fraction;
            bestC = k;
            bestS = sl;
            bestClamp = cl;
          }
        }
    c.check("mismatch fraction, best bias, sun " + label, best, 0.01,
            "constant " + num(bestC) + ", slope " + num(bestS) + ", clamp " + num(bestClamp));
  }
}

// Vertical FOV of 1 and 179 degrees, and a 100:1 output: positions, lighting and shadows
// against the reference.
void extremeFovCase(Context& c) {
  c.state("max |P - P_ref| / eye depth <= 1e-5 * (corner ray length / eye depth): float error is relative to "
          "the distance, which reaches sqrt(1 + t^2 + (aspect t)^2) eye depths, t = tan(yfov / 2)");
  c.state("lighting max relative error <= 1e-3, shadow mismatch <= 1%");
  Scene base = groundScene(40.0, true);
  generateLights(base, 16);
  struct Shot {
    const char* name;
    double yfov;
    uint32_t w, h;
  } shots[] = {{"vertical FOV 1 deg", M_PI / 180.0, c.quick ? 64u : 256u, c.quick ? 48u : 192u},
               {"vertical FOV 179 deg", 179.0 * M_PI / 180.0, c.quick ? 64u : 256u, c.quick ? 48u : 192u},
               {"aspect 100:1", 0.9, c.quick ? 400u : 1200u, c.quick ? 4u : 12u}};
  for (const Shot& v : shots) {
    c.progress(v.name);
    Scene s = base;
    placeCamera(s, {0, 4, 9}, {0, 0.8, 0}, v.yfov, 0.1, 200.0);
    SessionScene sr(*c.session, s);
    ReferenceCache cache(s);
    RenderOptions o;
    o.width = v.w;
    o.height = v.h;
    FrameError e = measure(c, o, cache, v.name);
    const double t = std::tan(v.yfov * 0.5), aspect = double(v.w) / v.h;
    c.check(std::string("position rel. error, ") + v.name, e.used.relative.count ? e.used.relative.max : NAN,
            1e-5 * std::sqrt(1.0 + t * t + aspect * aspect * t * t), std::to_string(e.surface) + " surface px");
    c.check(std::string("lighting rel. error, ") + v.name, e.lighting.relative.max, 1e-3);
    c.check(std::string("shadow mismatch fraction, ") + v.name, e.shadow.fraction, 0.01);
  }
}

static double peakRssMiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return double(u.ru_maxrss) / 1024.0;  // kilobytes on Linux
}

// 1x1, 3x2 and 8192x8192 (the device maximum if smaller; 1024x1024 in the quick run). The small
// ones are measured against the reference; the large one renders with every target read back,
// or, when the device cannot hold it, fails before allocating with the message the commands print.
void sizesCase(Context& c) {
  c.state("1x1, 3x2: max relative position error <= 1e-5, lighting max relative error <= 1e-3");
  c.state("large: renders with every target read back, or is refused before allocating (frameTooLarge)");
  Scene s = groundScene(10.0, true);
  generateLights(s, 16);
  ReferenceCache cache(s);
  for (auto [w, h] : {std::pair<uint32_t, uint32_t>{1, 1}, {3, 2}}) {
    const std::string label = std::to_string(w) + "x" + std::to_string(h);
    c.progress(label);
    SessionScene sr(*c.session, s);
    RenderOptions o;
    o.width = w;
    o.height = h;
    FrameError e = measure(c, o, cache, label);
    c.check("position rel. error, " + label, e.used.relative.count ? e.used.relative.max : 0.0, 1e-5,
            std::to_string(e.surface) + " surface px");
    c.check("lighting rel. error, " + label, e.lighting.relative.max, 1e-3);
  }
  SessionScene large(*c.session, s);
  const uint32_t maxDim = c.session->maxImageDimension();
  const uint32_t side = std::min<uint32_t>(c.quick ? 1024 : 8192, maxDim);
  std::string label = std::to_string(side) + "x" + std::to_string(side);
  RenderOptions o;
  o.width = o.height = side;
  // Beyond the device's limit the check must refuse (and name --size) without allocating.
  RenderOptions over = o;
  over.width = maxDim + 1;
  std::string overWhy = c.session->tooLarge(over);
  c.check("size over the device limit refused with a message (0 = yes)", overWhy.empty() ? 1.0 : 0.0, 0.0, overWhy);
  std::string why = c.session->tooLarge(o, c.session->readbackBytes(o));
  c.info("targets MiB, " + label, double(c.session->targetBytes(o)) / (1 << 20));
  if (!why.empty()) {
    c.info("refused before allocating, " + label, 1.0, why);
    // Then the largest power-of-two square this device holds is rendered instead.
    uint32_t fits = side;
    do {
      fits /= 2;
      o.width = o.height = fits;
    } while (fits > 1 && !c.session->tooLarge(o, c.session->readbackBytes(o)).empty());
    label = std::to_string(fits) + "x" + std::to_string(fits);
    c.info("largest square that fits, side", double(fits));
  }
  c.progress(label + " (every target read back)");
  double before = peakRssMiB();
  {
    Scan scan = scanAfterFrame(*c.session, o);
    addScan(c, scan, label);
    const CpuImage& fin = scan.frame.target(Target::Final).image;
    c.check("final rendered at " + label + " (size mismatch)", fin.width == o.width && fin.height == o.height ? 0.0 : 1.0,
            0.0);
  }
  c.info("peak RSS MiB (process), " + label, peakRssMiB(), "before this size: " + num(std::round(before)) + " MiB");
}

}  // namespace gb::stress
