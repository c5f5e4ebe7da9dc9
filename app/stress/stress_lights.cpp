// Stress cases about point lights: lights at and around the camera and across the near and far
// planes, tiny and huge and empty lights, and many lights summed on one pixel.
#include <algorithm>
#include <cmath>
#include <cstdio>

#include "app/stress/stress.h"
#include "renderer/core/camera.h"

namespace gb::stress {

namespace {

struct Variant {
  const char* name;
  void (*apply)(RenderOptions&);
};
const Variant kVariants[] = {
    {"deferred per-light mask", [](RenderOptions&) {}},
    {"deferred shared mask", [](RenderOptions& o) { o.stencilMask = StencilMask::Shared; }},
    {"stencil culling off", [](RenderOptions& o) { o.stencilCulling = false; }},
    {"single-pass", [](RenderOptions& o) { o.path = Path::SinglePass; }},
    {"tiled", [](RenderOptions& o) { o.method = Method::Tiled; }},
    {"forward", [](RenderOptions& o) { o.method = Method::Forward; }},
};

PointLightDesc light(glm::dvec3 centre, double radius, double intensity = 1.0, glm::vec3 colour = glm::vec3(1.0f)) {
  PointLightDesc l;
  l.center = centre;
  l.radius = radius;
  l.intensity = intensity;
  l.color = colour;
  return l;
}

// World position of an eye-space point of the scene's camera.
glm::dvec3 worldOf(const Scene& s, glm::dvec3 eye) { return glm::dvec3(s.cameras[0].worldFromEye * glm::dvec4(eye, 1.0)); }

// The worst lighting-pass error over every lighting variant (a lost light shows as ~its share
// of the pixel: far above the bound).
void worstOverVariants(Context& c, const Scene& s, uint32_t w, uint32_t h, const std::string& label, double bound,
                       const char* metric = "lighting rel. error (worst variant), ") {
  SessionScene sr(*c.session, s);
  ReferenceCache cache(s);
  double worst = 0.0;
  std::string worstName = "-";
  for (const Variant& v : kVariants) {
    RenderOptions o;
    o.width = w;
    o.height = h;
    v.apply(o);
    FrameError e = measure(c, o, cache, label + ", " + v.name);
    // Forward shades the material's exact albedo, not the G-buffer's 8-bit sRGB one: it is
    // measured by its final colour against the reference surfaces instead.
    const ErrorStats& stat = o.method == Method::Forward ? e.hdr.relative : e.lighting.relative;
    double m = stat.count ? stat.max : NAN;
    char line[160];
    std::snprintf(line, sizeof line, "%s: %s %.3g", label.c_str(), v.name, m);
    c.progress(line);
    if (!(m <= worst)) {
      worst = m;
      worstName = v.name;
    }
  }
  c.check(metric + label, worst, bound, std::string("worst: ") + worstName);
}

}  // namespace

// Point lights whose volumes contain the camera, sit exactly at it, or cross the near or the far
// plane, each set on its own, under every lighting variant: nothing may be lost against the
// reference shading of the same G-buffer.
void lightsAtCameraCase(Context& c) {
  const uint32_t w = c.quick ? 96 : 320, h = c.quick ? 64 : 200;
  const double bound = 1e-3;
  c.state("lighting passes vs the reference shading of the GPU's own G-buffer: max relative error <= 1e-3 for "
          "every variant (deferred per-light/shared mask, stencil off, single-pass, tiled, forward)");
  Scene base = groundScene(60.0, false);
  placeCamera(base, {0, 2, 8}, {0, 0.5, 0}, 0.9, 0.5, 30.0);
  base.sky.ambient = glm::vec3(0.02f);
  const CameraDesc& cam = base.cameras[0];
  struct Set {
    const char* name;
    std::vector<PointLightDesc> lights;
  } sets[4];
  sets[0].name = "camera inside a light";
  sets[0].lights = {light(worldOf(base, {0.3, -0.2, -1.0}), 6.0, 1.0, {1.0f, 0.8f, 0.6f})};
  sets[1].name = "light exactly at the camera";
  sets[1].lights = {light(worldOf(base, {0, 0, 0}), 10.0, 2.0)};
  sets[2].name = "lights across the near plane";
  for (int i = -2; i <= 2; ++i)
    for (int j = -1; j <= 1; ++j)
      sets[2].lights.push_back(light(worldOf(base, {0.15 * i, 0.1 * j, -cam.znear}), 3.0, 1.0,
                                     {0.5f + 0.1f * i, 0.7f, 0.6f - 0.1f * j}));
  sets[3].name = "lights across the far plane";
  for (int i = -3; i <= 3; ++i)
    sets[3].lights.push_back(light(worldOf(base, {4.0 * i, -1.9, -cam.zfar}), 5.0, 3.0, {0.9f, 0.6f, 0.4f}));
  for (const Set& set : sets) {
    c.progress(set.name);
    Scene s = base;
    s.lights = set.lights;
    worstOverVariants(c, s, w, h, set.name, bound);
  }
}

// Radius 1e-4 (well under a pixel), 1e4 (every pixel and the camera inside), and lights of zero
// radius or zero intensity, which must be skipped, never divided by.
void tinyHugeLightsCase(Context& c) {
  const uint32_t w = c.quick ? 96 : 320, h = c.quick ? 64 : 200;
  c.state("huge (radius 1e4): lighting max relative error <= 1e-3 for every variant");
  c.state("tiny (radius 1e-4, on the floor): lighting max relative error <= 2^-23 * eye depth * 16 / radius "
          "(the float difference light - P against the radius)");
  c.state("zero radius and zero intensity: skipped (culled as empty: exactly 2), lighting error <= 1e-3");
  Scene base = groundScene(12.0, false);
  base.sky.ambient = glm::vec3(0.02f);
  {
    c.progress("huge light");
    Scene s = base;
    s.lights = {light({0, 3, 0}, 1e4, 0.5)};
    worstOverVariants(c, s, w, h, "radius 1e4", 1e-3);
  }
  {
    c.progress("tiny lights");
    Scene s = base;
    for (int i = 0; i < 64; ++i) {
      double x = -6.0 + 12.0 * ((i * 37) % 64) / 64.0, z = -6.0 + 12.0 * ((i * 11) % 64) / 64.0;
      s.lights.push_back(light({x, 2e-5, z}, 1e-4, 1.0));
    }
    // The distance to the camera bounds the eye-space float rounding of both points.
    glm::dvec3 eye = glm::dvec3(s.cameras[0].worldFromEye[3]);
    double farthest = glm::length(eye - glm::dvec3(6, 0, 6)) + 12.0;
    worstOverVariants(c, s, w, h, "radius 1e-4", std::ldexp(1.0, -23) * farthest * 16.0 / 1e-4);
  }
  {
    c.progress("zero radius and zero intensity");
    Scene s = base;
    s.lights = {light({0, 1, 2}, 0.0, 1.0), light({1, 1, 2}, 3.0, 0.0), light({-1, 1, 2}, 3.0, 1.0)};
    worstOverVariants(c, s, w, h, "zero radius / intensity + one light", 1e-3);
    SessionScene sr(*c.session, s);
    RenderOptions o;
    o.width = w;
    o.height = h;
    const FrameStats& st = c.session->render(o);
    c.check("lights skipped as empty, |count - 2|", std::abs(double(st.lightsCulledEmpty) - 2.0), 0.0);
  }
}

// N identical lights on one spot of the floor (N = 1, 64, 1024, 16384), summed by blending into
// each accumulation format. Exact sum: N times the single light's value (from the rgba32f frame
// of N = 1, itself checked against the reference). Each of the N blends rounds once, by up to one
// ulp where the rounding is toward zero, so the sum errs by at most N u of itself (u = 2^-23
// fp32, 2^-10 fp16); rgba8 (UNORM) rounds every blend to 1/255 and clamps at 1. fp16 sums above 65504 are counted as saturated; the tone-mapped output
// must turn them white, never NaN.
void manyLightsCase(Context& c) {
  const uint32_t size = c.quick ? 40 : 128;
  Scene s = groundScene(12.0, false);
  s.sky.ambient = glm::vec3(0.0f);
  placeCamera(s, {0, 4, 0}, {0, 0, 0}, 0.9, 0.1, 20.0);
  const PointLightDesc one = light({0.3, 0.5, 0.2}, 1.5, 160.0);  // ~63 per light at the centre
  c.state("single light (rgba32f) vs the reference: lighting max relative error <= 1e-4");
  c.state("sum of N lights vs N x single: relative error <= N u + 1e-5, u = one ulp (Vulkan lets blending round "
          "toward zero): 2^-23 fp32, 2^-10 fp16 (relative to at least 2^-14, fp16's smallest normal)");
  c.state("rgba8: |value - min(sum, 1)| <= N / 510 + 1/255; fp16 above 65504: reported; final white there");
  // N = 1 in rgba32f: the per-pixel single-light value.
  std::vector<double> single;
  {
    s.lights = {one};
    SessionScene sr(*c.session, s);
    ReferenceCache cache(s);
    RenderOptions o;
    o.width = o.height = size;
    FrameSnapshot frame;
    FrameError e = measure(c, o, cache, "N=1", nullptr, &frame);
    c.check("single light lighting rel. error", e.lighting.relative.max, 1e-4);
    const CpuImage& hdr = frame.target(Target::Hdr).image;
    for (uint32_t y = 0; y < size; ++y)
      for (uint32_t x = 0; x < size; ++x) single.push_back(hdr.value(x, y, 0));  // red channel
  }
  for (int n : {1, 64, 1024, 16384}) {
    s.lights.assign(size_t(n), one);
    SessionScene sr(*c.session, s);
    for (AccumFormat f : {AccumFormat::Rgba32f, AccumFormat::Rgba16f, AccumFormat::Rgba8}) {
      const std::string label = "N=" + std::to_string(n) + " " + name(f);
      c.progress(label);
      RenderOptions o;
      o.width = o.height = size;
      o.accumFormat = f;
      o.coverage = true;
      o.fairies = false;  // the sprites add light of their own; the sum is of the lights
      Scan scan = scanAfterFrame(*c.session, o, f == AccumFormat::Rgba16f);
      addScan(c, scan, label);
      const CpuImage& hdr = scan.frame.target(Target::Hdr).image;
      const CpuImage& fin = scan.frame.target(Target::Final).image;
      double worst = 0.0;
      uint64_t saturated = 0, overHalf = 0, notWhite = 0, lit = 0;
      for (uint32_t y = 0; y < size; ++y)
        for (uint32_t x = 0; x < size; ++x) {
          double exact = n * single[size_t(y) * size + x], v = hdr.value(x, y, 0);
          if (exact <= 0.0) continue;
          lit++;
          if (f == AccumFormat::Rgba16f && exact > 65504.0) {
            overHalf++;
            if (v >= 65504.0) {  // Inf or the largest half: saturated, and white once tone-mapped
              saturated++;
              notWhite += fin.raw(x, y, 0) != 255;
              continue;
            }
          }
          // Relative to the sum, but never below the smallest normal of the format: under it
          // fp16 holds only absolute steps of 2^-24.
          const double floor = f == AccumFormat::Rgba16f ? std::ldexp(1.0, -14) : std::ldexp(1.0, -126);
          double err = f == AccumFormat::Rgba8 ? std::abs(v - std::min(exact, 1.0))
                                               : std::abs(v - exact) / std::max(exact, floor);
          worst = std::max(worst, std::isfinite(err) ? err : INFINITY);
        }
      double u = f == AccumFormat::Rgba32f ? std::ldexp(1.0, -23) : std::ldexp(1.0, -10);
      double bound = f == AccumFormat::Rgba8 ? n / 510.0 + 1.0 / 255.0 : n * u + 1e-5;
      c.check(std::string(f == AccumFormat::Rgba8 ? "sum abs. error, " : "sum rel. error, ") + label,
              lit ? worst : NAN, bound, std::to_string(lit) + " lit px");
      if (f == AccumFormat::Rgba16f) {
        c.info("fp16 saturated px (hdr >= 65504), " + label, double(saturated),
               std::to_string(overHalf) + " px with an exact sum > 65504" +
                   (saturated ? std::string("; hdr holds ") + (scan.hdrInf ? "Inf" : "65504") : ""));
        c.check("saturated px not white in final, " + label, double(notWhite), 0.0);
      }
    }
  }
}

}  // namespace gb::stress
