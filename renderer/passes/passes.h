// One function per pass: each declares what it reads and writes (its Uses) and records its
// commands. The frame function (renderer/frame/frame.cpp) decides which run and in what order.
#pragma once
#include "renderer/gpu/pipelines.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/graph/graph.h"

namespace gb {

void addClearCoveragePass(FrameGraph& g, Renderer& r);
void addShadowMapPass(FrameGraph& g, Renderer& r);
void addGBufferPass(FrameGraph& g, Renderer& r);
// The G-buffer's colour targets this frame writes, in the shader's output order (gbuffer.frag);
// clear_gbuffer (passes/clear_gbuffer.cpp) zeroes them when the render pass does not.
std::vector<Target> gbufferColourTargets(const Renderer& r);
void addClearGBufferPass(FrameGraph& g, Renderer& r);
// --gbuffer visibility (passes/visibility.cpp, passes/gbuffer_resolve.cpp): the raster pass of
// depth/stencil and the visibility id, then the compute pass that writes gbufferColourTargets.
void addVisibilityPass(FrameGraph& g, Renderer& r);
void addGBufferResolvePass(FrameGraph& g, Renderer& r);
void addDirectionalLightPass(FrameGraph& g, Renderer& r);
void addLightMaskPass(FrameGraph& g, Renderer& r);
void addPointLightPass(FrameGraph& g, Renderer& r);
void addForwardPass(FrameGraph& g, Renderer& r);
void addTiledLightingPass(FrameGraph& g, Renderer& r);
// Clustered shading (passes/clusters.cpp, passes/clustered_lighting.cpp): `visibleMax` bounds the
// visible list (the light bins' dispatch).
void addClusterClearPass(FrameGraph& g, Renderer& r);
void addClusterBoundsPass(FrameGraph& g, Renderer& r);
void addClusterBinsPass(FrameGraph& g, Renderer& r, uint32_t visibleMax);
void addClusterListsPass(FrameGraph& g, Renderer& r);
void addClusteredLightingPass(FrameGraph& g, Renderer& r);
// Clustered lighting from the CPU's cluster grid (passes/clustered_grid.cpp): a full-screen raster
// pass, inside the lighting render pass.
void addClusterGridLightingPass(FrameGraph& g, Renderer& r);
// Fairy sprites in compute (passes/fairy_splat.cpp): fairy_clear, fairy_bins, fairy_splat.
void addFairySplatPasses(FrameGraph& g, Renderer& r, uint32_t visibleMax);
// Light setup on the GPU (passes/light_setup.cpp): light_upload (the lights changed since the last
// upload: GpuLights::uploadBytes), light_setup and light_compact.
void addLightUploadPass(FrameGraph& g, Renderer& r);
void addLightSetupPasses(FrameGraph& g, Renderer& r);
// Binds set 0 and pushes only `buffers` to set 1 (compute passes that read no image).
void pushComputeBuffers(Renderer& r, VkCommandBuffer cmd, std::initializer_list<PassBuffer> buffers);
// The frame's light buffers (eye-space lights, visible list, counts) as a pass reads them: after
// light setup on the GPU the graph orders them (on the CPU path they were written before submission).
std::vector<BufferUse> lightReads(const Renderer& r, BufferAccess access);
// Binds set 0 and pushes the G-buffer reads, `images` and clustered shading's buffers (compute).
void pushClusterDescriptors(Renderer& r, const PassContext& pc, std::initializer_list<PassImage> images);
void addLightCoveragePass(FrameGraph& g, Renderer& r);
void addSkyboxPass(FrameGraph& g, Renderer& r);
void addFairyPass(FrameGraph& g, Renderer& r);
void addToneMapPass(FrameGraph& g, Renderer& r);
// tonemap_compute: the tone map in compute, through final's UNORM storage view (TonemapPass).
void addToneMapComputePass(FrameGraph& g, Renderer& r);
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
                 VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS,
                 std::initializer_list<PassBuffer> buffers = {});
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
// The scene geometry's depth and stencil state (depth tested and written, reversed Z as the options
// say; stencil kStencilGeometry where geometry is): the passes that draw the scene into the G-buffer's
// depth (gbuffer, visibility, forward) write the same depth and stencil through it.
void sceneGeometryDepthStencil(const Renderer& r, GraphicsPipelineDesc& d);

}  // namespace gb
