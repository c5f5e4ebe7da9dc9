// Per-quantity error of a GPU frame vs the reference (see error.h), and its error images.
#include "views/analysis/error.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/assert.h"
#include "renderer/core/codec.h"
#include "renderer/core/decode.h"
#include "renderer/core/statistics.h"
#include "views/analysis/visualize.h"

namespace gb {

ErrorStats errorStats(std::vector<double> v) {
  ErrorStats s;
  s.count = v.size();
  if (v.empty()) return s;
  double sum = 0.0, sq = 0.0;
  for (double x : v) {
    sum += x;
    sq += x * x;
    s.max = std::max(s.max, x);
  }
  s.mean = sum / v.size();
  s.rms = std::sqrt(sq / v.size());
  s.p99 = percentile(std::move(v), 0.99);
  return s;
}

static double linearToSrgb(double v) {
  v = std::clamp(v, 0.0, 1.0);
  return v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
}

static double ulpOf(float f) { return double(std::nextafter(std::abs(f), INFINITY)) - std::abs(f); }

static double angleDeg(const glm::dvec3& a, const glm::dvec3& b) {
  return std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)) * 180.0 / M_PI;
}

namespace {

struct PositionSamples {
  std::vector<double> rel, abs;
  void add(const glm::dvec3& p, const glm::dvec3& ref, double depth) {
    double e = glm::length(p - ref);
    abs.push_back(e);
    rel.push_back(e / depth);
  }
  PositionError stats() { return {errorStats(std::move(rel)), errorStats(std::move(abs))}; }
};

// Per-pixel samples of every per-surface figure, summarised at the end.
struct Samples {
  std::vector<double> eyeBeyond;  // position from eye depth beyond the rasterization allowance
  std::vector<double> normal, albedoU, albedoT, spec, depthRel, depthUlps, hdrAbs, hdrRel, hdrAbsU, hdrRelU;
  PositionSamples fromEye, fromHw, fromPos, used;
};

// One pixel of the GPU frame as the lighting passes saw it (gbuffer_read.glsl), and its stored
// depths and reconstructions.
struct GpuPixel {
  reference::ShadingInput in;
  float eyeDepth = 0.0f, hwDepth = 0.0f;
  glm::dvec3 pEye{0.0}, pHw{0.0}, pPos{0.0};
  DecodedNormal n;
};

GpuPixel readGpuPixel(const FrameSnapshot& g, uint32_t x, uint32_t y, bool storedPosition) {
  const RenderOptions& o = g.options;
  const CpuImage& as = g.target(Target::AlbedoSpecular).image;
  GpuPixel p;
  p.eyeDepth = float(g.target(Target::Depth).image.value(x, y, 0));
  p.hwDepth = float(g.target(Target::DepthStencil).image.value(x, y, 0));
  p.pEye = shaderEyeFromEyeDepth(g.frameData, x, y, p.eyeDepth);
  p.pHw = shaderEyeFromHardwareDepth(g.frameData, x, y, p.hwDepth);
  bool posGeometry = false;
  if (storedPosition) {
    const CpuImage& pos = g.target(Target::Position).image;
    glm::vec3 stored(pos.value(x, y, 0), pos.value(x, y, 1), pos.value(x, y, 2));
    p.pPos = shaderEyeFromStoredPosition(g.frameData, stored, o.positionSpace);
    posGeometry = pos.value(x, y, 3) > 0.0;
  }
  const float far = o.reversedZ ? 0.0f : 1.0f;
  if (storedPosition) {
    p.in.geometry = posGeometry;
    p.in.P = p.pPos;
  } else if (o.eyeDepth) {
    p.in.geometry = p.eyeDepth > 0.0f;
    p.in.P = p.pEye;
  } else {
    p.in.geometry = p.hwDepth != far;
    p.in.P = p.pHw;
  }
  // The normal and the shadow term through the frame's layout (the one decoder, decode.h).
  const NormalSample n = decodeNormal(g, *g.layout.find(QuantityKind::Normal), x, y);
  p.n.unit = n.unit;
  p.n.stored = n.stored;
  p.n.shadow = decodeScalar(g, *g.layout.find(QuantityKind::Shadow), x, y);
  p.in.N = p.n.unit;
  p.in.unlit = unlitTexel(g.target(Target::NormalShadow).image, x, y, o.normalFormat);
  for (int c = 0; c < 3; ++c)
    p.in.albedo[c] = g.srgbDecode.empty() ? as.value(x, y, c) : double(g.srgbDecode[as.raw(x, y, c)]);
  p.in.specular = as.value(x, y, 3);
  p.in.shadow = p.n.shadow;
  return p;
}

// Sky, surface, silhouette (another triangle) or geometry on one side only.
PixelClass classify(const FrameSnapshot& g, const GpuPixel& p, const reference::Surface& r, bool ids, uint32_t x,
                    uint32_t y) {
  const bool gpuHit = p.eyeDepth > 0.0f;
  if (!gpuHit && !r.hit) return PixelClass::Sky;
  if (gpuHit != r.hit) return gpuHit ? PixelClass::CoverageOnlyGpu : PixelClass::CoverageOnlyReference;
  bool same = ids ? g.target(Target::PrimitiveId).image.raw(x, y, 0) == r.primitiveId
                  : std::abs(p.eyeDepth - r.eyeDepth) <= 1e-3 * r.eyeDepth;
  return same ? PixelClass::Surface : PixelClass::Silhouette;
}

// Lit/shadowed state where it matters, outside the penumbra band.
void measureShadow(FrameError& e, size_t i, const GpuPixel& p, const reference::Surface& r, bool inBand) {
  if (r.sunVisible < 0) {
    e.shadowClass[i] = ShadowClass::NotCompared;
    e.shadow.notCompared++;
    return;
  }
  bool gpuLit = p.n.shadow > 0.5, refLit = r.sunVisible == 1;
  if (inBand) {
    e.shadowClass[i] = ShadowClass::Band;
    e.shadow.band++;
    e.shadow.bandMismatched += gpuLit != refLit;
  } else if (gpuLit == refLit) {
    e.shadow.compared++;
    e.shadowClass[i] = gpuLit ? ShadowClass::AgreeLit : ShadowClass::AgreeShadowed;
  } else {
    e.shadow.compared++;
    e.shadow.mismatched++;
    e.shadowClass[i] = gpuLit ? ShadowClass::FalseLight : ShadowClass::FalseShadow;
    (gpuLit ? e.shadow.falseLight : e.shadow.falseShadow)++;
  }
}

// Every per-surface figure of one surface pixel.
void measureSurface(FrameError& e, Samples& s, const FrameSnapshot& g, const ReferenceView& ref, const GpuPixel& p,
                    uint32_t x, uint32_t y) {
  const size_t i = size_t(y) * e.width + x;
  const reference::Surface& r = ref.frame->at(x, y);
  const CpuImage& as = g.target(Target::AlbedoSpecular).image;
  if (r.unlit || p.in.unlit) {
    // Unlit surfaces store no normal: counted, and where the two disagree, a mismatch.
    e.unlit++;
    e.unlitMismatched += r.unlit != p.in.unlit;
  } else {
    double nd = angleDeg(p.n.unit, r.normal);
    s.normal.push_back(nd);
    e.normalErrorDeg[i] = float(nd);
  }
  double a = 0.0;
  for (int c = 0; c < 3; ++c) a = std::max(a, std::abs(double(as.raw(x, y, c)) - linearToSrgb(r.albedo[c]) * 255.0));
  (r.textured ? s.albedoT : s.albedoU).push_back(a);
  s.spec.push_back(std::abs(double(as.raw(x, y, 3)) - r.specular * 255.0));
  s.depthRel.push_back(std::abs(p.eyeDepth - r.eyeDepth) / r.eyeDepth);
  s.depthUlps.push_back(std::abs(p.eyeDepth - r.eyeDepth) / ulpOf(float(r.eyeDepth)));
  s.fromEye.add(p.pEye, r.eye, r.eyeDepth);
  e.eyeDepthPositionRelative[i] = float(s.fromEye.rel.back());
  s.eyeBeyond.push_back(std::max(0.0, s.fromEye.rel.back() - placementAllowance(r, e.width, e.height)));
  s.fromHw.add(p.pHw, r.eye, r.eyeDepth);
  if (e.storedPosition) s.fromPos.add(p.pPos, r.eye, r.eyeDepth);
  s.used.add(p.in.P, r.eye, r.eyeDepth);
  const bool inBand = (*ref.band)[i];
  measureShadow(e, i, p, r, inBand);

  // Final HDR colour vs the reference's.
  const CpuImage& hdr = g.target(Target::Hdr).image;
  const glm::dvec3& rc = ref.shaded->hdr[i];
  double dAbs = 0.0, rMax = 0.0;
  for (int c = 0; c < 3; ++c) {
    dAbs = std::max(dAbs, std::abs(hdr.value(x, y, c) - rc[c]));
    rMax = std::max(rMax, std::abs(rc[c]));
  }
  double dRel = dAbs / std::max(rMax, 1e-3);
  s.hdrAbs.push_back(dAbs);
  s.hdrRel.push_back(dRel);
  e.hdrRelative[i] = float(dRel);
  if (!r.textured && !inBand) {
    s.hdrAbsU.push_back(dAbs);
    s.hdrRelU.push_back(dRel);
  }
}

void summarise(FrameError& e, Samples& s) {
  e.normalDeg = errorStats(std::move(s.normal));
  e.albedoUntextured = errorStats(std::move(s.albedoU));
  e.albedoTextured = errorStats(std::move(s.albedoT));
  e.specular = errorStats(std::move(s.spec));
  e.eyeDepthRelative = errorStats(std::move(s.depthRel));
  e.eyeDepthUlps = errorStats(std::move(s.depthUlps));
  e.fromEyeDepth = s.fromEye.stats();
  e.fromEyeDepthBeyondPlacement = errorStats(std::move(s.eyeBeyond));
  e.fromHardwareDepth = s.fromHw.stats();
  e.fromPosition = s.fromPos.stats();
  e.used = s.used.stats();
  e.shadow.fraction = e.shadow.compared ? double(e.shadow.mismatched) / e.shadow.compared : 0.0;
  uint64_t all = e.shadow.compared + e.shadow.band;
  e.shadow.fractionWithBand = all ? double(e.shadow.mismatched + e.shadow.bandMismatched) / all : 0.0;
  e.hdr = {errorStats(std::move(s.hdrAbs)), errorStats(std::move(s.hdrRel))};
  e.hdrUntexturedOutsideBand = {errorStats(std::move(s.hdrAbsU)), errorStats(std::move(s.hdrRelU))};
}

// The lighting passes alone: the same formulas in double on the GPU's own G-buffer, with the
// lights and sun as uploaded. What remains is shading arithmetic and accumulation rounding.
void measureLightingPasses(FrameError& e, const FrameSnapshot& g, const reference::Frame& rf,
                           const std::vector<reference::ShadingInput>& gpuInputs, unsigned threads) {
  std::vector<reference::Light> lights;
  for (const gpu::PointLight& l : g.eyeLights) {
    reference::Light rl{glm::dvec3(l.eyePositionRadius), l.eyePositionRadius.w, glm::dvec3(l.color)};
    if (rl.radius > 0.0 && glm::dot(rl.color, rl.color) > 0.0) lights.push_back(rl);
  }
  reference::Sun sun;
  sun.enabled = g.frameData.sunEyeDirection.w > 0.0f;
  sun.toSunEye = glm::dvec3(g.frameData.sunEyeDirection);
  sun.color = glm::dvec3(g.frameData.sunColor);
  sun.ambient = glm::dvec3(g.frameData.ambientColor);
  reference::Shaded s = reference::shade(gpuInputs, rf.camera, lights, sun, threads);
  const CpuImage& hdr = g.target(Target::Hdr).image;
  std::vector<double> lRel, lPer;
  for (uint32_t y = 0; y < e.height; ++y)
    for (uint32_t x = 0; x < e.width; ++x) {
      size_t i = size_t(y) * e.width + x;
      if (!gpuInputs[i].geometry) continue;
      double per = 0.0, rMax = 0.0, dMax = 0.0;
      for (int c = 0; c < 3; ++c) {
        double d = std::abs(hdr.value(x, y, c) - s.hdr[i][c]);
        dMax = std::max(dMax, d);
        rMax = std::max(rMax, std::abs(s.hdr[i][c]));
        // Below 2^-14 (the smallest normal half) relative precision is not representable in
        // fp16: such sums are measured against 2^-14.
        per = std::max(per, d / (std::max(s.count[i], 1u) * std::max(s.absSum[i][c], std::ldexp(1.0, -14))));
      }
      lRel.push_back(dMax / std::max(rMax, 1e-3));
      lPer.push_back(per);
      e.lightingPerContribution[i] = float(per);
      e.lighting.maxContributions = std::max(e.lighting.maxContributions, s.count[i]);
    }
  e.lighting.relative = errorStats(std::move(lRel));
  e.lighting.perContribution = errorStats(std::move(lPer));
}

}  // namespace

double lightingBoundPerContribution(AccumFormat f) {
  const double lobe = 32.0 * 6.0 * std::ldexp(1.0, -24);
  switch (f) {
    case AccumFormat::Rgba16f: return std::ldexp(1.0, -10) + lobe;
    case AccumFormat::Rgba32f: return std::ldexp(1.0, -23) + lobe;
    case AccumFormat::Rgba8: return std::ldexp(1.0, -8) + lobe;
  }
  return lobe;
}

double placementAllowance(const reference::Surface& s, uint32_t width, uint32_t height) {
  const double extent = std::max(s.screenExtent, double(std::max(width, height)));
  return std::ldexp(1.0, -24) * (3.0 * s.vertexTerms + 2.0 * extent * s.eyeDepthChange) / s.eyeDepth;
}

std::vector<Target> measuredTargets(const RenderOptions& o) {
  std::vector<Target> t = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth, Target::DepthStencil,
                           Target::Hdr};
  if (o.position != PositionSource::Depth) t.push_back(Target::Position);
  if (o.primitiveId) t.push_back(Target::PrimitiveId);
  return t;
}

FrameError measureError(const FrameSnapshot& g, const ReferenceView& ref, unsigned threads) {
  const reference::Frame& rf = *ref.frame;
  const uint32_t w = rf.camera.width, h = rf.camera.height;
  for (Target t : {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth, Target::DepthStencil, Target::Hdr})
    GB_ASSERT(g.target(t).present() && g.target(t).whole());
  FrameError e;
  e.width = w;
  e.height = h;
  e.primitiveIds = g.target(Target::PrimitiveId).present() && g.target(Target::PrimitiveId).image.width == w;
  e.storedPosition = g.target(Target::Position).present() && g.options.position != PositionSource::Depth;
  e.pixelClass.assign(size_t(w) * h, PixelClass::Sky);
  e.shadowClass.assign(size_t(w) * h, ShadowClass::None);
  e.normalErrorDeg.assign(size_t(w) * h, 0.0f);
  e.hdrRelative.assign(size_t(w) * h, 0.0f);
  e.eyeDepthPositionRelative.assign(size_t(w) * h, 0.0f);
  e.lightingPerContribution.assign(size_t(w) * h, 0.0f);
  Samples samples;
  std::vector<reference::ShadingInput> gpuInputs(size_t(w) * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      GpuPixel p = readGpuPixel(g, x, y, e.storedPosition);
      gpuInputs[i] = p.in;
      PixelClass c = classify(g, p, rf.at(x, y), e.primitiveIds, x, y);
      e.pixelClass[i] = c;
      switch (c) {
        case PixelClass::Sky: e.sky++; break;
        case PixelClass::CoverageOnlyGpu: e.coverageOnlyGpu++; break;
        case PixelClass::CoverageOnlyReference: e.coverageOnlyReference++; break;
        case PixelClass::Silhouette: e.silhouette++; break;
        case PixelClass::Surface:
          e.surface++;
          measureSurface(e, samples, g, ref, p, x, y);
          break;
      }
    }
  summarise(e, samples);
  measureLightingPasses(e, g, rf, gpuInputs, threads);
  if (!g.srgbDecode.empty()) {
    e.srgbDecodeMaxRelative = 0.0;
    for (int b = 1; b < 256; ++b) {
      double exact = srgbToLinear(b / 255.0);
      e.srgbDecodeMaxRelative = std::max(e.srgbDecodeMaxRelative, std::abs(g.srgbDecode[b] - exact) / exact);
    }
  }
  return e;
}

nlohmann::json errorJson(const ErrorStats& s) {
  return {{"count", s.count}, {"max", s.max}, {"mean", s.mean}, {"rms", s.rms}, {"p99", s.p99}};
}

static nlohmann::json positionJson(const PositionError& p) {
  return {{"relative", errorJson(p.relative)}, {"scene_units", errorJson(p.absolute)}};
}

nlohmann::json errorJson(const FrameError& e) {
  nlohmann::json j;
  j["pixels"] = {{"total", uint64_t(e.width) * e.height},
                 {"surface", e.surface},
                 {"sky", e.sky},
                 {"silhouette", e.silhouette + e.coverageOnlyGpu + e.coverageOnlyReference},
                 {"silhouette_other_triangle", e.silhouette},
                 {"silhouette_only_gpu", e.coverageOnlyGpu},
                 {"silhouette_only_reference", e.coverageOnlyReference},
                 {"silhouettes_from", e.primitiveIds ? "primitive_id" : "depth difference > 1e-3 (no primitive_id)"},
                 {"unlit", e.unlit},
                 {"unlit_mismatched", e.unlitMismatched}};
  j["normal_deg"] = errorJson(e.normalDeg);
  j["albedo_steps"] = {{"untextured", errorJson(e.albedoUntextured)}, {"textured", errorJson(e.albedoTextured)}};
  j["specular_steps"] = errorJson(e.specular);
  j["eye_depth"] = {{"relative", errorJson(e.eyeDepthRelative)}, {"ulps", errorJson(e.eyeDepthUlps)}};
  nlohmann::json pos = {{"eye_depth", positionJson(e.fromEyeDepth)}, {"hardware_depth", positionJson(e.fromHardwareDepth)}};
  pos["eye_depth"]["beyond_placement"] = errorJson(e.fromEyeDepthBeyondPlacement);
  if (e.storedPosition) pos["stored"] = positionJson(e.fromPosition);
  pos["used"] = positionJson(e.used);
  j["position"] = pos;
  j["shadow"] = {{"compared", e.shadow.compared},
                 {"mismatched", e.shadow.mismatched},
                 {"fraction", e.shadow.fraction},
                 {"false_shadow", e.shadow.falseShadow},
                 {"false_light", e.shadow.falseLight},
                 {"band", e.shadow.band},
                 {"band_mismatched", e.shadow.bandMismatched},
                 {"fraction_with_band", e.shadow.fractionWithBand},
                 {"not_compared", e.shadow.notCompared}};
  j["hdr"] = {{"absolute", errorJson(e.hdr.absolute)},
              {"relative", errorJson(e.hdr.relative)},
              {"untextured_outside_band",
               {{"absolute", errorJson(e.hdrUntexturedOutsideBand.absolute)},
                {"relative", errorJson(e.hdrUntexturedOutsideBand.relative)}}}};
  j["lighting"] = {{"relative", errorJson(e.lighting.relative)},
                   {"per_contribution", errorJson(e.lighting.perContribution)},
                   {"max_contributions", e.lighting.maxContributions},
                   {"device_srgb_decode_max_relative", e.srgbDecodeMaxRelative}};
  return j;
}

// ---- images ----------------------------------------------------------------------------------

static Rgba8Image blank(const FrameError& e) {
  Rgba8Image img;
  img.width = e.width;
  img.height = e.height;
  img.pixels.assign(size_t(e.width) * e.height * 4, 255);
  for (size_t i = 0; i < size_t(e.width) * e.height; ++i) img.pixels[i * 4] = img.pixels[i * 4 + 1] = img.pixels[i * 4 + 2] = 0;
  return img;
}
static void put(Rgba8Image& img, size_t i, uint8_t r, uint8_t g, uint8_t b) {
  img.pixels[i * 4] = r;
  img.pixels[i * 4 + 1] = g;
  img.pixels[i * 4 + 2] = b;
}

// Legend: agree lit light grey, agree shadowed dark grey, band yellow, GPU shadowed but the ray
// reaches the sun (acne, over-shadowing) red, GPU lit but the ray is blocked (light leak,
// peter-panning) blue, not compared (faces away from the sun) dark blue-grey, silhouettes magenta.
Rgba8Image shadowErrorImage(const FrameError& e) {
  Rgba8Image img = blank(e);
  for (size_t i = 0; i < e.shadowClass.size(); ++i) {
    if (e.pixelClass[i] != PixelClass::Surface && e.pixelClass[i] != PixelClass::Sky) put(img, i, 160, 0, 160);
    switch (e.shadowClass[i]) {
      case ShadowClass::AgreeLit: put(img, i, 200, 200, 200); break;
      case ShadowClass::AgreeShadowed: put(img, i, 70, 70, 70); break;
      case ShadowClass::Band: put(img, i, 200, 180, 40); break;
      case ShadowClass::FalseShadow: put(img, i, 255, 0, 0); break;
      case ShadowClass::FalseLight: put(img, i, 0, 90, 255); break;
      case ShadowClass::NotCompared: put(img, i, 40, 45, 70); break;
      case ShadowClass::None: break;
    }
  }
  return img;
}

// Legend: surfaces grey, silhouettes (other triangle) magenta, geometry only on the GPU red,
// only in the reference cyan, sky black.
Rgba8Image silhouetteImage(const FrameError& e) {
  Rgba8Image img = blank(e);
  for (size_t i = 0; i < e.pixelClass.size(); ++i) switch (e.pixelClass[i]) {
      case PixelClass::Surface: put(img, i, 110, 110, 110); break;
      case PixelClass::Silhouette: put(img, i, 255, 0, 255); break;
      case PixelClass::CoverageOnlyGpu: put(img, i, 255, 40, 0); break;
      case PixelClass::CoverageOnlyReference: put(img, i, 0, 220, 255); break;
      case PixelClass::Sky: break;
    }
  return img;
}

// Heat maps on a log scale: black = no error (or not a surface pixel), blue -> red over the range.
static Rgba8Image heatLog(const FrameError& e, const std::vector<float>& v, double lo, double hi) {
  Rgba8Image img = blank(e);
  for (size_t i = 0; i < v.size(); ++i) {
    if (e.pixelClass[i] != PixelClass::Surface) {
      if (e.pixelClass[i] != PixelClass::Sky) put(img, i, 90, 0, 90);
      continue;
    }
    if (!(v[i] > lo)) continue;
    double t = std::log(std::min(double(v[i]), hi) / lo) / std::log(hi / lo);
    heatColor(t, 1.0, &img.pixels[i * 4]);
  }
  return img;
}
Rgba8Image normalErrorImage(const FrameError& e) { return heatLog(e, e.normalErrorDeg, 1e-4, 1.0); }
Rgba8Image hdrErrorImage(const FrameError& e) { return heatLog(e, e.hdrRelative, 1e-5, 1.0); }
Rgba8Image positionErrorImage(const FrameError& e) { return heatLog(e, e.eyeDepthPositionRelative, 1e-8, 1e-4); }
Rgba8Image lightingErrorImage(const FrameError& e) { return heatLog(e, e.lightingPerContribution, 1e-8, 1e-4); }

}  // namespace gb
