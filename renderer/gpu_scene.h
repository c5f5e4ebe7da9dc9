// The scene on the GPU (gpu_scene.cpp): what initRenderer creates, step by step.
#pragma once
#include "renderer/renderer.h"

namespace gb {

// G-buffer pipeline variant of an instance: bit 1 alpha-tested, bit 0 has a normal texture.
uint32_t drawVariant(const Scene& scene, uint32_t instance);

// Vertex and index buffers, the light-volume icosahedron, materials, textures (the scene's, then
// white and flat-normal stand-ins).
void uploadScene(Renderer& r);
// Samplers, set 0 (scene + frame) and set 1 (pushed per pass) layouts, the pipeline layouts.
void createDescriptors(Renderer& r);
// Draw order by pipeline variant: opaque before alpha-tested, by material within a variant.
void sortDraws(Renderer& r);

}  // namespace gb
