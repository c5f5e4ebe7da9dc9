// The renderer: a scene on the GPU, the frame's targets, and renderFrame(), which builds the
// frame graph (frame.cpp), records it, submits, waits, and reads back what was asked for.
#pragma once
#include <array>
#include <map>
#include <string>
#include <vector>

#include "renderer/core/camera.h"
#include "renderer/core/frame_stats.h"
#include "renderer/graph/graph.h"
#include "renderer/core/image.h"
#include "renderer/core/options.h"
#include "renderer/scene/scene.h"
#include "renderer/vk/formats.h"
#include "renderer/vk/pipeline.h"
#include "renderer/vk/resources.h"
#include "shaders/shared.h"

namespace gb {

// The request of a capture of `targets`: those are read back and nothing else; culling statistics
// only when they need no extra read-back (coverage on, coverage_masked and depth asked).
FrameRequest captureRequest(const std::vector<Target>& targets, const RenderOptions& options);

// Lights of this frame after CPU culling. Drawn instanced from `visible`:
// [0, stencilCount) use the stencil mask; [stencilCount, visible.size()) contain or touch the
// near plane and are drawn as back faces with the depth test reversed (no stencil).
// The stencil class is ordered in layers: [layerStarts[k], layerStarts[k + 1]) are lights whose
// volumes cover disjoint pixels, so the per-light mask marks and shades a layer in one draw each.
struct FrameLights {
  std::vector<gpu::PointLight> eye;  // every light, eye space (index = Scene::lights index)
  std::vector<uint32_t> visible;
  uint32_t stencilCount = 0;
  std::vector<uint32_t> layerStarts;  // size layers + 1; the last is stencilCount
  uint32_t culledFrustum = 0;  // outside the view frustum
  uint32_t culledEmpty = 0;    // zero radius, intensity or colour: nothing to add
  uint32_t culledSubpixel = 0; // its screen rectangle holds no pixel centre (see light_culling.h)
};



struct Renderer {
  GpuContext* ctx = nullptr;
  const Scene* scene = nullptr;

  // The scene on the GPU (gpu_scene.cpp).
  Buffer vertexBuffer, indexBuffer, icosahedronBuffer;
  Buffer frameBuffer, drawBuffer, materialBuffer, lightBuffer, visibleBuffer;
  std::vector<Image> textures;      // the scene's, then white and flat-normal stand-ins
  std::vector<uint32_t> drawOrder;  // instance indices grouped by drawVariant()
  std::array<uint32_t, 5> drawVariants{};  // drawOrder[drawVariants[v], drawVariants[v+1]) has variant v
  VkSampler samplerRepeat = VK_NULL_HANDLE, samplerClamp = VK_NULL_HANDLE;
  VkSampler samplerShadow = VK_NULL_HANDLE, samplerPoint = VK_NULL_HANDLE;
  VkDescriptorSetLayout sceneSetLayout = VK_NULL_HANDLE, passSetLayout = VK_NULL_HANDLE;
  VkDescriptorSetLayout passSetLayoutInput = VK_NULL_HANDLE;  // set 1 with subpass inputs
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayoutInput = VK_NULL_HANDLE;      // single-pass lighting pipelines
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;
  VkDescriptorSet sceneSet = VK_NULL_HANDLE;

  // Frame resources.
  RenderOptions options;  // the options the targets were created for
  bool targetsValid = false;
  std::string targetsKey;  // size, formats and usage the targets were created for
  uint32_t timestampCapacity = 0;
  GraphTargets targets;
  GraphCache graphCache;
  std::map<std::string, VkPipeline> pipelines;
  VkQueryPool timestampPool = VK_NULL_HANDLE, statisticsPool = VK_NULL_HANDLE;
  bool statisticsActive = false;  // this frame counts fragment invocations of the point-light pass
  VkQueryPool occlusionPool = VK_NULL_HANDLE;  // sky pixels drawn by the skybox
  bool skyQueryActive = false;                 // this frame's skybox counts them
  std::string skyKey;                          // skyVisibilityKey() of the last count
  uint64_t skyPixels = UINT64_MAX;             // the last count (UINT64_MAX: none yet)
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  std::array<Buffer, kTargetCount> readbackBuffers;
  std::array<CpuImage, kTargetCount> readback;  // filled for the targets a request named

  // This frame, as the frame function and the passes see it.
  Camera camera;
  FrameLights lights;
  glm::dmat4 lightClipFromWorld{1.0};
  gpu::FrameData frameData{};  // this frame's uniform data, as the shaders saw it
  std::vector<float> srgbDecode;  // probeSrgbDecode's table (empty until probed)
  std::string shadowKey;  // what the shadow map was rendered for (reuse when unchanged)
  FrameStats stats;
};

// G-buffer pipeline variant of an instance: bit 1 alpha-tested, bit 0 has a normal texture.
uint32_t drawVariant(const Scene& scene, uint32_t instance);

// Uploads the scene; the Renderer keeps a pointer to it (the scene must outlive the renderer;
// lights may change between frames).
void initRenderer(Renderer& r, GpuContext& ctx, const Scene& scene);
void destroyRenderer(Renderer& r);

// Renders one frame with these options and waits for it. Targets are re-created when the size
// or a format changes.
const FrameStats& renderFrame(Renderer& r, const RenderOptions& options, const FrameRequest& request = {});
// One more frame with the coverage counters on and the eye depth kept, for its culling counts
// (FrameStats::culling): the counters' atomics would slow frames that are being timed.
const FrameStats& renderCountingFrame(Renderer& r, const RenderOptions& options, FrameRequest request = {});

// Decodes tightly packed texels as vkCmdCopyImageToBuffer wrote them (for depth/stencil: the
// depth aspect, then one stencil byte per texel) into a CpuImage of the target's description.
CpuImage unpackTexels(Target t, const RenderOptions& options, VkFormat format, const uint8_t* src, uint32_t width,
                      uint32_t height);
// The read-back buffer of `t` after the frame, unpacked.
CpuImage unpackReadback(Renderer& r, Target t);

// Runs a small graph over this frame's targets after renderFrame (the viewer's region read-back
// and view ranges): `build` adds passes, then the `handOff` targets are left readable by fragment
// shaders again. Barriers come from the passes' declarations, as in the frame. Submits and waits.
void runAfterFrame(Renderer& r, const std::function<void(FrameGraph&)>& build, const std::vector<Target>& handOff);

// ---- used by the frame function and the passes ----
// Cached graphics pipeline for the current render pass / subpass; `fill` describes it once.
VkPipeline graphicsPipeline(Renderer& r, const PassContext& pc, const std::string& id,
                            const std::function<void(GraphicsPipelineDesc&)>& fill);
// Cached compute pipeline of r.pipelineLayout with the common specialization constants.
VkPipeline computePipeline(Renderer& r, const std::string& shader);
struct PassImage {
  uint32_t binding;
  VkDescriptorType type;
  VkImageView view;
  VkImageLayout layout;
  VkSampler sampler = VK_NULL_HANDLE;
};
// Binds set 0 (scene) and pushes set 1 (this pass's images) for a pipeline of `layout`.
void bindDescriptors(Renderer& r, VkCommandBuffer cmd, VkPipelineLayout layout, std::initializer_list<PassImage> images,
                     VkPipelineBindPoint bindPoint = VK_PIPELINE_BIND_POINT_GRAPHICS);
// Depth-test helpers that follow options.reversedZ.
VkCompareOp closerOrEqual(const Renderer& r);   // LESS_OR_EQUAL, or GREATER_OR_EQUAL reversed
VkCompareOp fartherOrEqual(const Renderer& r);  // the opposite
float farDepth(const Renderer& r);

// What this device's sampler returns for each 8-bit sRGB value (index = byte), measured once.
const std::vector<float>& probeSrgbDecode(Renderer& r);

// A target's size under these options (1x1 for a target the frame does not compute), and whether
// it lives only in tile memory (single-pass G-buffer nobody reads).
VkExtent2D targetExtent(const GpuContext& ctx, Target t, const Scene& scene, const RenderOptions& o);
bool targetTransient(Target t, const RenderOptions& o);

// The targets a frame of these options can read back on this renderer's device (targetAbsence()
// is Absent::No; primitive_id also needs gl_PrimitiveID).
std::vector<Target> readableTargets(const Renderer& r, const RenderOptions& o);

// The primitive_id target is written this frame (requested, and the device has gl_PrimitiveID).
bool primitiveIdOn(const GpuContext& ctx, const RenderOptions& o);

// Specialization constants every pipeline gets (eye depth, reversed Z, normal encoding, ...).
std::vector<SpecConstant> commonSpec(const Renderer& r);

}  // namespace gb
