// Point lights on the CPU: eye-space positions, frustum culling, the near-plane class that the
// stencil scheme cannot handle, the screen-disjoint layers the per-light mask draws at once, and
// the ideal (pixel, light) pair count that culling is measured by.
#pragma once
#include "renderer/core/camera.h"
#include "renderer/core/image.h"
#include "renderer/core/light_rect.h"  // cullLight: the rules
#include "renderer/frame/renderer.h"

namespace gb {

// Fills lights.eye (all lights at `time`, eye space) and lights.visible / stencilCount; with
// `layers`, orders the stencil class in screen-disjoint layers (lights.layerStarts) for the
// per-light mask, which draws a layer at once.
void classifyLights(const Scene& scene, const Camera& camera, double time, bool layers, FrameLights& lights);


// The eye-depth image (0 where nothing was drawn) of a read-back depth_stencil target, for
// frames without the eye-depth target (method forward).
CpuImage eyeDepthFromHardware(const Camera& camera, const CpuImage& depthStencil);


// (pixel, light) pairs whose surface point, reconstructed from the read-back eye depth, lies
// strictly inside the light's radius. Only pixels within each light's screen rectangle are tested.
uint64_t idealPairs(const Camera& camera, const CpuImage& eyeDepth, const std::vector<gpu::PointLight>& eyeLights);

// The same count by testing every pixel against every light (for tests on small images).
uint64_t idealPairsBruteForce(const Camera& camera, const CpuImage& eyeDepth,
                              const std::vector<gpu::PointLight>& eyeLights);

}  // namespace gb
