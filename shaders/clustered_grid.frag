#version 460
#extension GL_GOOGLE_include_directive : require
// Clustered shading from the cluster grid (--cluster-assign cpu, renderer/core/cluster_grid.h):
// one full-screen pass reads the G-buffer once per pixel, shades the sun and ambient term and every
// light of the pixel's grid cell (listed by the CPU, in visible-list order), or writes the sky.
// With COVERAGE on, coverage_masked gets the number of lights each geometry pixel evaluated.
#include "common.glsl"
#include "gbuffer_read.glsl"
#include "shading.h"
#include "sky.glsl"

layout(set = 1, binding = kBindingGridCells, std430) readonly buffer GridCellBlock { uvec2 gridCells[]; };
layout(set = 1, binding = kBindingGridLights, std430) readonly buffer GridLightBlock { PointLight gridLights[]; };
layout(set = 1, binding = kBindingCoverage, r32ui) uniform writeonly uimage2D coverage;
layout(location = 0) out vec4 outColor;

// The pixel's cell: its tile and the exponential slice of its eye depth (gridSlice on the CPU).
uint gridCell(uvec2 pixel, float eyeDepth) {
  const uvec2 tile = pixel / frame.gridShape.w;
  const float k = floor(log2(max(eyeDepth, 1e-30)) * frame.gridSlices.x + frame.gridSlices.y);
  const uint slice = uint(clamp(k, 0.0, float(frame.gridShape.z - 1u)));
  return (slice * frame.gridShape.y + tile.y) * frame.gridShape.x + tile.x;
}

void main() {
  const Surface s = readSurface(gl_FragCoord.xy);
  vec3 c = vec3(0.0);
  uint evaluated = 0u;
  if (s.geometry && s.unlit) {
    c = shadeUnlit(s.albedo);  // KHR_materials_unlit: no light changes its colour
  } else if (s.geometry) {
    c = shadeDirectional(s.albedo, s.specular, s.N, normalize(-s.P), frame.sunEyeDirection.xyz, frame.sunColor.rgb,
                         frame.ambientColor.rgb, frame.sunEyeDirection.w > 0.0 ? s.shadow : 0.0);
    const uvec2 cell = gridCells[gridCell(uvec2(gl_FragCoord.xy), -s.P.z)];
    for (uint i = 0u; i < cell.y; ++i) {
      const PointLight l = gridLights[cell.x + i];
      c += shadePoint(s.albedo, s.specular, s.N, s.P, l.eyePositionRadius.xyz, l.eyePositionRadius.w, l.color.rgb);
    }
    evaluated = cell.y;
  }
  // No geometry: the sky (the skybox pass is skipped), else nothing.
  const vec2 ndc = gl_FragCoord.xy * frame.viewport.zw * 2.0 - 1.0;
  outColor = s.geometry ? vec4(c, 1.0) : skyEnabled() ? vec4(skyColor(ndc), 1.0) : vec4(0.0);
  if (COVERAGE != 0) imageStore(coverage, ivec2(gl_FragCoord.xy), uvec4(evaluated));
}
