// The frame, top to bottom: shadow map -> G-buffer -> directional light -> light mask ->
// point lights -> skybox -> fairy lights -> tone map, in the two-pass or single-pass path.
// Every pass that does not run is listed with the reason (see --stats).
#include "renderer/frame.h"

#include <algorithm>
#include <sstream>

#include "renderer/passes/passes.h"

namespace gb {

// What the shadow map depends on: when unchanged since the last frame, it is reused.
static std::string shadowMapKey(const Renderer& r) {
  const Scene& s = *r.scene;
  const RenderOptions& o = r.options;
  std::ostringstream k;
  k.precision(17);
  k << &s << ' ' << s.instances.size() << ' ' << s.sun.toSun.x << ' ' << s.sun.toSun.y << ' ' << s.sun.toSun.z << ' '
    << o.shadowMapSize << ' ' << name(o.shadowFormat) << ' ' << o.shadowBiasConstant << ' ' << o.shadowBiasSlope << ' '
    << o.shadowBiasClamp;
  return k.str();
}

void buildFrame(FrameGraph& g, Renderer& r, const FrameRequest& request) {
  const Scene& scene = *r.scene;
  const RenderOptions& o = r.options;
  const bool singlePass = o.path == Path::SinglePass;
  const size_t visibleLights = r.lights.visible.size();

  // ── Coverage counters (views 8/9, --stats, captures) ─────────────────────────────────────
  if (o.coverage)
    addClearCoveragePass(g, r);
  else
    g.skipPass("clear_coverage", "coverage not requested");

  // ── 1. Shadow map ───────────────────────────────────────────────────────────────────────────
  const std::string shadowKey = shadowMapKey(r);
  if (!scene.sun.enabled) {
    g.skipPass("shadow_map", "no sun (shadow term 1)");
  } else if (r.drawOrder.empty()) {
    g.skipPass("shadow_map", "no shadow casters (shadow term 1)");
  } else if (shadowKey == r.shadowKey) {
    g.skipPass("shadow_map", "reused: sun and geometry unchanged");
  } else {
    addShadowMapPass(g, r);
    r.shadowKey = shadowKey;
  }

  // ── 2. G-buffer ─────────────────────────────────────────────────────────────────────────────
  g.beginRenderPass(singlePass ? "deferred (single pass)" : "gbuffer");
  addGBufferPass(g, r);
  if (singlePass) {
    g.nextSubpass();  // lighting reads the G-buffer as subpass inputs, in tile memory where possible
  } else {
    g.endRenderPass();
    g.beginRenderPass("lighting");
  }

  // ── 3. Directional light ──────────────────────────────────────────────────────────────────
  addDirectionalLightPass(g, r);

  // ── 4. Light mask ─────────────────────────────────────────────────────────────────────────
  if (visibleLights == 0)
    g.skipPass("light_mask", "no visible point lights");
  else if (!o.stencilCulling)
    g.skipPass("light_mask", "stencil culling off");
  else if (o.stencilMask == StencilMask::PerLight)
    g.skipPass("light_mask", "per-light masks are drawn inside point_lights (7 lights per stencil batch)");
  else if (r.lights.stencilCount == 0)
    g.skipPass("light_mask", "every visible light touches the near plane");
  else
    addLightMaskPass(g, r);

  // ── 5. Point lights ───────────────────────────────────────────────────────────────────────
  if (visibleLights == 0)
    g.skipPass("point_lights", "no visible point lights");
  else
    addPointLightPass(g, r);
  if (!o.coverage)
    g.skipPass("light_coverage", "coverage not requested");
  else if (visibleLights == 0)
    g.skipPass("light_coverage", "no visible point lights");
  else
    addLightCoveragePass(g, r);

  // ── 6. Skybox ─────────────────────────────────────────────────────────────────────────────
  if (!o.sky)
    g.skipPass("skybox", "sky disabled");
  else
    addSkyboxPass(g, r);

  // ── 7. Fairy lights ───────────────────────────────────────────────────────────────────────
  if (!o.fairies)
    g.skipPass("fairy_lights", "fairies disabled");
  else if (visibleLights == 0)
    g.skipPass("fairy_lights", "no visible point lights");
  else
    addFairyPass(g, r);

  // ── Tone map: hdr -> final ────────────────────────────────────────────────────────────────
  if (singlePass) {
    g.nextSubpass();
  } else {
    g.endRenderPass();
    g.beginRenderPass("tonemap");
  }
  addToneMapPass(g, r);
  g.endRenderPass();

  // ── Hand-off: read-back for the CPU, sampling for the viewer ─────────────────────────────
  if (!request.readback.empty()) addReadbackPass(g, r, request.readback);
  if (!request.sampleAfter.empty()) addSampleAfterPass(g, request.sampleAfter);
}

}  // namespace gb
