// Per-quantity error of a GPU frame vs the reference (see error.h), and its error images.
#include "views/error.h"

#include <algorithm>
#include <cmath>

#include "renderer/codec.h"
#include "views/visualize.h"

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
  size_t k = std::min(v.size() - 1, size_t(std::ceil(0.99 * v.size())) - 1);
  std::nth_element(v.begin(), v.begin() + k, v.end());
  s.p99 = v[k];
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
}  // namespace

FrameError measureError(const GpuFrame& g, const ReferenceView& ref, unsigned threads) {
  const reference::Frame& rf = *ref.frame;
  const uint32_t w = rf.view.width, h = rf.view.height;
  const RenderOptions& o = g.options;
  FrameError e;
  e.width = w;
  e.height = h;
  e.primitiveIds = g.primitiveId && g.primitiveId->width == w;
  e.storedPosition = g.position && o.position != PositionSource::Depth;
  e.pixelClass.assign(size_t(w) * h, PixelClass::Sky);
  e.shadowClass.assign(size_t(w) * h, ShadowClass::None);
  e.normalErrorDeg.assign(size_t(w) * h, 0.0f);
  e.hdrRelative.assign(size_t(w) * h, 0.0f);
  const float far = o.reversedZ ? 0.0f : 1.0f;

  std::vector<double> normal, albedoU, albedoT, spec, depthRel, depthUlps, hdrAbs, hdrRel, hdrAbsU, hdrRelU;
  PositionSamples fromEye, fromHw, fromPos, used;
  std::vector<reference::ShadingInput> gpuInputs(size_t(w) * h);
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      const size_t i = size_t(y) * w + x;
      const reference::Surface& r = rf.at(x, y);
      const float eyeDepth = float(g.depth->value(x, y, 0));
      const float hwDepth = float(g.depthStencil->value(x, y, 0));
      glm::dvec3 pEye = shaderEyeFromEyeDepth(g.frame, x, y, eyeDepth);
      glm::dvec3 pHw = shaderEyeFromHardwareDepth(g.frame, x, y, hwDepth);
      glm::dvec3 pPos(0.0);
      bool posGeometry = false;
      if (e.storedPosition) {
        glm::vec3 stored(g.position->value(x, y, 0), g.position->value(x, y, 1), g.position->value(x, y, 2));
        pPos = shaderEyeFromStoredPosition(g.frame, stored, o.positionSpace);
        posGeometry = g.position->value(x, y, 3) > 0.0;
      }
      // The lighting passes' own view of the pixel (gbuffer_read.glsl).
      reference::ShadingInput& in = gpuInputs[i];
      if (e.storedPosition) {
        in.geometry = posGeometry;
        in.P = pPos;
      } else if (o.eyeDepth) {
        in.geometry = eyeDepth > 0.0f;
        in.P = pEye;
      } else {
        in.geometry = hwDepth != far;
        in.P = pHw;
      }
      DecodedNormal n = decodeNormalTexel(*g.normalShadow, x, y, o.normalFormat);
      in.N = n.unit;
      for (int c = 0; c < 3; ++c)
        in.albedo[c] = g.srgbDecode ? double((*g.srgbDecode)[g.albedoSpecular->raw(x, y, c)])
                                    : g.albedoSpecular->value(x, y, c);
      in.specular = g.albedoSpecular->value(x, y, 3);
      in.shadow = n.shadow;

      // Pixel class.
      const bool gpuHit = eyeDepth > 0.0f;
      if (!gpuHit && !r.hit) {
        e.sky++;
        continue;
      }
      if (gpuHit != r.hit) {
        e.pixelClass[i] = gpuHit ? PixelClass::CoverageOnlyGpu : PixelClass::CoverageOnlyReference;
        (gpuHit ? e.coverageOnlyGpu : e.coverageOnlyReference)++;
        continue;
      }
      bool same = e.primitiveIds ? g.primitiveId->raw(x, y, 0) == r.primitiveId
                                 : std::abs(eyeDepth - r.eyeDepth) <= 1e-3 * r.eyeDepth;
      if (!same) {
        e.pixelClass[i] = PixelClass::Silhouette;
        e.silhouette++;
        continue;
      }
      e.pixelClass[i] = PixelClass::Surface;
      e.surface++;

      double nd = angleDeg(n.unit, r.normal);
      normal.push_back(nd);
      e.normalErrorDeg[i] = float(nd);
      double a = 0.0;
      for (int c = 0; c < 3; ++c)
        a = std::max(a, std::abs(double(g.albedoSpecular->raw(x, y, c)) - linearToSrgb(r.albedo[c]) * 255.0));
      (r.textured ? albedoT : albedoU).push_back(a);
      spec.push_back(std::abs(double(g.albedoSpecular->raw(x, y, 3)) - r.specular * 255.0));
      depthRel.push_back(std::abs(eyeDepth - r.eyeDepth) / r.eyeDepth);
      depthUlps.push_back(std::abs(eyeDepth - r.eyeDepth) / ulpOf(float(r.eyeDepth)));
      fromEye.add(pEye, r.eye, r.eyeDepth);
      fromHw.add(pHw, r.eye, r.eyeDepth);
      if (e.storedPosition) fromPos.add(pPos, r.eye, r.eyeDepth);
      used.add(in.P, r.eye, r.eyeDepth);

      // Shadow: lit/shadowed state where it matters, outside the penumbra band.
      if (r.sunVisible < 0) {
        e.shadowClass[i] = ShadowClass::NotCompared;
        e.shadow.notCompared++;
      } else {
        bool gpuLit = n.shadow > 0.5, refLit = r.sunVisible == 1;
        if ((*ref.band)[i]) {
          e.shadowClass[i] = ShadowClass::Band;
          e.shadow.band++;
          e.shadow.bandMismatched += gpuLit != refLit;
        } else {
          e.shadow.compared++;
          if (gpuLit == refLit) {
            e.shadowClass[i] = gpuLit ? ShadowClass::AgreeLit : ShadowClass::AgreeShadowed;
          } else {
            e.shadow.mismatched++;
            e.shadowClass[i] = gpuLit ? ShadowClass::FalseLight : ShadowClass::FalseShadow;
            (gpuLit ? e.shadow.falseLight : e.shadow.falseShadow)++;
          }
        }
      }

      // Final HDR colour vs the reference's.
      const glm::dvec3& rc = ref.shaded->hdr[i];
      double dAbs = 0.0, rMax = 0.0;
      for (int c = 0; c < 3; ++c) {
        dAbs = std::max(dAbs, std::abs(g.hdr->value(x, y, c) - rc[c]));
        rMax = std::max(rMax, std::abs(rc[c]));
      }
      double dRel = dAbs / std::max(rMax, 1e-3);
      hdrAbs.push_back(dAbs);
      hdrRel.push_back(dRel);
      e.hdrRelative[i] = float(dRel);
      if (!r.textured && !(*ref.band)[i]) {
        hdrAbsU.push_back(dAbs);
        hdrRelU.push_back(dRel);
      }
    }
  e.normalDeg = errorStats(std::move(normal));
  e.albedoUntextured = errorStats(std::move(albedoU));
  e.albedoTextured = errorStats(std::move(albedoT));
  e.specular = errorStats(std::move(spec));
  e.eyeDepthRelative = errorStats(std::move(depthRel));
  e.eyeDepthUlps = errorStats(std::move(depthUlps));
  e.fromEyeDepth = fromEye.stats();
  e.fromHardwareDepth = fromHw.stats();
  e.fromPosition = fromPos.stats();
  e.used = used.stats();
  e.shadow.fraction = e.shadow.compared ? double(e.shadow.mismatched) / e.shadow.compared : 0.0;
  uint64_t all = e.shadow.compared + e.shadow.band;
  e.shadow.fractionWithBand = all ? double(e.shadow.mismatched + e.shadow.bandMismatched) / all : 0.0;
  e.hdr = {errorStats(std::move(hdrAbs)), errorStats(std::move(hdrRel))};
  e.hdrUntexturedOutsideBand = {errorStats(std::move(hdrAbsU)), errorStats(std::move(hdrRelU))};

  // The lighting passes alone: the same formulas in double on the GPU's own G-buffer, with the
  // lights and sun as uploaded. What remains is shading arithmetic and accumulation rounding.
  std::vector<reference::Light> lights;
  for (const gpu::PointLight& l : g.lights) {
    reference::Light rl{glm::dvec3(l.eyePositionRadius), l.eyePositionRadius.w, glm::dvec3(l.color)};
    if (rl.radius > 0.0 && glm::dot(rl.color, rl.color) > 0.0) lights.push_back(rl);
  }
  reference::Sun sun;
  sun.enabled = g.frame.sunEyeDirection.w > 0.0f;
  sun.toSunEye = glm::dvec3(g.frame.sunEyeDirection);
  sun.color = glm::dvec3(g.frame.sunColor);
  sun.ambient = glm::dvec3(g.frame.ambientColor);
  reference::Shaded s = reference::shade(gpuInputs, rf.view, lights, sun, threads);
  std::vector<double> lRel, lPer;
  for (uint32_t y = 0; y < h; ++y)
    for (uint32_t x = 0; x < w; ++x) {
      size_t i = size_t(y) * w + x;
      if (!gpuInputs[i].geometry) continue;
      double rel = 0.0, per = 0.0, rMax = 0.0, dMax = 0.0;
      for (int c = 0; c < 3; ++c) {
        double d = std::abs(g.hdr->value(x, y, c) - s.hdr[i][c]);
        dMax = std::max(dMax, d);
        rMax = std::max(rMax, std::abs(s.hdr[i][c]));
        // Below 2^-14 (the smallest normal half) relative precision is not representable in
        // fp16: such sums are measured against 2^-14.
        per = std::max(per, d / (std::max(s.count[i], 1u) * std::max(s.absSum[i][c], std::ldexp(1.0, -14))));
      }
      rel = dMax / std::max(rMax, 1e-3);
      lRel.push_back(rel);
      lPer.push_back(per);
      e.lighting.maxContributions = std::max(e.lighting.maxContributions, s.count[i]);
    }
  e.lighting.relative = errorStats(std::move(lRel));
  e.lighting.perContribution = errorStats(std::move(lPer));
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
                 {"silhouettes_from", e.primitiveIds ? "primitive_id" : "depth difference > 1e-3 (no primitive_id)"}};
  j["normal_deg"] = errorJson(e.normalDeg);
  j["albedo_steps"] = {{"untextured", errorJson(e.albedoUntextured)}, {"textured", errorJson(e.albedoTextured)}};
  j["specular_steps"] = errorJson(e.specular);
  j["eye_depth"] = {{"relative", errorJson(e.eyeDepthRelative)}, {"ulps", errorJson(e.eyeDepthUlps)}};
  nlohmann::json pos = {{"eye_depth", positionJson(e.fromEyeDepth)}, {"hardware_depth", positionJson(e.fromHardwareDepth)}};
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
                   {"max_contributions", e.lighting.maxContributions}};
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

}  // namespace gb
