// One function per pass: each declares what it reads and writes (its Uses) and records its
// commands. The frame function (renderer/frame.cpp) decides which run and in what order.
#pragma once
#include "renderer/graph/graph.h"
#include "renderer/pipelines.h"
#include "renderer/render_targets.h"

namespace gb {

void addClearCoveragePass(FrameGraph& g, Renderer& r);
void addShadowMapPass(FrameGraph& g, Renderer& r);
void addGBufferPass(FrameGraph& g, Renderer& r);
void addDirectionalLightPass(FrameGraph& g, Renderer& r);
void addLightMaskPass(FrameGraph& g, Renderer& r);
void addPointLightPass(FrameGraph& g, Renderer& r);
void addForwardPass(FrameGraph& g, Renderer& r);
void addTiledLightingPass(FrameGraph& g, Renderer& r);
void addLightCoveragePass(FrameGraph& g, Renderer& r);
void addSkyboxPass(FrameGraph& g, Renderer& r);
void addFairyPass(FrameGraph& g, Renderer& r);
void addToneMapPass(FrameGraph& g, Renderer& r);
void addReadbackPass(FrameGraph& g, Renderer& r, const std::vector<Target>& targets);
void addSampleAfterPass(FrameGraph& g, const std::vector<Target>& targets);

// ---- shared by the lighting passes (passes/lighting_common.cpp) ----
bool singlePass(const Renderer& r);
// The G-buffer reads of a lighting pass: albedo, normal and the position source, as subpass
// inputs (single-pass) or textures (two-pass).
std::vector<Use> gbufferReads(const Renderer& r);
// The lighting subpass's attachments as a pass uses them: hdr and depth/stencil.
Use hdrUse(Access access, bool clear = false);
Use depthStencilUse(Access access);
// Fragment shader variant for the path: sampled G-buffer (two-pass) or subpass inputs (single pass).
Shader lightingShader(const Renderer& r, Shader sampled, Shader input);
VkPipelineLayout lightingLayout(const Renderer& r);
// Binds set 0 and pushes the G-buffer reads (+ extra images) for a lighting pass.
void bindGBuffer(Renderer& r, const PassContext& pc, std::initializer_list<PassImage> extra = {},
                 VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS);
// Draws the visible lights' icosahedra: [first, first + count) of the visible list.
void drawLightVolumes(Renderer& r, VkCommandBuffer cmd, uint32_t first, uint32_t count);
// Draws the scene's instances in drawOrder [begin, end), pushing each material's textures
// (bindings kBindingBaseColorTexture/kBindingNormalTexture of r.pipelineLayout).
void drawInstances(Renderer& r, VkCommandBuffer cmd, uint32_t begin, uint32_t end, bool shadowCastersOnly);
// Binds a graphics pipeline and sets the viewport/scissor to the pass's extent, so every pass's
// dynamic state is complete whatever ran before it.
void bindPipeline(const PassContext& pc, VkPipeline pipeline);
VkStencilOpState stencil(VkCompareOp compare, uint32_t compareMask, VkStencilOp depthFail = VK_STENCIL_OP_KEEP,
                         VkStencilOp pass = VK_STENCIL_OP_KEEP);

}  // namespace gb
