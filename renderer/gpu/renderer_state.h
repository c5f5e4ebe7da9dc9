// The renderer's state (renderer/gpu/): the Renderer and what it holds on the GPU (scene, targets,
// cluster buffers, lights, frame slots, cached pipelines) and this frame as the passes see it.
// The code that fills it lives beside it in gpu/; the frame function and its API in renderer/frame/.
#pragma once
#include <array>
#include <chrono>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "renderer/core/camera.h"
#include "renderer/core/cluster_grid.h"
#include "renderer/core/frame_stats.h"
#include "renderer/core/image.h"
#include "renderer/core/options.h"
#include "renderer/core/visibility.h"
#include "renderer/graph/graph.h"
#include "renderer/scene/scene.h"
#include "renderer/vk/formats.h"
#include "renderer/vk/pipeline.h"
#include "renderer/vk/resources.h"
#include "shaders/shared.h"

namespace gb {

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
  uint32_t culledSubpixel = 0; // its screen rectangle holds no pixel centre (see renderer/frame/light_culling.h)
};



// What cached GPU state was made for: when the key of a new frame equals the stored one, the
// state is reused (targets kept, shadow map not re-rendered, skybox skipped when it drew nothing).
struct TargetsKey {
  uint32_t width = 0, height = 0, shadowMapSize = 0;
  NormalFormat normalFormat{};
  DepthFormat depthFormat{};
  AccumFormat accumFormat{};
  ShadowFormat shadowFormat{};
  PositionSource position{};
  bool coverage = false, transientGBuffer = false, primitiveId = false, clearViews = false, finalStorage = false;
  bool motion = false, visibility = false, slotImages = false;
  bool operator==(const TargetsKey&) const = default;
};
struct ShadowMapKey {
  size_t instances = 0;
  glm::dvec3 toSun{0.0};
  uint32_t size = 0;
  ShadowFormat format{};
  float biasConstant = 0.0f, biasSlope = 0.0f, biasClamp = 0.0f;
  bool operator==(const ShadowMapKey&) const = default;
};
struct SkyKey {
  size_t instances = 0;
  uint32_t width = 0, height = 0;
  bool reversedZ = false;
  DepthFormat depthFormat{};
  glm::dmat4 clipFromWorld{1.0};
  bool operator==(const SkyKey&) const = default;
};

// A cached pipeline: its id (shader variant and state), the render-pass compatibility class and
// subpass it is used in (graphics), and the values of the common specialization constants.
struct PipelineKey {
  std::string id;
  bool compute = false;
  uint32_t compatClass = 0, subpass = 0;
  std::vector<uint32_t> spec;
  auto operator<=>(const PipelineKey&) const = default;
};

// Clustered shading's buffers (renderer/gpu/cluster_buffers.cpp): device-local, sized for the frame;
// capacities in clusters and light-list entries grow when a frame runs out of room. (The header's
// copy for the CPU is per frame slot: FrameSlot::clusterHeader.) With --cluster-assign cpu: the
// CPU's cluster grid (renderer/core/cluster_grid.h); its copies for the GPU are per frame slot.
struct ClusterBuffers {
  Buffer header, clusters, pixelClusters, lists, binBits, binBoxes;
  uint32_t clusterCapacity = 0, listCapacity = 0;
  // Tests: cluster_clear starts the list count past the capacity, so every list overflows, empty
  // ones too (a capacity of 0 would let empty lists that come first fit: an order-dependent frame).
  bool listsFull = false;
  VkDeviceSize binBitsBytes = 0, binBoxBytes = 0;  // this frame's parts to clear
  ClusterGrid grid;
};

// Light setup on the GPU (renderer/gpu/gpu_lights.cpp): the scene's lights as uploaded, and scratch.
// `descs` holds the lights of `scene` at lights generation `generation` (LightList).
struct GpuLights {
  Buffer descs, scratch;
  VkDeviceSize uploadBytes = 0;  // this frame copies this many bytes of new descriptions (light_upload)
  const Scene* scene = nullptr;
  uint64_t generation = 0;
  uint64_t uploads = 0;  // how many times `descs` was written (tests: an unchanged scene uploads nothing)
  std::vector<PointLightDesc> checkCopy;  // with validation on: what `descs` holds, to catch a missed edit
};

// Frames in flight: the renderer records a frame into one slot while the GPU may still run the
// frame of the other (submitFrame; renderFrame waits for its own). A slot holds what a frame
// writes from the CPU and what the CPU reads after it (renderer/frame/frame_slots.cpp).
inline constexpr uint32_t kFrameSlots = 2;
// The targets a frame's side part writes: one image per slot when frames overlap.
inline constexpr std::array<Target, 2> kSlotTargets = {Target::DepthStencil, Target::Visibility};

struct FrameSlot {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  // A frame that overlaps (Renderer::overlap): its side part's command buffer (graphics queue),
  // the semaphore it signals, and the command buffer of the rest (compute queue's pool).
  VkCommandBuffer sideCmd = VK_NULL_HANDLE, computeCmd = VK_NULL_HANDLE;
  VkSemaphore sideDone = VK_NULL_HANDLE;
  // Set 0's per-frame buffers (written by the CPU before submission, or by light setup on the
  // GPU) and set 0 naming them: the other slot's frame may still read its own.
  Buffer frameBuffer, drawBuffer, lightBuffer, visibleBuffer, lightCountBuffer, visiblePositionBuffer;
  VkDescriptorSet sceneSet = VK_NULL_HANDLE;
  Buffer lightDescStaging;  // new light descriptions, copied into GpuLights::descs by light_upload
  Buffer clusterHeader;     // the cluster counters copied for the CPU (clustered frames)
  Buffer gridCells, gridLights;  // the cluster grid's cells and lights as the CPU wrote them (--cluster-assign cpu)
  VkQueryPool timestampPool = VK_NULL_HANDLE, occlusionPool = VK_NULL_HANDLE;
  uint32_t timestampCapacity = 0;

  // The frame in the slot, from its submission until it is retired (fence waited, stats complete).
  bool pending = false;
  FrameStats stats;        // what the CPU knew at submission; the GPU's figures when retired
  bool skyQuery = false;   // its skybox counted sky pixels ...
  SkyKey skyKey;           // ... for this camera, size and geometry
  bool gpuLightCounts = false, clusterCounts = false;  // counts to read from the GPU when retired
  std::chrono::steady_clock::time_point start;        // when its CPU work began
};

struct Renderer {
  GpuContext* ctx = nullptr;
  const Scene* scene = nullptr;

  // The scene on the GPU (gpu_scene.cpp).
  Buffer vertexBuffer, indexBuffer, icosahedronBuffer, materialBuffer;
  std::vector<Image> textures;      // the scene's, then white and flat-normal stand-ins
  std::vector<uint32_t> drawOrder;  // instance indices grouped by drawVariant()
  std::array<uint32_t, 9> drawVariants{};  // drawOrder[drawVariants[v], drawVariants[v+1]) has variant v (gpu_scene.h)
  VkSampler samplerRepeat = VK_NULL_HANDLE, samplerClamp = VK_NULL_HANDLE;
  VkSampler samplerShadow = VK_NULL_HANDLE, samplerPoint = VK_NULL_HANDLE;
  VkDescriptorSetLayout sceneSetLayout = VK_NULL_HANDLE, passSetLayout = VK_NULL_HANDLE;
  VkDescriptorSetLayout passSetLayoutInput = VK_NULL_HANDLE;  // set 1 with subpass inputs
  VkPipelineLayout pipelineLayout = VK_NULL_HANDLE;
  VkPipelineLayout pipelineLayoutInput = VK_NULL_HANDLE;      // single-pass lighting pipelines
  VkDescriptorPool descriptorPool = VK_NULL_HANDLE;  // set 0 of each frame slot
  // --gbuffer visibility (gpu/visibility_scene.cpp): the id's packing for this scene (or why the
  // scene or device cannot have it), gbuffer_resolve's set layouts (set 1 pushed, set 2 the scene's
  // vertices, indices, draws' geometry and textures, written once) and its pipeline layout.
  VisibilityPacking visibilityPacking;
  std::string visibilityRefusal;  // "" when the scene fits and the device can resolve
  Buffer drawGeometryBuffer;
  std::vector<std::pair<int, int>> textureGroups;  // (base colour, normal) texture per group; [0] = (-1, -1)
  VkDescriptorSetLayout resolveSetLayout = VK_NULL_HANDLE, resolveSceneSetLayout = VK_NULL_HANDLE;
  VkDescriptorPool resolvePool = VK_NULL_HANDLE;
  VkDescriptorSet resolveSceneSet = VK_NULL_HANDLE;
  VkPipelineLayout resolveLayout = VK_NULL_HANDLE;

  // Frame resources.
  // The options the targets were created for: as asked, but the G-buffer kind that runs
  // (frameOptions: never --gbuffer auto); method may be auto.
  RenderOptions options;
  Method method = Method::Deferred;  // the method this frame runs (options.method resolved by chooseMethod)
  std::string methodReason;
  ClusterBuffers clusters;
  // clustered_lighting's pixels an invocation: 1 (clustered_lighting.comp) or 2
  // (clustered_lighting2.comp: the same image, each staged light read once for two pixels; issue 39
  // measures which is faster on a GPU). initRenderer reads GBLENS_LIGHTING_PIXELS; tests set it.
  uint32_t lightingPixels = 1;
  GpuLights gpuLights;
  Buffer fairyBits;                 // fairy_bins' masks (--fairy-splat compute), the light bins' layout
  VkDeviceSize fairyBitsBytes = 0;  // this frame's part
  bool fairyCompute = false;        // this frame splats the fairies in compute
  bool clusterGrid = false;         // method clustered with the lights assigned on the CPU (--cluster-assign)
  std::string clusterAssignReason;
  bool computeClear = false;        // clear_gbuffer clears the G-buffer (not the render pass)
  std::string clearReason;
  bool visibility = false;          // this frame fills the G-buffer through the visibility id (--gbuffer)
  std::string gbufferReason;        // why it does or does not (frameGBuffer)
  // Side queue (renderer/frame/side_queue.h): whether frames may put their visibility pass on it
  // (GBLENS_OVERLAP and the device, decided once), whether this frame does, and why.
  bool overlapAllowed = false;
  std::string overlapAllowedReason;
  bool overlap = false;
  std::string overlapReason;
  // With overlapAllowed, every frame's last submission signals this timeline (the value: frames
  // submitted) and waits for the one before: the frames' non-side parts run in order whichever
  // queue each went to.
  VkSemaphore frameTimeline = VK_NULL_HANDLE;
  uint64_t framesSubmitted = 0;
  bool computeToneMap = false;      // tonemap_compute writes final (not the raster tonemap pass)
  std::string toneMapReason;
  std::string fairyReason;
  bool lightsOnGpu = false;    // this frame's lights are set up on the GPU (r.lights is empty then)
  std::string lightSetupReason;
  uint32_t visibleBound = 0;   // visible lights this frame: exact on the CPU path, the scene's lights on the GPU's
  bool targetsValid = false;
  std::optional<TargetsKey> targetsKey;  // what the targets were created for (none: uploaded ones)
  GraphTargets targets;
  // With overlapAllowed and a visibility G-buffer, the side part's targets (kSlotTargets) have an
  // image per frame slot: `targets` holds the current slot's, `parked` the other's.
  std::array<GraphTarget, 2> parked;
  uint32_t targetsSlot = 0;  // the slot whose images `targets` holds
  GraphCache graphCache;
  std::map<PipelineKey, VkPipeline> pipelines;
  std::array<FrameSlot, kFrameSlots> slots;
  uint32_t slot = 0;                  // the slot of the frame being recorded, or of the last one submitted
  std::vector<FrameStats> retired;    // frames in flight retired since finishFrames last returned them
  VkQueryPool statisticsPool = VK_NULL_HANDLE;  // culling frames only (synchronous)
  bool statisticsActive = false;  // this frame counts fragment invocations of the point-light pass
  bool skyQueryActive = false;    // this frame's skybox counts sky pixels (the slot's occlusion query)
  std::optional<SkyKey> skyKey;   // skyVisibilityKey() of the last count of a retired frame
  uint64_t skyPixels = UINT64_MAX;  // that count (UINT64_MAX: none yet); never a pending frame's
  std::array<Buffer, kTargetCount> readbackBuffers;
  std::array<CpuImage, kTargetCount> readback;  // filled for the targets a request named

  // This frame, as the frame function and the passes see it: `camera` draws (jittered by `jitter`
  // pixels under --jitter), `unjitteredCamera` is the frame's camera as captures record it.
  Camera camera, unjitteredCamera;
  glm::dvec2 jitter{0.0};
  FrameLights lights;
  glm::dmat4 lightClipFromWorld{1.0};
  gpu::FrameData frameData{};  // this frame's uniform data, as the shaders saw it
  std::vector<float> srgbDecode;  // probeSrgbDecode's table (empty until probed)
  std::optional<ShadowMapKey> shadowKey;  // what the shadow map was rendered for (reuse when unchanged)
  FrameStats stats;  // of the last synchronous frame (renderFrame)
};

inline FrameSlot& frameSlot(Renderer& r) { return r.slots[r.slot]; }
inline const FrameSlot& frameSlot(const Renderer& r) { return r.slots[r.slot]; }

}  // namespace gb
