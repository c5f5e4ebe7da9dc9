// The frame, top to bottom: shadow map -> G-buffer -> directional light -> light mask ->
// point lights -> skybox -> fairy lights -> tone map, in the two-pass or single-pass path;
// method tiled replaces the three lighting passes by one compute pass, method forward replaces
// the G-buffer and lighting by one forward pass. Every pass that does not run is listed with
// the reason (see --stats).
#include "renderer/frame.h"

#include <algorithm>

#include "renderer/passes/passes.h"

namespace gb {

// What the shadow map depends on: when unchanged since the last frame, it is reused. (The
// renderer draws one scene for its whole life: the instances and the sun are what can change.)
static ShadowMapKey shadowMapKey(const Renderer& r) {
  const RenderOptions& o = r.options;
  return {r.scene->instances.size(), r.scene->sun.toSun, o.shadowMapSize, o.shadowFormat,
          o.shadowBiasConstant, o.shadowBiasSlope, o.shadowBiasClamp};
}

SkyKey skyVisibilityKey(const Renderer& r) {
  const RenderOptions& o = r.options;
  return {r.scene->instances.size(), o.width, o.height, o.reversedZ, o.depthFormat, r.camera.clipFromWorld};
}

void buildFrame(FrameGraph& g, Renderer& r, const FrameRequest& request) {
  const Scene& scene = *r.scene;
  const RenderOptions& o = r.options;
  const Method method = o.method;
  const bool singlePass = singlePassFrame(o);  // deferred only
  const size_t visibleLights = r.lights.visible.size();
  const char* methodName = name(method);

  // ── Coverage counters (views 8/9, --stats, captures) ─────────────────────────────────────
  if (o.coverage)
    addClearCoveragePass(g, r);
  else
    g.skipPass("clear_coverage", "coverage not requested");

  // ── 1. Shadow map ───────────────────────────────────────────────────────────────────────────
  const ShadowMapKey shadowKey = shadowMapKey(r);
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

  // ── 2. G-buffer (deferred, tiled) or the forward pass ──────────────────────────────────────
  if (method == Method::Forward) {
    g.skipPass("gbuffer", "method forward: materials are shaded where they are drawn (no G-buffer)");
    g.beginRenderPass("forward");
    addForwardPass(g, r);  // sun + every visible point light per fragment, into hdr
  } else {
    g.beginRenderPass(singlePass ? "deferred (single pass)" : "gbuffer");
    addGBufferPass(g, r);
    if (singlePass) {
      g.nextSubpass();  // lighting reads the G-buffer as subpass inputs, in tile memory where possible
    } else {
      g.endRenderPass();
      if (method == Method::Tiled) addTiledLightingPass(g, r);  // compute: sun + binned point lights
      g.beginRenderPass("lighting");
    }
  }

  // ── 3. Directional light ──────────────────────────────────────────────────────────────────
  if (method != Method::Deferred)
    g.skipPass("directional_light", std::string("method ") + methodName + ": the sun is shaded in " +
                                        (method == Method::Tiled ? "tiled_lighting" : "forward"));
  else
    addDirectionalLightPass(g, r);

  // ── 4. Light mask ─────────────────────────────────────────────────────────────────────────
  if (method != Method::Deferred)
    g.skipPass("light_mask", std::string("method ") + methodName + ": no stencil culling");
  else if (visibleLights == 0)
    g.skipPass("light_mask", "no visible point lights");
  else if (!o.stencilCulling)
    g.skipPass("light_mask", "stencil culling off");
  else if (o.stencilMask == StencilMask::PerLight)
    g.skipPass("light_mask", "per-light masks are drawn inside point_lights (7 stencil bits per batch)");
  else if (r.lights.stencilCount == 0)
    g.skipPass("light_mask", "every visible light touches the near plane");
  else
    addLightMaskPass(g, r);

  // ── 5. Point lights ───────────────────────────────────────────────────────────────────────
  if (method == Method::Tiled)
    g.skipPass("point_lights", "method tiled: lights are binned per 16x16 tile and shaded in tiled_lighting");
  else if (method == Method::Forward)
    g.skipPass("point_lights", "method forward: every fragment loops over the visible lights");
  else if (visibleLights == 0)
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
  // Sky pixels are where the depth buffer kept the far plane, so they depend only on the
  // camera, the size and the geometry: the last frame with the same ones counted them
  // (occlusion query around the skybox draw). Zero then means zero now.
  const SkyKey skyKey = skyVisibilityKey(r);
  if (!o.sky)
    g.skipPass("skybox", "sky disabled");
  else if (skyKey == r.skyKey && r.skyPixels == 0)
    g.skipPass("skybox", "no sky visible: geometry covered every pixel in the last frame with this camera and geometry");
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
