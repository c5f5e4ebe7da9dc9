// The frame, top to bottom: shadow map -> G-buffer (or, --gbuffer visibility, the visibility pass
// and gbuffer_resolve) -> directional light -> light mask ->
// point lights -> skybox -> fairy lights -> tone map (raster or compute), in the two-pass or
// single-pass path;
// method tiled replaces the three lighting passes by one compute pass, method clustered by four
// light-assignment passes and one shading pass (all compute), or, with the cluster grid filled on
// the CPU (--cluster-assign cpu), by one full-screen raster pass; method forward replaces the
// G-buffer and lighting by one forward pass. The method is r.method (auto resolved by
// chooseMethod), the G-buffer kind r.options.gbuffer (auto resolved by frameGBuffer). Every pass that does not run is listed with the reason (see --stats).
#include "renderer/frame/frame.h"

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

// ── Clustered shading (compute, after the G-buffer) ────────────────────────────────────────
// Clusters and their boxes from the G-buffer, lights into bins, each cluster's list, shading.
// With no visible light every cluster keeps the empty list cluster_bounds gave it.
static void addClusteredPasses(FrameGraph& g, Renderer& r) {
  const uint32_t visible = r.visibleBound;
  addClusterClearPass(g, r);
  addClusterBoundsPass(g, r);
  if (visible == 0) {
    g.skipPass("cluster_bins", "no (visible) point lights: every cluster's list is empty");
    g.skipPass("cluster_lists", "no (visible) point lights: every cluster's list is empty");
  } else {
    addClusterBinsPass(g, r, visible);
    addClusterListsPass(g, r);
  }
  addClusteredLightingPass(g, r);
}

void buildFrame(FrameGraph& g, Renderer& r, const FrameRequest& request) {
  const Scene& scene = *r.scene;
  const RenderOptions& o = r.options;
  const Method method = r.method;  // never auto
  const bool singlePass = singlePassFrame(o);  // deferred only
  // Visible lights: counted on the CPU, or bounded by the scene's lights when the GPU sets them up.
  const size_t visibleLights = r.visibleBound;
  const char* methodName = name(method);

  // ── 0. Lights: animation, eye space, culling, the visible list ────────────────────────────
  if (!r.lightsOnGpu || scene.lights.empty()) {
    const std::string why = !r.lightsOnGpu ? r.lightSetupReason : "no point lights in the scene";
    g.skipPass("light_upload", why);
    g.skipPass("light_setup", why);
    g.skipPass("light_compact", why);
  } else {
    if (r.gpuLights.uploadBytes == 0)
      g.skipPass("light_upload", "the scene's lights are unchanged since they were uploaded (same generation)");
    else
      addLightUploadPass(g, r);  // the new descriptions, from the frame slot
    addLightSetupPasses(g, r);  // light_setup + light_compact (compute)
  }

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
  // --gbuffer visibility: the visibility pass draws depth/stencil and the id, gbuffer_resolve
  // (compute) writes every pixel of the G-buffer's targets from it (r.visibility: frameGBuffer).
  // r.overlap: the id's clear and the visibility pass go into the frame's side command buffer,
  // which a queue of its own starts while the previous frame's compute still runs (the depth and
  // the id are the slot's own images: frame_slots.h); everything before them touches neither.
  if (r.overlap) g.beginSide();
  if (method == Method::Forward)
    g.skipPass("clear_gbuffer", "method forward: no G-buffer");
  else if (!r.computeClear)
    g.skipPass("clear_gbuffer", r.clearReason);  // the gbuffer (or visibility) render pass clears its targets
  else
    addClearGBufferPass(g, r);  // compute: zero the G-buffer's colour targets (or the visibility id) through storage views
  if (!r.visibility) {
    g.skipPass("visibility", r.gbufferReason);
    g.skipPass("gbuffer_resolve", r.gbufferReason);
  }
  if (method == Method::Forward) {
    g.skipPass("gbuffer", "method forward: materials are shaded where they are drawn (no G-buffer)");
    g.beginRenderPass("forward");
    addForwardPass(g, r);  // sun + every visible point light per fragment, into hdr
  } else {
    if (r.visibility) {  // never single pass (visibilityFrame)
      g.skipPass("gbuffer", "gbuffer visibility: the visibility pass draws, gbuffer_resolve writes the G-buffer");
      g.beginRenderPass("visibility");
      addVisibilityPass(g, r);  // depth/stencil + the visibility id
      g.endRenderPass();
      if (r.overlap) g.endSide();
      addGBufferResolvePass(g, r);  // compute: the G-buffer's targets from the id
    } else {
      g.beginRenderPass(singlePass ? "deferred (single pass)" : "gbuffer");
      addGBufferPass(g, r);
    }
    if (singlePass) {
      g.nextSubpass();  // lighting reads the G-buffer as subpass inputs, in tile memory where possible
    } else {
      if (!r.visibility) g.endRenderPass();
      if (method == Method::Tiled) addTiledLightingPass(g, r);  // compute: sun + binned point lights
      if (method == Method::Clustered && !r.clusterGrid) addClusteredPasses(g, r);
      if (method == Method::Clustered && r.clusterGrid)
        for (const char* pass : {"cluster_clear", "cluster_bounds", "cluster_bins", "cluster_lists"})
          g.skipPass(pass, r.clusterAssignReason + ": the CPU listed each grid cell's lights before submission");
      g.beginRenderPass("lighting");
      // The cluster grid's shading is a raster pass: the sun, the cells' lights and the sky, full screen.
      if (method == Method::Clustered && r.clusterGrid) addClusterGridLightingPass(g, r);
    }
  }

  // ── 3. Directional light ──────────────────────────────────────────────────────────────────
  if (method != Method::Deferred)
    g.skipPass("directional_light", std::string("method ") + methodName + ": the sun is shaded in " +
                                        (method == Method::Tiled       ? "tiled_lighting"
                                         : method == Method::Clustered ? "clustered_lighting"
                                                                       : "forward"));
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
  else if (method == Method::Clustered)
    g.skipPass("point_lights", "method clustered: each cluster's lights are listed and shaded in clustered_lighting");
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
  else if (method == Method::Tiled || method == Method::Clustered)
    g.skipPass("skybox", std::string("method ") + methodName + ": " +
                             (method == Method::Tiled ? "tiled_lighting" : "clustered_lighting") +
                             " writes the sky where no geometry was drawn (no pass of its own)");
  else if (skyKey == r.skyKey && r.skyPixels == 0)
    g.skipPass("skybox", "no sky visible: geometry covered every pixel in the last frame with this camera and geometry");
  else
    addSkyboxPass(g, r);

  // ── 7. Fairy lights: drawn, or splatted per tile in compute (the same image) ───────────────
  bool lightingOpen = true;  // the render pass begun above ("lighting" or "forward")
  if (!o.fairies) {
    g.skipPass("fairy_lights", "fairies disabled");
  } else if (visibleLights == 0) {
    g.skipPass("fairy_lights", "no visible point lights");
  } else if (r.fairyCompute) {
    g.skipPass("fairy_lights", "splatted in compute (fairy_splat): " + r.fairyReason);
    g.endRenderPass();
    lightingOpen = false;
    addFairySplatPasses(g, r, uint32_t(visibleLights));  // fairy_clear, fairy_bins, fairy_splat
  } else {
    addFairyPass(g, r);
  }

  // ── Tone map: hdr -> final, a raster pass or in compute ───────────────────────────────────
  if (r.computeToneMap) {
    if (lightingOpen) g.endRenderPass();
    g.skipPass("tonemap", "in compute (tonemap_compute): " + r.toneMapReason);
    addToneMapComputePass(g, r);  // sRGB encoded in the shader, through final's UNORM storage view
  } else {
    if (singlePass) {
      g.nextSubpass();
    } else {
      if (lightingOpen) g.endRenderPass();
      g.beginRenderPass("tonemap");
    }
    addToneMapPass(g, r);
    g.endRenderPass();
    g.skipPass("tonemap_compute", r.toneMapReason);
  }

  // ── Hand-off: read-back for the CPU, sampling for the viewer ─────────────────────────────
  if (!request.readback.empty()) addReadbackPass(g, r, request.readback);
  if (!request.sampleAfter.empty()) addSampleAfterPass(g, request.sampleAfter);
}

}  // namespace gb
