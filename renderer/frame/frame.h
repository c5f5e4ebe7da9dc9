// The frame: every pass in order, with every skip decided in one place (frame.cpp).
#pragma once
#include "renderer/frame/renderer.h"
#include "renderer/graph/graph.h"

namespace gb {

void buildFrame(FrameGraph& graph, Renderer& r, const FrameRequest& request);

// What decides which pixels show sky (camera, size, geometry, depth convention): a frame with
// the same key has the same sky pixels, so a count of zero lets the next frame skip the skybox.
SkyKey skyVisibilityKey(const Renderer& r);

}  // namespace gb
