// The probe's light ledger: why each light that could matter does or does not light the pixel,
// by the renderer's own rules (renderer/core/light_rect.h cullLight; the volume and stencil
// prediction of probe.cpp; tiles and clusters, which keep every light whose sphere reaches the
// surface), ordered by what it adds.
#include <algorithm>
#include <cstdio>

#include "renderer/core/cluster_grid.h"
#include "renderer/core/light_rect.h"
#include "shaders/shared.h"
#include "views/analysis/probe_internal.h"

namespace gb {

namespace {

constexpr double kListedRadii = 4.0;   // point lights within this many radii of the surface point
constexpr size_t kMostEntries = 256;

std::string fmt(const char* f, double a, double b = 0.0) {
  char buf[160];
  std::snprintf(buf, sizeof buf, f, a, b);
  return buf;
}

LedgerEntry sunEntry(const FrameSnapshot& f, const PixelDossier& d) {
  LedgerEntry e;
  e.light = "sun";
  e.contribution = d.directional;
  if (!f.sun.enabled) {
    e.fate = "no_sun";
    e.why = "the scene has no sun: ambient only";
    return e;
  }
  e.nDotL = glm::dot(d.normal, f.sunEyeDirection());
  if (d.unlit) {
    e.fate = "shaded", e.why = "unlit material (KHR_materials_unlit): the albedo, no light";
  } else if (e.nDotL <= 0.0) {
    e.fate = "facing_away", e.why = fmt("N.L = %.4g <= 0: the surface faces away from the sun (ambient only)", e.nDotL);
  } else if (d.shadow < 0.5) {
    e.fate = "shadowed";
    e.why = d.shadowMap.valid ? fmt("shadow-map lookup: %.4g of the filtered texels lit; nearest texel margin %.3g "
                                    "(stored - receiver depth, < 0: occluded)",
                                    d.shadowMap.filtered, d.shadowMap.nearestMargin)
                              : fmt("the stored shadow term is %.4g", d.shadow);
  } else {
    e.fate = "lit", e.why = fmt("N.L = %.4g, stored shadow term %.4g", e.nDotL, d.shadow);
  }
  return e;
}

// Where the method that ran put drawn light `k` (its position in the visible list) for pixel
// (x, y): the per-light mask's batch, stencil bit and layer (renderer/passes/point_lights.cpp
// groups: the layers, or one per stencil-class light, then one per near-plane light; 7 bits a
// batch), the shared mask, no mask, forward's loop, or the tile / cluster of the compute methods.
// `slice`: the pixel's clustered depth slice.
std::string placement(const FrameSnapshot& f, Method m, uint32_t x, uint32_t y, uint32_t k, uint32_t slice) {
  const bool stencilClass = k < f.stencilCount;
  if (m == Method::Tiled) return "tile (" + std::to_string(x / gpu::kTileSize) + ", " + std::to_string(y / gpu::kTileSize) + ")";
  if (m == Method::Clustered && f.clusterGrid) {
    const uint32_t tile = gpu::kGridTile;
    return "cluster grid cell (" + std::to_string(x / tile) + ", " + std::to_string(y / tile) + ", depth slice " +
           std::to_string(slice) + "), listed on the CPU";
  }
  if (m == Method::Clustered) {
    return "cluster (" + std::to_string(x / gpu::kClusterTile) + ", " + std::to_string(y / gpu::kClusterTile) +
           ", depth slice " + std::to_string(slice) + ")";
  }
  if (m == Method::Forward) return "forward: evaluated for every fragment of the pixel";
  const std::string nearClass = "near-plane class (back faces, no mask)";
  if (!f.options.stencilCulling) return stencilClass ? "front faces, no stencil mask (culling off)" : nearClass;
  if (!perLightMask(f.options, m))
    return stencilClass ? "stencil class (front faces where the shared light_mask marked the pixel)" : nearClass;
  constexpr uint32_t kBitsPerBatch = 7;  // stencil bits 0..6; bit 7 marks geometry
  const std::vector<uint32_t>& starts = f.layerStarts;
  const uint32_t stencilGroups = starts.empty() ? f.stencilCount : uint32_t(starts.size() - 1);
  uint32_t group = stencilClass ? k : stencilGroups + (k - f.stencilCount);
  std::string layer;
  if (stencilClass && !starts.empty()) {
    group = uint32_t(std::upper_bound(starts.begin(), starts.end(), k) - starts.begin()) - 1;
    layer = ", layer " + std::to_string(group) + " of " + std::to_string(stencilGroups) + " (" +
            std::to_string(starts[group + 1] - starts[group]) + " lights with disjoint volumes share the bit)";
  }
  return std::string(stencilClass ? "per-light mask" : "per-light mask, near-plane light (both faces mark, back faces shade)") +
         ": batch " + std::to_string(group / kBitsPerBatch) + ", stencil bit " + std::to_string(group % kBitsPerBatch) + layer;
}

// The fate of a drawn light at the pixel: its volume and stencil (deferred) or its tile/cluster (compute).
void drawnFate(const FrameSnapshot& f, uint32_t x, uint32_t y, const ProbeLight* drawn, int visiblePosition,
               uint32_t slice, LedgerEntry& e) {
  const Method m = f.method != Method::Auto ? f.method : f.options.method;  // Auto: not known (deferred's rules)
  if (visiblePosition >= 0) e.drawnAs = placement(f, m, x, y, uint32_t(visiblePosition), slice);
  const bool volumes = m != Method::Tiled && m != Method::Clustered && m != Method::Forward;  // deferred's
  if (e.distance >= e.radius) {
    e.fate = "out_of_range";
    e.why = fmt("distance %.4g >= radius %.4g: attenuation is exactly 0", e.distance, e.radius);
  } else if (e.nDotL <= 0.0) {
    e.fate = "facing_away";
    e.why = fmt("N.L = %.4g <= 0 inside the radius (distance / radius %.3g): no diffuse or specular term", e.nDotL,
                e.distance / e.radius);
  } else if (volumes && !drawn) {
    e.fate = "volume_misses", e.why = "the pixel's ray does not meet the light's icosahedron";
  } else if (volumes && !drawn->stencilPass) {
    e.fate = "stencil_test";
    e.why = fmt("the volume spans eye depth %.4g..%.4g along the ray; the depth/stencil test rejected this pixel",
                drawn->enter, drawn->exit);
  } else {
    e.fate = "shaded";
    e.why = fmt("distance / radius %.3g, N.L %.4g", e.distance / e.radius, e.nDotL);
  }
}

double luminance(const glm::dvec3& c) { return 0.2126 * c.r + 0.7152 * c.g + 0.0722 * c.b; }

}  // namespace

LightLedger lightLedger(const FrameSnapshot& f, uint32_t x, uint32_t y, const glm::dvec3& P, const PixelDossier& d) {
  LightLedger ledger;
  ledger.entries.push_back(sunEntry(f, d));
  std::vector<int> position(f.eyeLights.size(), -1);  // in the visible list
  // Clustered: the pixel's depth slice, of the cluster grid or of Olsson's slicing.
  const uint32_t slice = f.clusterGrid ? gridSlice(gridShapeForLights(f.camera, f.eyeLights, f.visibleLights), -P.z)
                                       : clusterSlice(clusterSlicing(f.camera), -P.z);
  for (size_t k = 0; k < f.visibleLights.size(); ++k) position[f.visibleLights[k]] = int(k);
  for (uint32_t i = 0; i < f.eyeLights.size(); ++i) {
    const gpu::PointLight& l = f.eyeLights[i];
    LedgerEntry e;
    e.light = "point";
    e.index = i;
    const glm::dvec3 c(l.eyePositionRadius);
    e.radius = l.eyePositionRadius.w;
    e.distance = glm::length(c - P);
    const ProbeLight* drawn = nullptr;
    for (const ProbeLight& pl : d.lights)
      if (pl.index == i) drawn = &pl;
    if (!drawn && !(e.distance < kListedRadii * e.radius)) {
      ledger.notListed++;
      continue;
    }
    e.nDotL = e.distance > 0.0 ? glm::dot(d.normal, (c - P) / e.distance) : 0.0;
    if (drawn && drawn->stencilPass) e.contribution = drawn->contribution;
    switch (cullLight(f.camera, c, e.radius, 1.0, glm::dvec3(l.color))) {
      case LightCull::Empty: e.fate = "empty", e.why = "zero radius or colour: lights nothing"; break;
      case LightCull::Frustum: e.fate = "frustum_culled", e.why = "its sphere lies outside the camera frustum"; break;
      case LightCull::SubPixel:
        e.fate = "sub_pixel";
        e.why = "in front of the near plane, its sphere's screen rectangle holds no pixel centre: no ray through a "
                "pixel centre can reach a point inside it";
        break;
      default: drawnFate(f, x, y, drawn, position[i], slice, e); break;
    }
    ledger.entries.push_back(std::move(e));
  }
  std::stable_sort(ledger.entries.begin() + 1, ledger.entries.end(), [](const LedgerEntry& a, const LedgerEntry& b) {
    const double la = luminance(a.contribution), lb = luminance(b.contribution);
    if (la != lb) return la > lb;
    return a.distance / a.radius < b.distance / b.radius;
  });
  if (ledger.entries.size() > kMostEntries + 1) {
    ledger.notListed += ledger.entries.size() - (kMostEntries + 1);
    ledger.entries.resize(kMostEntries + 1);
  }
  ledger.rule = "the sun, and every point light whose volume the pixel's ray meets or whose centre is within " +
                std::to_string(int(kListedRadii)) + " radii of the surface point (drawn or culled), at most " +
                std::to_string(kMostEntries);
  return ledger;
}

}  // namespace gb
