// The lighting formulas, written once in the subset of GLSL that GLM also compiles:
// the shaders use them in float, the CPU reference (renderer/reference) in double.
#ifndef GBLENS_SHADING_H
#define GBLENS_SHADING_H

#ifdef __cplusplus
#include <glm/glm.hpp>
namespace gb::shading {
using real = double;
using vec3 = glm::dvec3;
using glm::clamp;
using glm::dot;
using glm::exp;
using glm::inversesqrt;
using glm::max;
using glm::normalize;
using glm::pow;
using glm::sqrt;
#define GB_FN inline
#else
#define real float
#define GB_FN
#endif

// Blinn-Phong exponent; the G-buffer stores only a specular intensity (as the Apple sample).
#define GB_SHININESS 32.0

// x^32 (GB_SHININESS) by five squarings. GLSL's pow(x, y) is exp2(y log2 x), and the precision
// Vulkan requires of log2 near 1 is 2^-21 absolute: times 32 that is up to 1.06e-5 relative in the
// specular term (llvmpipe reaches it: VC's fp32 lighting passes measured 1.07e-5 per light
// contribution). Five roundings of a product keep it within ~2^-21 relative, and cost less.
GB_FN real pow32(real x) {
  real x2 = x * x;
  real x4 = x2 * x2;
  real x8 = x4 * x4;
  real x16 = x8 * x8;
  return x16 * x16;
}

// Window falloff: 1 at the centre, exactly 0 at (and beyond) the radius, so culling to the
// light volume loses nothing. x = squared distance / squared radius.
GB_FN real pointAttenuation(real distanceSquared, real radius) {
  real x = distanceSquared / (radius * radius);
  real w = clamp(1.0 - x, 0.0, 1.0);
  return w * w;
}

// Diffuse + specular of one light of radiance `radiance` arriving from unit direction L.
// N unit normal, V unit vector toward the eye.
GB_FN vec3 blinnPhong(vec3 albedo, real specular, vec3 N, vec3 V, vec3 L, vec3 radiance) {
  real nDotL = dot(N, L);
  if (nDotL <= 0.0) return vec3(0.0);
  vec3 H = normalize(L + V);
  real nDotH = max(dot(N, H), 0.0);
  return radiance * (albedo * nDotL + vec3(specular * pow32(nDotH)));
}

// The sun: ambient everywhere geometry is, direct light scaled by the shadow term (1 lit, 0 shadowed).
GB_FN vec3 shadeDirectional(vec3 albedo, real specular, vec3 N, vec3 V, vec3 toSun, vec3 sunColor,
                            vec3 ambient, real shadow) {
  return albedo * ambient + shadow * blinnPhong(albedo, specular, N, V, toSun, sunColor);
}

// One point light at eye-space `lightPosition` lighting the surface point P (eye space): the
// Blinn-Phong of blinnPhong in the form a loop over many lights evaluates, with what depends only on
// the pixel (V = normalize(-P)) and on the light (1 / radius^2) given. The range test comes first
// (x >= 1 is exactly where the window falloff is 0). One inverse square root gives N.L and the
// unnormalized half vector u = L + V, and N.H = N.u / |u| without normalizing u. (Forming |u|^2 as
// 2 + 2 L.V instead, which L and V being unit allows, cancels where L is nearly -V: in float the
// specular term was then off by up to 1.5e-3 relative at grazing angles, against 1e-5 this way.)
GB_FN vec3 shadePointPrepared(vec3 albedo, real specular, vec3 N, vec3 P, vec3 V, vec3 lightPosition,
                              real invRadiusSquared, vec3 color) {
  vec3 t = lightPosition - P;
  real d2 = dot(t, t);
  real x = d2 * invRadiusSquared;
  if (x >= 1.0) return vec3(0.0);
  real invLength = inversesqrt(max(d2, 1e-30));
  real nDotL = dot(N, t) * invLength;
  if (nDotL <= 0.0) return vec3(0.0);
  vec3 u = t * invLength + V;
  real nDotH = max(dot(N, u) * inversesqrt(max(dot(u, u), 1e-30)), 0.0);
  real w = 1.0 - x;  // pointAttenuation's window, unclamped: 0 <= x < 1 here
  real a = w * w;
  return color * (albedo * (a * nDotL) + vec3(a * specular * pow32(nDotH)));
}

// One point light at eye-space `lightPosition` lighting the surface point P (eye space).
GB_FN vec3 shadePoint(vec3 albedo, real specular, vec3 N, vec3 P, vec3 lightPosition, real radius,
                      vec3 color) {
  return shadePointPrepared(albedo, specular, N, P, normalize(-P), lightPosition, 1.0 / (radius * radius), color);
}

// An unlit surface (KHR_materials_unlit): its albedo (the base colour) as is, in place of
// ambient + sun; point lights add nothing to it.
GB_FN vec3 shadeUnlit(vec3 albedo) { return albedo; }

// HDR -> display: exposure and an exponential shoulder (monotonic, never NaN: the input is
// clamped to the largest half first so +Inf from saturated fp16 blending stays white).
GB_FN vec3 toneMap(vec3 hdr, real exposure) {
  vec3 x = clamp(hdr, vec3(0.0), vec3(65504.0)) * exposure;
  return vec3(1.0) - exp(-x);
}

#ifdef __cplusplus
}  // namespace gb::shading
#undef GB_FN
#endif

#endif
