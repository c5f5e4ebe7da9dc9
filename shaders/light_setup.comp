#version 460
#extension GL_GOOGLE_include_directive : require
// Light setup on the GPU, step 1: one invocation per scene light does what classifyLights does on
// the CPU (renderer/frame/light_culling.cpp), in double with the same formulas: the light's position at
// this frame's time (lights.h), eye space, and whether it is culled (nothing to add, outside the
// frustum, or covering no pixel centre). It writes the eye-space light and its place among the
// visible lights of its workgroup; light_compact turns those into the visible list.
#define GB_LIGHTS_WRITTEN
#include "common.glsl"

layout(local_size_x = kLightSetupGroup) in;
layout(set = 1, binding = kBindingLightDescs, std430) readonly buffer DescBlock { LightDesc descs[]; };
layout(set = 1, binding = kBindingLightScratch, std430) writeonly buffer ScratchBlock { uint scratch[]; };

shared uint sVisible[kLightSetupGroup];
shared uint sCulled[3];

double d(uvec2 bits) { return packDouble2x32(bits); }

// sin and cos of a double (GLSL has them only in float): reduction by pi/2 in three parts
// (Cody-Waite, exact while |x| / (pi/2) < 2^20, i.e. |x| < 1.6e6 rad), then the fdlibm kernels
// on [-pi/4, pi/4] (errors below a double ulp; the result is rounded to float afterwards).
const double kPio2_1 = 1.57079632673412561417e+00LF, kPio2_2 = 6.07710050630396597660e-11LF,
             kPio2_2t = 2.02226624879595063154e-21LF, kInvPio2 = 6.36619772367581382433e-01LF;
double kernelSin(double x) {
  double z = x * x;
  return x + x * z * (-1.66666666666666324348e-01LF + z * (8.33333333332248946124e-03LF +
             z * (-1.98412698298579493134e-04LF + z * (2.75573137070700676789e-06LF +
             z * (-2.50507602534068634195e-08LF + z * 1.58969099521155010221e-10LF)))));
}
double kernelCos(double x) {
  double z = x * x;
  return 1.0LF - 0.5LF * z + z * z * (4.16666666666666019037e-02LF + z * (-1.38888888888741095749e-03LF +
         z * (2.48015872894767294178e-05LF + z * (-2.75573143513906633035e-07LF +
         z * (2.08757232129817482790e-09LF + z * -1.13596475577881948265e-11LF)))));
}
dvec2 sinCos(double x) {
  precise double k = floor(x * kInvPio2 + 0.5LF);
  precise double r = ((x - k * kPio2_1) - k * kPio2_2) - k * kPio2_2t;
  double s = kernelSin(r), c = kernelCos(r);
  int q = int(mod(k, 4.0LF));
  return q == 0 ? dvec2(s, c) : q == 1 ? dvec2(c, -s) : q == 2 ? dvec2(-s, -c) : dvec2(-c, s);
}

// Sphere vs the frustum in eye space (sphereInFrustum in light_culling.cpp).
bool inFrustum(dvec3 c, double r, double p00, double p11, double p20, double p21, double znear, double zfar) {
  if (-c.z + r < znear || -c.z - r > zfar) return false;
  dvec3 planes[4] = dvec3[](dvec3(p00, 0.0, p20 + 1.0), dvec3(-p00, 0.0, 1.0 - p20), dvec3(0.0, p11, p21 + 1.0),
                            dvec3(0.0, -p11, 1.0 - p21));
  for (int i = 0; i < 4; ++i)
    if (dot(planes[i], c) > r * length(planes[i])) return false;
  return true;
}

// Pixel centres a sphere in front of the near plane can cover along one axis (centreRange).
bool centresAlong(double depth, double r, double lateral, double scale, double offset, double size) {
  double d2 = depth * depth - r * r;
  double root = r * sqrt(lateral * lateral + d2);
  double t0 = (lateral * depth - root) / d2, t1 = (lateral * depth + root) / d2;
  double a = (scale * t0 - offset + 1.0) * 0.5 * size, b = (scale * t1 - offset + 1.0) * 0.5 * size;
  double lo = min(a, b) - 1e-3, hi = max(a, b) + 1e-3;
  return max(ceil(lo - 0.5), 0.0LF) <= min(floor(hi - 0.5), size - 1.0);
}

void main() {
  const uint i = gl_GlobalInvocationID.x, local = gl_LocalInvocationIndex;
  if (local < 3u) sCulled[local] = 0u;
  barrier();
  uint visible = 0u;
  if (i < frame.time64.z) {
    const LightDesc l = descs[i];
    const dvec3 center = dvec3(d(l.centerXY.xy), d(l.centerXY.zw), d(l.centerZOrbit.xy));
    const double orbit = d(l.centerZOrbit.zw), speed = d(l.speedPhase.xy), phase = d(l.speedPhase.zw);
    const double bob = d(l.bobRadius.xy), radius = d(l.bobRadius.zw);
    precise dvec3 world = center;
    if (!(orbit <= 0.0LF && bob == 0.0LF)) {
      precise double a = phase + speed * d(frame.time64.xy);
      const dvec2 sc = sinCos(a);
      precise double b = a * 1.7LF + phase;
      world = center + dvec3(sc.y * orbit, sinCos(b).x * bob, sc.x * orbit);
    }
    // eyeFromWorld * (world, 1) summed as GLM does, (m0 x + m1 y) + (m2 z + m3), so it rounds alike.
    precise dvec3 eye;
    for (int row = 0; row < 3; ++row) {
      const uvec4 a = frame.eyeFromWorld64[2 * row], b = frame.eyeFromWorld64[2 * row + 1];
      precise double e = (d(a.xy) * world.x + d(a.zw) * world.y) + (d(b.xy) * world.z + d(b.zw));
      eye[row] = e;
    }
    lights[i] = PointLight(vec4(vec3(eye), float(radius)), vec4(l.color.rgb, 0.0));
    const double p00 = d(frame.projection64[0].xy), p11 = d(frame.projection64[0].zw);
    const double p20 = d(frame.projection64[1].xy), p21 = d(frame.projection64[1].zw);
    const double znear = d(frame.depthRange64.xy), zfar = d(frame.depthRange64.zw);
    if (l.color.w != 0.0) {
      atomicAdd(sCulled[1], 1u);
    } else if (!inFrustum(eye, radius, p00, p11, p20, p21, znear, zfar)) {
      atomicAdd(sCulled[0], 1u);
    } else if (-eye.z - radius > znear &&
               !(centresAlong(-eye.z, radius, eye.x, p00, p20, double(frame.viewport.x)) &&
                 centresAlong(-eye.z, radius, eye.y, p11, p21, double(frame.viewport.y)))) {
      atomicAdd(sCulled[2], 1u);
    } else {
      visible = 1u;
    }
  }
  sVisible[local] = visible;
  barrier();
  if (local == 0u) {  // exclusive prefix over the group (256 adds)
    uint sum = 0u;
    for (uint k = 0u; k < kLightSetupGroup; ++k) {
      uint v = sVisible[k];
      sVisible[k] = sum;
      sum += v;
    }
    const uint at = frame.time64.z + gl_WorkGroupID.x * 4u;  // after the lights: per group visible, frustum, empty, sub-pixel
    scratch[at] = sum;
    scratch[at + 1u] = sCulled[0];
    scratch[at + 2u] = sCulled[1];
    scratch[at + 3u] = sCulled[2];
  }
  barrier();
  if (i < frame.time64.z) scratch[i] = visible != 0u ? sVisible[local] : 0xFFFFFFFFu;
}
