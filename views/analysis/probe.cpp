// The pixel probe's computations: decoding, both reconstructions, the shadow-map footprint,
// light volumes met by the pixel's ray, and each light's contribution (shaders/shading.h in double).
#include "views/analysis/probe.h"

#include <algorithm>
#include <cmath>

#include "renderer/core/codec.h"
#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "renderer/scene/mesh_builder.h"
#include "shaders/shading.h"
#include "views/analysis/probe_internal.h"
#include "views/analysis/sample_views.h"

namespace gb {

static double floatUlp(double v) {
  float f = std::abs(float(v));
  return double(std::nextafter(f, INFINITY)) - double(f);
}

static ProbeTarget rawTarget(const FrameSnapshot& f, uint32_t t, uint32_t x, uint32_t y) {
  ProbeTarget p;
  p.target = f.layout.targets[t].name;
  const TargetImage& ti = f.images[t];
  if (!ti.present()) {
    p.absent = absentText(f.absences[t] == Absent::No ? Absent::NotCaptured : f.absences[t]);
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
  for (const CpuImage& s : ti.samples) {  // whole planes, as the image they go with
    if (s.width != ti.image.width || s.height != ti.image.height) break;
    std::vector<ProbeChannel>& ch = p.samples.emplace_back();
    for (uint32_t c = 0; c < s.channelCount(); ++c) ch.push_back({s.channels[c], s.raw(x - ti.x0, y - ti.y0, c), s.value(x - ti.x0, y - ti.y0, c)});
  }
  if (p.samples.size() != ti.samples.size()) p.samples.clear();
  // The spread views' rule (sample_views.h), per channel.
  for (uint32_t c = 0; !p.samples.empty() && c < p.channels.size(); ++c) p.spread.push_back(channelSpread(ti, x, y, c));
  return p;
}

// Multisampled targets: each quantity they hold decoded per sample, from a frame whose targets are
// that sample's texel at (x, y) (a 1x1 window: what a region read-back gives the probe too).
static void decodeSamples(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  size_t samples = 0;
  for (const TargetImage& ti : f.images)
    if (ti.contains(x, y) && ti.samples.size() > 1) samples = std::max(samples, ti.samples.size());
  if (samples < 2) return;
  FrameSnapshot one;
  static_cast<FrameContext&>(one) = f;  // everything but the planes, which the windows below replace
  one.setLayout(f.layout);
  one.absences = f.absences;
  for (size_t k = 0; k < samples; ++k) {
    for (size_t t = 0; t < f.images.size(); ++t) {
      const TargetImage& ti = f.images[t];
      if (!ti.contains(x, y)) continue;
      const CpuImage& plane = k < ti.samples.size() && ti.samples[k].width == ti.image.width ? ti.samples[k] : ti.image;
      TargetImage& w = one.images[t];
      w.samples.clear();
      w.image = plane;
      w.image.width = w.image.height = 1;
      const size_t bytes = plane.texelBytes();
      const size_t at = (size_t(y - ti.y0) * plane.width + (x - ti.x0)) * bytes;
      w.image.data.assign(plane.data.begin() + long(at), plane.data.begin() + long(at + bytes));
      w.x0 = x, w.y0 = y;
    }
    PixelDossier per;
    decodeQuantities(one, x, y, per);
    for (size_t q = 0; q < d.quantities.size() && q < per.quantities.size(); ++q) {
      const int t = f.layout.findTarget(d.quantities[q].target);
      if (t < 0 || f.images[size_t(t)].samples.size() < 2) continue;
      d.quantities[q].sampleValues.push_back(per.quantities[q].values);
      d.quantities[q].sampleNotes.push_back(per.quantities[q].note);
    }
  }
}

// A target holding only the sun's depth (the shadow map): the shadow-map lookup shows it.
static bool sunDepthTarget(const Layout& l, uint32_t t) {
  for (const Quantity* q : l.quantitiesOf(t))
    if (!(q->kind == QuantityKind::Depth && q->ofSun)) return false;
  return true;
}

// The layout's camera depth of one encoding (eye depth, hardware depth), or null.
static const Quantity* cameraDepth(const Layout& l, DepthEncoding e) {
  for (const Quantity& q : l.quantities)
    if (q.kind == QuantityKind::Depth && !q.ofSun && q.depth == e) return &q;
  return nullptr;
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

// The depth the lighting passes reconstruct positions from: per USE_EYE_DEPTH when the layout has
// both (gblens's frames), else the layout's first camera depth; null when it has none.
static const Quantity* lightingDepth(const FrameSnapshot& f) {
  const Quantity* eye = cameraDepth(f.layout, DepthEncoding::Eye);
  const Quantity* hardware = cameraDepth(f.layout, DepthEncoding::Hardware);
  if (eye && hardware) return f.options.eyeDepth ? eye : hardware;
  return surfaceDepth(f.layout);
}

// The position the lighting passes used, or none without geometry (a stored position when the
// layout has no depth).
static bool usedPosition(const FrameSnapshot& f, uint32_t x, uint32_t y, glm::dvec3& eye) {
  const Quantity* q = lightingDepth(f);
  if (!q) q = f.layout.find(QuantityKind::Position);
  if (!q || !holds(f, *q, x, y)) return false;
  std::optional<glm::dvec3> p = decodePosition(f, *q, x, y);
  if (p) eye = *p;
  return p.has_value();
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
  const glm::dvec3 origin = eyeFromEyeDepth(f.camera, x, y, 0.0);  // the eye (orthographic: on z = 0)
  const glm::dvec3 dir = eyeFromEyeDepth(f.camera, x, y, 1.0) - origin;
  glm::vec3 v[12];
  float scale = l.eyePositionRadius.w / float(kIcosahedronInradius);
  for (int i = 0; i < 12; ++i) v[i] = glm::vec3(l.eyePositionRadius) + ico.vertices[i] * scale;
  enter = -INFINITY;
  exit = INFINITY;
  for (int t = 0; t < 20; ++t) {
    glm::dvec3 a(v[ico.indices[3 * t]]), b(v[ico.indices[3 * t + 1]]), c(v[ico.indices[3 * t + 2]]);
    glm::dvec3 n = glm::cross(b - a, c - a);  // outward (counter-clockwise seen from outside)
    double nd = glm::dot(n, dir), na = glm::dot(n, a - origin);
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
      pl.contribution = d.unlit ? glm::dvec3(0.0)
                                : shading::shadePoint(d.albedo, d.specular, d.normal, P, pl.eyePosition, pl.radius, pl.color);
      d.pointLightTotal += pl.contribution;
      d.shadedLights++;
    }
    d.lights.push_back(pl);
  }
}

// True when the snapshot holds the quantity at the pixel; else its target joins d.missing.
static bool need(const FrameSnapshot& f, const Quantity* q, uint32_t x, uint32_t y, PixelDossier& d) {
  if (!q) return false;  // the layout has no such quantity: nothing is missing
  if (holds(f, *q, x, y)) return true;
  d.missing.push_back(f.layout.targets[q->target].name);
  return false;
}
static bool need(const FrameSnapshot& f, Target t, uint32_t x, uint32_t y, PixelDossier& d) {
  if (f.target(t).contains(x, y)) return true;
  if (f.indexOf(t) >= 0) d.missing.push_back(targetName(t));
  return false;
}

// The decoded G-buffer the lighting reads, through the layout: albedo and specular, the normal
// (stored and unit) and the shadow term, both depths and the stencil.
static void decodeGBuffer(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  const Layout& l = f.layout;
  const Quantity* albedo = l.find(QuantityKind::Albedo) ? l.find(QuantityKind::Albedo) : l.find(QuantityKind::BaseColor);
  const Quantity* specular = l.find(QuantityKind::Specular);
  const Quantity* normal = l.find(QuantityKind::Normal);
  const Quantity* shadow = l.find(QuantityKind::Shadow);
  const Quantity* eye = cameraDepth(l, DepthEncoding::Eye);
  const Quantity* hardware = cameraDepth(l, DepthEncoding::Hardware);
  const Quantity* stencil = l.find(QuantityKind::Stencil);
  if ((d.hasAlbedo = need(f, albedo, x, y, d))) d.albedo = glm::dvec3(decodeColor(f, *albedo, x, y));
  if ((d.hasSpecular = need(f, specular, x, y, d))) d.specular = decodeScalar(f, *specular, x, y);
  if ((d.hasNormal = need(f, normal, x, y, d))) {
    NormalSample n = decodeNormal(f, *normal, x, y);
    d.normal = n.unit;
    d.normalStored = n.stored;
    double length = glm::length(n.stored);
    d.normalLengthError = length > 0.0 ? std::abs(length - 1.0) : 0.0;  // zero: no geometry
    // The unlit mark (KHR_materials_unlit) is gblens's own normal code: only its layout has it.
    const bool native = f.layout.name == nativeLayout(f.options).name;
    const int nt = f.indexOf("normal_shadow");
    if (native && nt >= 0) {
      const TargetImage& ni = f.images[size_t(nt)];
      d.unlit = ni.contains(x, y) && unlitTexel(ni.image, x - ni.x0, y - ni.y0, f.options.normalFormat);
    }
  }
  if ((d.hasShadow = need(f, shadow, x, y, d))) d.shadow = decodeScalar(f, *shadow, x, y);
  if ((d.hasEyeDepth = need(f, eye, x, y, d))) d.eyeDepth = storedValues(f, *eye, x, y)[0];
  if ((d.hasHardwareDepth = need(f, hardware, x, y, d))) d.hardwareDepth = storedValues(f, *hardware, x, y)[0];
  if ((d.hasStencil = need(f, stencil, x, y, d))) d.stencil = decodeInteger(f, *stencil, x, y);
}

// The position from each depth (eye and world space) and how far apart they are, in scene units
// and in float ulps of each stored depth.
static void reconstructPositions(const FrameSnapshot& f, uint32_t x, uint32_t y, PixelDossier& d) {
  auto from = [&](const Quantity* q, ProbePosition& p) {
    if (!q || !holds(f, *q, x, y)) return;
    std::optional<glm::dvec3> e = decodePosition(f, *q, x, y);
    if (e) p = {true, *e, glm::dvec3(f.camera.worldFromEye * glm::dvec4(*e, 1.0))};
  };
  from(cameraDepth(f.layout, DepthEncoding::Eye), d.fromEyeDepth);
  from(cameraDepth(f.layout, DepthEncoding::Hardware), d.fromHardwareDepth);
  if (d.fromEyeDepth.valid && d.fromHardwareDepth.valid) {
    d.positionDifference = glm::length(d.fromEyeDepth.eye - d.fromHardwareDepth.eye);
    d.eyeDepthUlps = std::abs(d.fromEyeDepth.eye.z - d.fromHardwareDepth.eye.z) / floatUlp(d.eyeDepth);
    d.hardwareDepthUlps = std::abs(hardwareDepth(f.camera, d.fromEyeDepth.eye) - d.hardwareDepth) / floatUlp(d.hardwareDepth);
  }
  reconstructAll(f, x, y, d);
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

// Lights are evaluated with shaders/shading.h for gblens's own G-buffer and for layouts whose
// lights say they use its model; "" when they are, else why not.
static std::string lightingNote(const FrameSnapshot& f) {
  if (gblensLayout(f.layout)) return "";
  if (!f.layout.lights.present) return "this layout gives no lights: lighting not evaluated";
  if (!f.layout.lights.gblensModel)
    return "this layout's lights use the model \"" + f.layout.lights.model +
           "\", which gblens does not implement: lighting not evaluated";
  return "";
}

bool lightingInputs(const FrameSnapshot& f, uint32_t x, uint32_t y, LightingInputs& in) {
  PixelDossier d;
  decodeGBuffer(f, x, y, d);
  if (!usedPosition(f, x, y, in.P) || !d.hasAlbedo || !d.hasNormal) return false;
  in.albedo = d.albedo, in.specular = d.specular, in.normal = d.normal, in.unlit = d.unlit;
  in.shadow = f.layout.find(QuantityKind::Shadow) ? d.shadow : 1.0;  // no shadow term stored: lit
  return true;
}

std::string lightingNotEvaluated(const FrameSnapshot& f) { return lightingNote(f); }

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
  d.native = gblensLayout(f.layout);
  for (uint32_t t = 0; t < f.layout.targets.size(); ++t)
    if (!sunDepthTarget(f.layout, t)) d.targets.push_back(rawTarget(f, t, x, y));
  decodeGBuffer(f, x, y, d);
  decodeQuantities(f, x, y, d);
  decodeSamples(f, x, y, d);
  glm::dvec3 P(0.0);
  d.geometry = usedPosition(f, x, y, P);
  const Quantity* used = lightingDepth(f);
  d.positionSource = !used ? "stored position" : used->depth == DepthEncoding::Eye ? "eye_depth" : "hardware_depth";
  reconstructPositions(f, x, y, d);
  d.lightingNote = lightingNote(f);
  const bool hasSunDepth = std::any_of(f.layout.quantities.begin(), f.layout.quantities.end(),
                                       [](const Quantity& q) { return q.kind == QuantityKind::Depth && q.ofSun; });
  if (!d.geometry) {
    d.shadowMap.note = "no geometry at this pixel";
  } else if (!hasSunDepth) {
    d.shadowMap.note = "this layout has no shadow map";
  }
  if (d.geometry && d.lightingNote.empty()) {
    d.viewDirection = glm::normalize(-P);
    if (hasSunDepth) probeShadow(f, P, d);
    glm::dvec3 sun = f.sunEyeDirection();
    d.directional = d.unlit ? shading::shadeUnlit(d.albedo)
                            : shading::shadeDirectional(d.albedo, d.specular, d.normal, d.viewDirection, sun,
                                                        glm::dvec3(f.sun.color), glm::dvec3(f.sky.ambient),
                                                        f.sun.enabled ? d.shadow : 0.0);
  }
  if (d.lightingNote.empty()) probeLights(f, x, y, P, d);
  if (d.lightingNote.empty() && d.geometry) d.ledger = lightLedger(f, x, y, P, d);
  d.hdrExpected = d.directional + d.pointLightTotal;
  readOutputs(f, x, y, d);
  return d;
}

}  // namespace gb
