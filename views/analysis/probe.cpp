// The pixel probe's computations: decoding, both reconstructions, the shadow-map footprint,
// light volumes met by the pixel's ray, and each light's contribution (shaders/shading.h in double).
#include "views/analysis/probe.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/codec.h"
#include "renderer/scene/mesh_builder.h"
#include "shaders/shading.h"

namespace gb {

static double floatUlp(double v) {
  float f = std::abs(float(v));
  return double(std::nextafter(f, INFINITY)) - double(f);
}

static ProbeTarget rawTarget(const FrameSnapshot& f, Target t, uint32_t x, uint32_t y) {
  ProbeTarget p;
  p.target = targetName(t);
  const TargetImage& ti = f.target(t);
  if (!ti.present()) {
    p.absent = absentText(f.absence(t) == Absent::No ? Absent::NotCaptured : f.absence(t));
    return p;
  }
  p.type = name(ti.image.type);
  p.encoding = name(ti.image.encoding);
  if (!ti.contains(x, y)) {
    p.absent = absentText(Absent::OutsideRegion);
    return p;
  }
  p.present = true;
  for (uint32_t c = 0; c < ti.image.channelCount(); ++c) p.channels.push_back({ti.image.channels[c], ti.raw(x, y, c), ti.value(x, y, c)});
  return p;
}

// Where the pixel's receiver point falls in the shadow map (continuous texel coordinates).
static bool shadowTexel(const FrameSnapshot& f, const glm::dvec3& eye, glm::dvec3& lightClip, glm::dvec2& texel) {
  glm::dvec4 world = f.camera.worldFromEye * glm::dvec4(eye, 1.0);
  glm::dvec4 lc = f.lightClipFromWorld * world;
  lightClip = glm::dvec3(lc) / lc.w;
  const TargetImage& sm = f.target(Target::ShadowMap);
  double w = sm.present() ? sm.targetWidth : f.options.shadowMapSize;
  double h = sm.present() ? sm.targetHeight : f.options.shadowMapSize;
  texel = {(lightClip.x * 0.5 + 0.5) * w - 0.5, (lightClip.y * 0.5 + 0.5) * h - 0.5};
  return f.sun.enabled;
}

// The position the lighting passes used, per USE_EYE_DEPTH, or none without geometry.
static bool usedPosition(const FrameSnapshot& f, uint32_t x, uint32_t y, glm::dvec3& eye) {
  const TargetImage& depth = f.target(Target::Depth);
  const TargetImage& ds = f.target(Target::DepthStencil);
  if (f.options.eyeDepth) {
    if (!depth.contains(x, y) || !(depth.value(x, y, 0) > 0.0)) return false;
    eye = eyeFromEyeDepth(f.camera, x, y, depth.value(x, y, 0));
    return true;
  }
  double far = f.options.reversedZ ? 0.0 : 1.0;
  if (!ds.contains(x, y) || ds.value(x, y, 0) == far) return false;
  eye = eyeFromHardwareDepth(f.camera, x, y, ds.value(x, y, 0));
  return true;
}

bool shadowMapFootprint(const FrameSnapshot& f, uint32_t x, uint32_t y, int32_t& x0, int32_t& y0) {
  glm::dvec3 eye, lc;
  glm::dvec2 texel;
  if (!usedPosition(f, x, y, eye) || !shadowTexel(f, eye, lc, texel)) return false;
  x0 = int32_t(std::floor(texel.x));
  y0 = int32_t(std::floor(texel.y));
  return true;
}

static void probeShadow(const FrameSnapshot& f, const glm::dvec3& eye, PixelDossier& d) {
  ProbeShadow& s = d.shadowMap;
  s.biasConstant = f.options.shadowBiasConstant;
  s.biasSlope = f.options.shadowBiasSlope;
  s.biasClamp = f.options.shadowBiasClamp;
  s.storedShadow = d.shadow;
  if (!shadowTexel(f, eye, s.lightClip, s.texel)) {
    s.note = "no sun: the shadow term is 1";
    return;
  }
  s.receiverDepth = s.lightClip.z;
  s.x0 = int32_t(std::floor(s.texel.x));
  s.y0 = int32_t(std::floor(s.texel.y));
  const TargetImage& sm = f.target(Target::ShadowMap);
  if (!sm.present()) {
    const Absent why = f.absence(Target::ShadowMap);
    s.note = std::string("shadow_map: ") + absentText(why == Absent::No ? Absent::NotCaptured : why);
    d.missing.push_back("shadow_map");
    return;
  }
  double fx = s.texel.x - s.x0, fy = s.texel.y - s.y0;
  const double weights[4] = {(1 - fx) * (1 - fy), fx * (1 - fy), (1 - fx) * fy, fx * fy};
  double best = -1.0;
  for (int k = 0; k < 4; ++k) {
    int32_t tx = s.x0 + (k & 1), ty = s.y0 + (k >> 1);
    s.outside[k] = tx < 0 || ty < 0 || uint32_t(tx) >= sm.targetWidth || uint32_t(ty) >= sm.targetHeight;
    if (!s.outside[k] && !sm.contains(uint32_t(tx), uint32_t(ty))) {
      s.note = "shadow-map texel outside the read-back region";
      d.missing.push_back("shadow_map texels");
      return;
    }
    s.stored[k] = s.outside[k] ? 1.0 : sm.value(uint32_t(tx), uint32_t(ty), 0);  // border: opaque white
    s.weight[k] = weights[k];
    s.lit[k] = s.receiverDepth <= s.stored[k];
    s.filtered += weights[k] * (s.lit[k] ? 1.0 : 0.0);
    if (weights[k] > best) {
      best = weights[k];
      s.nearestMargin = s.stored[k] - s.receiverDepth;
    }
  }
  s.valid = true;
  s.note = "bilinear 2x2 depth compare (LESS_OR_EQUAL); bias applied when the map was rendered";
}

// Where the ray through the pixel centre (eye space, parameterised by eye depth) enters and
// leaves a light's icosahedron, built as light_volume.vert builds it (float).
static bool rayVolume(const FrameSnapshot& f, uint32_t x, uint32_t y, const gpu::PointLight& l, double& enter,
                      double& exit) {
  const Icosahedron& ico = icosahedron();
  glm::dvec3 dir = eyeFromEyeDepth(f.camera, x, y, 1.0);
  glm::vec3 v[12];
  float scale = l.eyePositionRadius.w / float(kIcosahedronInradius);
  for (int i = 0; i < 12; ++i) v[i] = glm::vec3(l.eyePositionRadius) + ico.vertices[i] * scale;
  enter = -INFINITY;
  exit = INFINITY;
  for (int t = 0; t < 20; ++t) {
    glm::dvec3 a(v[ico.indices[3 * t]]), b(v[ico.indices[3 * t + 1]]), c(v[ico.indices[3 * t + 2]]);
    glm::dvec3 n = glm::cross(b - a, c - a);  // outward (counter-clockwise seen from outside)
    double nd = glm::dot(n, dir), na = glm::dot(n, a);
    if (nd > 0.0)
      exit = std::min(exit, na / nd);
    else if (nd < 0.0)
      enter = std::max(enter, na / nd);
    else if (na < 0.0)
      return false;
  }
  return enter <= exit;
}

static void probeLights(const FrameSnapshot& f, uint32_t x, uint32_t y, const glm::dvec3& P, PixelDossier& d) {
  // Depth and stencil tests compare against the depth buffer, whatever USE_EYE_DEPTH says.
  double surface = d.fromHardwareDepth.valid ? -d.fromHardwareDepth.eye.z : -P.z;
  bool sharedMarked = d.stencil > gpu::kStencilGeometry;
  for (size_t k = 0; k < f.visibleLights.size(); ++k) {
    const gpu::PointLight& l = f.eyeLights[f.visibleLights[k]];
    ProbeLight pl;
    if (!rayVolume(f, x, y, l, pl.enter, pl.exit)) continue;
    bool stencilClass = k < f.stencilCount;
    if (!(stencilClass ? pl.enter > 0.0 : pl.exit > 0.0)) continue;  // the volume is behind the eye
    pl.index = f.visibleLights[k];
    pl.lightClass = stencilClass ? "stencil" : "near_plane";
    pl.eyePosition = glm::dvec3(l.eyePositionRadius);
    pl.radius = l.eyePositionRadius.w;
    pl.color = glm::dvec3(l.color);
    pl.distance = glm::length(pl.eyePosition - P);
    pl.attenuation = shading::pointAttenuation(pl.distance * pl.distance, pl.radius);
    const RenderOptions& o = f.options;
    if (!d.geometry)
      pl.stencilPass = false;
    else if (!o.stencilCulling)
      pl.stencilPass = stencilClass ? pl.enter <= surface : pl.exit >= surface;
    else if (o.stencilMask == StencilMask::PerLight)
      pl.stencilPass = pl.enter <= surface && surface <= pl.exit;  // Z-fail parity: inside the volume
    else
      pl.stencilPass = stencilClass ? pl.enter <= surface && sharedMarked : pl.exit >= surface;
    if (pl.stencilPass) {
      pl.contribution = shading::shadePoint(d.albedo, d.specular, d.normal, P, pl.eyePosition, pl.radius, pl.color);
      d.pointLightTotal += pl.contribution;
      d.shadedLights++;
    }
    d.lights.push_back(pl);
  }
}

// True when the snapshot holds target t at the pixel; else its name joins d.missing.
static bool need(const FrameSnapshot& f, Target t, uint32_t x, uint32_t y, PixelDossier& d) {
  if (f.target(t).contains(x, y)) return true;
  d.missing.push_back(targetName(t));
  return false;
}

// The decoded G-buffer: albedo and specular, the normal (stored and unit) and the shadow term,
// both depths and the stencil.
static void decodeGBuffer(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  if ((d.hasAlbedo = need(f, Target::AlbedoSpecular, x, y, d))) {
    const TargetImage& a = f.target(Target::AlbedoSpecular);
    d.albedo = {a.value(x, y, 0), a.value(x, y, 1), a.value(x, y, 2)};
    d.specular = a.value(x, y, 3);
  }
  if ((d.hasNormal = need(f, Target::NormalShadow, x, y, d))) {
    const TargetImage& n = f.target(Target::NormalShadow);
    DecodedNormal dn = decodeNormalTexel(n.image, x - n.x0, y - n.y0, f.options.normalFormat);
    d.normal = dn.unit;
    d.normalStored = dn.stored;
    double length = glm::length(dn.stored);
    d.normalLengthError = length > 0.0 ? std::abs(length - 1.0) : 0.0;  // zero: no geometry
    d.shadow = dn.shadow;
  }
  d.hasEyeDepth = need(f, Target::Depth, x, y, d);
  d.hasHardwareDepth = need(f, Target::DepthStencil, x, y, d);
  if (d.hasEyeDepth) d.eyeDepth = f.target(Target::Depth).value(x, y, 0);
  if (d.hasHardwareDepth) {
    d.hardwareDepth = f.target(Target::DepthStencil).value(x, y, 0);
    d.stencil = uint32_t(f.target(Target::DepthStencil).value(x, y, 1));
  }
}

// The position from each depth (eye and world space) and how far apart they are, in scene units
// and in float ulps of each stored depth.
static void reconstructPositions(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  double far = f.options.reversedZ ? 0.0 : 1.0;
  if (d.hasEyeDepth && d.eyeDepth > 0.0) {
    d.fromEyeDepth = {true, eyeFromEyeDepth(f.camera, x, y, d.eyeDepth), {}};
    d.fromEyeDepth.world = glm::dvec3(f.camera.worldFromEye * glm::dvec4(d.fromEyeDepth.eye, 1.0));
  }
  if (d.hasHardwareDepth && d.hardwareDepth != far) {
    d.fromHardwareDepth = {true, eyeFromHardwareDepth(f.camera, x, y, d.hardwareDepth), {}};
    d.fromHardwareDepth.world = glm::dvec3(f.camera.worldFromEye * glm::dvec4(d.fromHardwareDepth.eye, 1.0));
  }
  if (d.fromEyeDepth.valid && d.fromHardwareDepth.valid) {
    d.positionDifference = glm::length(d.fromEyeDepth.eye - d.fromHardwareDepth.eye);
    d.eyeDepthUlps = std::abs(d.fromEyeDepth.eye.z - d.fromHardwareDepth.eye.z) / floatUlp(d.eyeDepth);
    d.hardwareDepthUlps = std::abs(hardwareDepth(f.camera, d.fromEyeDepth.eye) - d.hardwareDepth) / floatUlp(d.hardwareDepth);
  }
}

// The stored outputs: coverage counts, hdr and what tone mapping it should give, final.
static void readOutputs(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  for (auto [t, out] : {std::pair{Target::CoverageMasked, &d.coverageMasked}, {Target::CoverageFull, &d.coverageFull}})
    if (f.target(t).contains(x, y)) *out = int64_t(f.target(t).raw(x, y, 0));
  if (need(f, Target::Hdr, x, y, d)) {
    const TargetImage& h = f.target(Target::Hdr);
    d.hasHdr = true;
    d.hdr = {h.value(x, y, 0), h.value(x, y, 1), h.value(x, y, 2), h.value(x, y, 3)};
    glm::dvec3 c = glm::dvec3(d.hdr);
    for (int i = 0; i < 3; ++i)
      if (std::isnan(c[i])) c[i] = 0.0;  // as tonemap.frag
    d.finalExpected = shading::toneMap(c, f.options.exposure);
    for (int i = 0; i < 3; ++i) {  // sRGB encoding, as the target's hardware conversion rounds it
      double v = std::clamp(d.finalExpected[i], 0.0, 1.0);
      v = v <= 0.0031308 ? v * 12.92 : 1.055 * std::pow(v, 1.0 / 2.4) - 0.055;
      d.finalExpectedSrgb8[i] = uint32_t(std::lround(v * 255.0));
    }
  }
  if (need(f, Target::Final, x, y, d)) {
    const TargetImage& fi = f.target(Target::Final);
    d.hasFinal = true;
    d.finalColor = {fi.value(x, y, 0), fi.value(x, y, 1), fi.value(x, y, 2), fi.value(x, y, 3)};
  }
}

PixelDossier probePixel(const FrameSnapshot& f, uint32_t x, uint32_t y) {
  PixelDossier d;
  d.x = x;
  d.y = y;
  d.width = f.camera.width;
  d.height = f.camera.height;
  if (x >= f.camera.width || y >= f.camera.height) {
    d.error = "pixel " + std::to_string(x) + "," + std::to_string(y) + " is outside the " +
              std::to_string(f.camera.width) + "x" + std::to_string(f.camera.height) + " frame";
    return d;
  }
  for (size_t i = 0; i < kTargetCount; ++i)
    if (screenSpaceTarget(Target(i))) d.targets.push_back(rawTarget(f, Target(i), x, y));
  decodeGBuffer(f, x, y, d);
  glm::dvec3 P(0.0);
  d.geometry = usedPosition(f, x, y, P);
  d.positionSource = f.options.eyeDepth ? "eye_depth" : "hardware_depth";
  reconstructPositions(f, x, y, d);

  if (d.geometry) {
    d.viewDirection = glm::normalize(-P);
    probeShadow(f, P, d);
    glm::dvec3 sun = f.sunEyeDirection();
    d.directional = shading::shadeDirectional(d.albedo, d.specular, d.normal, d.viewDirection, sun,
                                              glm::dvec3(f.sun.color), glm::dvec3(f.sky.ambient),
                                              f.sun.enabled ? d.shadow : 0.0);
  } else {
    d.shadowMap.note = "no geometry at this pixel";
  }
  probeLights(f, x, y, P, d);
  d.hdrExpected = d.directional + d.pointLightTotal;
  readOutputs(f, x, y, d);
  return d;
}

}  // namespace gb
