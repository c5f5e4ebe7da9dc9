// The frame: every pass in order, with every skip decided in one place (frame.cpp).
#pragma once
#include "renderer/graph.h"
#include "renderer/renderer.h"

namespace gb {

void buildFrame(FrameGraph& graph, Renderer& r, const FrameRequest& request);

// Copies a target into its read-back buffer (after the graph has put it in TRANSFER_SRC).
void recordReadback(Renderer& r, VkCommandBuffer cmd, Target t);

}  // namespace gb
