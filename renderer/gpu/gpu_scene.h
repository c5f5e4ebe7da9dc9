// The scene on the GPU (gpu_scene.cpp): what initRenderer creates, step by step.
#pragma once
#include "renderer/gpu/renderer_state.h"

namespace gb {

// G-buffer (and forward) pipeline variant of an instance: bit 2 alpha-tested, bit 1 has a normal
// texture, bit 0 has a base-colour texture. Opaque variants are [0, 4), alpha-tested [4, 8).
constexpr uint32_t kDrawVariants = 8;
uint32_t drawVariant(const Scene& scene, uint32_t instance);
struct DrawVariantBits {
  bool alpha, normalMap, baseTexture;
};
inline DrawVariantBits drawVariantBits(uint32_t v) { return {(v & 4u) != 0, (v & 2u) != 0, (v & 1u) != 0}; }
// The pipeline id suffix of a variant: ".opaque" / ".alpha", ".normal_map", ".base_texture".
std::string drawVariantName(uint32_t v);

// Vertex and index buffers, the light-volume icosahedron, materials, textures (the scene's, then
// white and flat-normal stand-ins).
void uploadScene(Renderer& r);
// Samplers, set 0 (scene + frame) and set 1 (pushed per pass) layouts, the pipeline layouts.
void createDescriptors(Renderer& r);
// Draw order by pipeline variant: opaque before alpha-tested, by material within a variant.
void sortDraws(Renderer& r);

}  // namespace gb
