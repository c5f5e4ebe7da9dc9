// What --gbuffer visibility needs of the scene on the GPU (visibility_scene.cpp): the visibility
// id's packing (renderer/core/visibility.h) or why the scene or the device cannot have it, each
// draw's geometry, and gbuffer_resolve's descriptor layouts and scene set.
#pragma once
#include "renderer/gpu/renderer_state.h"

namespace gb {

// At initRenderer, after uploadScene and createDescriptors: sets r.visibilityPacking, or
// r.visibilityRefusal with the reason; creates the resolve's resources when it can run.
void createVisibilityScene(Renderer& r);
void destroyVisibilityScene(Renderer& r);

// Why a frame of these options cannot fill its G-buffer through the visibility id on this
// renderer ("" when it can or when --gbuffer raster): the options, then the scene and device.
std::string visibilityRefusal(const Renderer& r, const RenderOptions& o);

}  // namespace gb
