// renderFrame and submitFrame: per-frame CPU work (view, draws, lights, frame data), target
// (re)creation, recording the frame graph into a frame slot and submitting it; renderFrame then
// waits for it (statistics, read-back, culling statistics). Frame slots: frame_slots.cpp.
#include "renderer/frame/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <sstream>

#include "renderer/core/camera_motion.h"
#include "renderer/core/method_choice.h"
#include "renderer/frame/frame.h"
#include "renderer/frame/frame_slots.h"
#include "renderer/frame/side_queue.h"
#include "renderer/frame/light_culling.h"
#include "renderer/gpu/cluster_buffers.h"
#include "renderer/gpu/gpu_lights.h"
#include "renderer/gpu/gpu_scene.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/gpu/visibility_scene.h"
#include "renderer/passes/passes.h"
#include "renderer/readback/target_readback.h"
#include "renderer/vk/check.h"

namespace gb {

// ---- per-frame CPU work -----------------------------------------------------------------------

// Lights classified on the CPU (light_culling.h) and written to the light buffers.
static void uploadCpuLights(Renderer& r) {
  const RenderOptions& o = r.options;
  classifyLights(*r.scene, r.camera, o.time, stencilLayersOn(o, r.method, r.ctx->isCpu), r.lights);
  // (memcpy from an empty vector's null data() is undefined even for 0 bytes: UBSan reports it)
  FrameSlot& slot = frameSlot(r);
  if (!r.lights.eye.empty())
    std::memcpy(slot.lightBuffer.mapped, r.lights.eye.data(), r.lights.eye.size() * sizeof(gpu::PointLight));
  if (!r.lights.visible.empty())
    std::memcpy(slot.visibleBuffer.mapped, r.lights.visible.data(), r.lights.visible.size() * sizeof(uint32_t));
  auto* positions = static_cast<glm::vec4*>(slot.visiblePositionBuffer.mapped);
  for (size_t v = 0; v < r.lights.visible.size(); ++v) positions[v] = r.lights.eye[r.lights.visible[v]].eyePositionRadius;
  gpu::LightCounts counts{};
  const uint32_t visible = uint32_t(r.lights.visible.size());
  counts.counts = glm::uvec4(visible, r.lights.culledFrustum, r.lights.culledEmpty, r.lights.culledSubpixel);
  counts.fairyDraw = glm::uvec4(6u, visible, 0u, 0u);
  std::memcpy(slot.lightCountBuffer.mapped, &counts, sizeof(counts));
}

static void prepareFrame(Renderer& r) {
  const Scene& s = *r.scene;
  const RenderOptions& o = r.options;
  GB_ASSERT(!s.cameras.empty());
  const CameraDesc& cam = s.cameras[size_t(o.camera) < s.cameras.size() ? size_t(o.camera) : 0];
  // The frame's camera at its time (camera_motion), drawn with the jitter's offset (camera_motion.h).
  const glm::dvec3 centre = s.bounds.center();
  const double radius = s.bounds.radius();
  r.unjitteredCamera = makeCamera(movedCamera(cam, o, centre, radius, o.time), o.width, o.height, o.reversedZ);
  r.jitter = frameJitter(o);
  r.camera = jitteredCamera(r.unjitteredCamera, r.jitter);
  r.lightClipFromWorld = shadowClipFromWorld(s);

  // Draws: camera-relative transforms formed in double.
  auto* draws = static_cast<gpu::DrawData*>(frameSlot(r).drawBuffer.mapped);
  const std::vector<uint32_t> firstPrimitive = firstPrimitiveIds(s);
  for (size_t i = 0; i < s.instances.size(); ++i) {
    const Instance& inst = s.instances[i];
    glm::dmat4 eyeFromObject = r.camera.eyeFromWorld * inst.worldFromObject;
    glm::dmat3 normal = glm::transpose(glm::inverse(glm::dmat3(eyeFromObject)));
    gpu::DrawData d{};
    d.eyeFromObject = glm::mat4(eyeFromObject);
    d.normalEyeFromObject = glm::mat4(glm::mat3(normal));
    d.lightClipFromObject = glm::mat4(r.lightClipFromWorld * inst.worldFromObject);
    d.info = glm::uvec4(uint32_t(s.meshes[inst.mesh].material), glm::determinant(glm::dmat3(inst.worldFromObject)) < 0.0,
                        firstPrimitive[i], 0u);
    draws[i] = d;
  }

  gpu::FrameData f{};
  r.lightsOnGpu = lightsOnGpu(*r.ctx, o, r.method, r.clusterGrid ? &r.clusterAssignReason : nullptr, r.lightSetupReason);
  GB_ASSERT(s.lights.size() <= frameSlot(r).lightBuffer.size / sizeof(gpu::PointLight));
  if (r.lightsOnGpu) {
    prepareGpuLights(r, f);  // light_setup and light_compact do the rest
    r.visibleBound = uint32_t(s.lights.size());
  } else {
    uploadCpuLights(r);
    r.visibleBound = uint32_t(r.lights.visible.size());
    std::string why;  // the lights of each cell of the cluster grid, or the occupied clusters if they do not fit
    if (r.clusterGrid && !writeClusterGrid(r, why)) r.clusterGrid = false, r.clusterAssignReason = why;
  }

  f.clipFromEye = glm::mat4(r.camera.clipFromEye);
  f.eyeFromClip = glm::mat4(r.camera.eyeFromClip);
  f.worldFromEye = glm::mat4(r.camera.worldFromEye);
  f.lightClipFromEye = glm::mat4(r.lightClipFromWorld * r.camera.worldFromEye);
  f.viewport = glm::vec4(o.width, o.height, 1.0 / o.width, 1.0 / o.height);
  const glm::dmat4& p = r.camera.clipFromEye;
  f.eyeRay = glm::vec4(1.0 / p[0][0], 1.0 / p[1][1], p[2][0], p[2][1]);
  glm::dvec3 sunEye = glm::normalize(glm::dmat3(r.camera.eyeFromWorld) * s.sun.toSun);
  f.sunEyeDirection = glm::vec4(glm::vec3(sunEye), s.sun.enabled ? 1.0f : 0.0f);
  f.sunColor = glm::vec4(s.sun.color, 0.0f);
  f.ambientColor = glm::vec4(s.sky.ambient, 0.0f);
  f.skyZenith = glm::vec4(s.sky.zenith, 0.0f);
  f.skyHorizon = glm::vec4(s.sky.horizon, o.sky ? 1.0f : 0.0f);  // w: skyEnabled() in sky.glsl
  f.skyGround = glm::vec4(s.sky.ground, 0.0f);
  f.params = glm::vec4(o.exposure, 0.05f, 1.0f / float(o.shadowMapSize), float(o.time));
  f.counts = glm::uvec4(uint32_t(r.lights.visible.size()), uint32_t(r.lights.visible.size()) - r.lights.stencilCount,
                        0u, 0u);
  if (o.motion) {  // the previous frame: time - time_step, unjittered (the scene's instances do not move)
    const Camera previous =
        makeCamera(movedCamera(cam, o, centre, radius, o.time - o.timeStep), o.width, o.height, o.reversedZ);
    f.prevClipFromEye = glm::mat4(previous.clipFromWorld * r.camera.worldFromEye);
    f.unjitteredClipFromEye = glm::mat4(r.unjitteredCamera.clipFromEye);
    f.jitter = glm::vec4(r.jitter, 2.0 * r.jitter.x / o.width, 2.0 * r.jitter.y / o.height);
  }
  clusterFrameData(r.camera, r.visibleBound, f);
  if (r.clusterGrid) gridFrameData(r.clusters.grid.shape, f);
  std::memcpy(frameSlot(r).frameBuffer.mapped, &f, sizeof(f));
  r.frameData = f;
}

void runAfterFrame(Renderer& r, const std::function<void(FrameGraph&)>& build, const std::vector<Target>& handOff) {
  GB_ASSERT(r.targetsValid && !framesInFlight(r));
  FrameGraph graph;
  build(graph);
  if (!handOff.empty()) addSampleAfterPass(graph, handOff);
  submitOnce(*r.ctx, [&](VkCommandBuffer cmd) { graph.record(*r.ctx, cmd, r.targets, r.graphCache, VK_NULL_HANDLE); });
}

// ---- the frame ----------------------------------------------------------------------------------

const FrameStats& renderCountingFrame(Renderer& r, const RenderOptions& options, FrameRequest request) {
  RenderOptions counting = options;
  counting.coverage = true;
  counting.keepGBuffer = true;  // the ideal pairs are counted on the eye depth
  request.cullingStats = true;
  return renderFrame(r, counting, request);
}

// Culling statistics count from coverage_masked and the eye depth (forward has no eye-depth
// target: its surface points come from the hardware depth).
static Target cullingDepthSource(Method method) {
  return method == Method::Forward ? Target::DepthStencil : Target::Depth;
}

static FrameRequest completeRequest(const FrameRequest& user, const RenderOptions& o, Method method) {
  FrameRequest request = user;
  if (request.cullingStats && o.coverage)
    for (Target t : {Target::CoverageMasked, cullingDepthSource(method)})
      if (std::find(request.readback.begin(), request.readback.end(), t) == request.readback.end())
        request.readback.push_back(t);
  return request;
}

// The light counts of the CPU path (light setup on the GPU: retireFrame reads the GPU's).
static void cpuLightCounts(const Renderer& r, FrameStats& st) {
  const FrameLights& l = r.lights;
  st.lights = uint32_t(r.scene->lights.size());
  st.lightsVisible = uint32_t(l.visible.size());
  st.lightsInside = uint32_t(l.visible.size()) - l.stencilCount;
  st.stencilLayers = l.layerStarts.empty() ? 0u : uint32_t(l.layerStarts.size() - 1);
  st.lightsCulled = l.culledFrustum + l.culledEmpty + l.culledSubpixel;
  st.lightsCulledFrustum = l.culledFrustum;
  st.lightsCulledEmpty = l.culledEmpty;
  st.lightsCulledSubpixel = l.culledSubpixel;
}

// Point-light shader runs (coverage_masked) against the ideal pixel-light pairs.
static CullingStats cullingStats(Renderer& r, const FrameStats& st) {
  CullingStats c;
  c.valid = true;
  const CpuImage& masked = r.readback[size_t(Target::CoverageMasked)];
  for (uint32_t y = 0; y < masked.height; ++y)
    for (uint32_t x = 0; x < masked.width; ++x) c.invocations += masked.raw(x, y, 0);
  const Target depth = cullingDepthSource(r.method);
  c.idealPairs = idealPairs(r.camera, depth == Target::Depth ? r.readback[size_t(Target::Depth)]
                                                             : eyeDepthFromHardware(r.camera, r.readback[size_t(depth)]),
                            r.lights.eye);
  c.workOverIdeal = c.idealPairs ? double(c.invocations) / double(c.idealPairs) : 0.0;
  bool pointLightsRan = false;
  for (const PassStat& p : st.passes) pointLightsRan |= p.name == "point_lights" && !p.skipped;
  if (r.statisticsActive && pointLightsRan) c.pipelineInvocations = queryResult(*r.ctx, r.statisticsPool, 0);
  return c;
}

// The frame's CPU part, into the current slot (its previous frame retired), up to submission:
// method, targets, per-frame data, the graph, recording. The slot's FrameStats get what the CPU
// knows; retireFrame adds what the GPU measured and counted.
static FrameRequest recordFrame(Renderer& r, const RenderOptions& asked, const FrameRequest& userRequest) {
  const auto start = std::chrono::steady_clock::now();
  const MethodChoice choice = chooseMethod(asked, r.ctx->isCpu ? DeviceKind::Cpu : DeviceKind::Gpu, r.scene->lights.size());
  GB_ASSERT(choice.method != Method::Auto && (asked.method != Method::Auto || choice.method != Method::Forward));
  // The G-buffer kind resolved before anything reads it (targets, absences, the snapshot's options).
  const GBufferChoice gbuffer = frameGBuffer(r, asked);
  RenderOptions options = asked;
  options.gbuffer = gbuffer.gbuffer;
  const FrameRequest request = completeRequest(userRequest, options, choice.method);
  ensureTargets(r, options);
  r.computeClear = computeClears(*r.ctx, options, choice.method, r.clearReason);
  r.visibility = visibilityFrame(options);
  r.gbufferReason = gbuffer.reason;
  r.computeToneMap = computeToneMap(*r.ctx, options, choice.method, r.toneMapReason);
  // Transient images have no memory to copy from, and forward frames never write the G-buffer.
  for (Target t : request.readback) {
    GB_ASSERT(!r.targets[size_t(t)].image.desc.transient);
    GB_ASSERT(choice.method != Method::Forward || targetInfo(t).role != TargetRole::GBuffer);
  }
  r.options = options;
  r.method = choice.method;
  r.methodReason = choice.reason;
  r.clusterGrid = clusterGridOn(options, r.ctx->isCpu ? DeviceKind::Cpu : DeviceKind::Gpu, r.method, r.clusterAssignReason);
  prepareFrame(r);
  if (r.method == Method::Clustered && !r.clusterGrid) ensureClusterBuffers(r, r.visibleBound);
  r.fairyCompute = fairiesInCompute(*r.ctx, options, r.fairyReason);
  if (r.fairyCompute && options.fairies) ensureFairyBits(r, r.visibleBound);
  r.overlap = overlapFrame(r, r.overlapReason);
  useSlotTargets(r);  // this slot's depth and id (frames that may overlap have one per slot)

  FrameGraph graph;
  r.skyQueryActive = false;
  buildFrame(graph, r, request);
  overlapRecorded(r, graph);  // not when the compute part has a raster pass
  resetQueries(r, graph, request);
  const auto recordStart = std::chrono::steady_clock::now();
  const uint64_t compiled = r.graphCache.compilations, reused = r.graphCache.reuses;
  const auto submitted = recordAndSubmit(r, graph);

  FrameSlot& slot = frameSlot(r);
  FrameStats& st = slot.stats;
  st = FrameStats{};
  st.cpuMs = std::chrono::duration<double, std::milli>(submitted - start).count();
  st.recordMs = std::chrono::duration<double, std::milli>(submitted - recordStart).count();
  st.groupsCompiled = uint32_t(r.graphCache.compilations - compiled);
  st.groupsReused = uint32_t(r.graphCache.reuses - reused);
  st.passes = graph.stats();
  for (PassStat& p : st.passes) p.ms = p.skipped ? 0.0 : -1.0;  // -1 until the frame is retired
  st.gpuMs = -1.0;
  st.method = name(r.method);
  st.methodReason = r.methodReason;
  st.gbuffer = name(options.gbuffer);
  st.gbufferReason = r.gbufferReason;
  st.overlap = r.overlap;
  st.overlapReason = r.overlapReason;
  st.lightSetup = r.lightsOnGpu ? "gpu" : "cpu";
  st.lightSetupReason = r.lightSetupReason;
  cpuLightCounts(r, st);
  if (r.method == Method::Clustered) {
    st.clusterAssign = r.clusterGrid ? "cpu" : "gpu";
    st.clusterAssignReason = r.clusterAssignReason;
    if (r.clusterGrid) st.clusters = gridClusterStats(r);  // known on the CPU; the GPU's counts when retired
  }
  slot.start = start;
  slot.skyQuery = r.skyQueryActive;
  slot.skyKey = skyVisibilityKey(r);
  slot.gpuLightCounts = r.lightsOnGpu;
  slot.clusterCounts = r.method == Method::Clustered && !r.clusterGrid;
  return request;
}

const FrameStats& renderFrame(Renderer& r, const RenderOptions& options, const FrameRequest& userRequest) {
  retireFrames(r);  // frames in flight first (their stats wait in r.retired for finishFrames)
  nextFrameSlot(r);
  const FrameRequest request = recordFrame(r, options, userRequest);
  FrameStats& st = r.stats;
  st = retireFrame(r, frameSlot(r));
  // Light setup on the GPU: the lights themselves when the frame is inspected.
  if (r.lightsOnGpu && (!request.readback.empty() || request.cullingStats)) readGpuLights(r);
  for (Target t : request.readback) r.readback[size_t(t)] = unpackReadback(r, t);
  if (request.cullingStats && options.coverage) st.culling = cullingStats(r, st);
  return st;
}

void submitFrame(Renderer& r, const RenderOptions& options) {
  // Coverage frames count per pixel for read-backs and culling statistics: renderFrame's.
  GB_ASSERT(!options.coverage);
  // New targets: the frames in flight finish on the old ones first (their sky counts belong there).
  if (!targetsCurrent(r, frameOptions(r, options))) retireFrames(r);
  nextFrameSlot(r);  // waits for the frame that last used this slot
  recordFrame(r, options, {});
}

// GBLENS_LIGHTING_PIXELS: clustered_lighting's variant for an A/B run without rebuilding. Any
// value but 1 or 2 stops the program, so a mistyped run does not time the default as the variant.
static uint32_t lightingPixelsFromEnvironment() {
  const char* v = std::getenv("GBLENS_LIGHTING_PIXELS");
  if (!v || !*v || std::strcmp(v, "1") == 0) return 1;
  if (std::strcmp(v, "2") == 0) return 2;
  std::fprintf(stderr, "gblens: GBLENS_LIGHTING_PIXELS=%s: 1 or 2 (clustered_lighting's pixels an invocation)\n", v);
  std::exit(2);
}

void initRenderer(Renderer& r, GpuContext& ctx, const Scene& scene) {
  r.ctx = &ctx;
  r.lightingPixels = lightingPixelsFromEnvironment();
  decideOverlapAllowed(r);  // GBLENS_OVERLAP and the device's queues
  r.scene = &scene;
  uploadScene(r);
  createDescriptors(r);
  createFrameSlots(r);
  sortDraws(r);
  createVisibilityScene(r);  // --gbuffer visibility: the id's packing, gbuffer_resolve's scene set
}

void destroyRenderer(Renderer& r) {
  if (!r.ctx) return;
  GpuContext& ctx = *r.ctx;
  vkDeviceWaitIdle(ctx.device);
  destroyTargets(r);
  destroyClusterBuffers(r);
  destroyGpuLights(r);
  destroyGraphCache(ctx, r.graphCache);
  for (auto& [k, p] : r.pipelines) vkDestroyPipeline(ctx.device, p, nullptr);
  if (r.statisticsPool) vkDestroyQueryPool(ctx.device, r.statisticsPool, nullptr);
  destroyFrameSlots(r);
  destroyVisibilityScene(r);
  for (Buffer* b : {&r.vertexBuffer, &r.indexBuffer, &r.icosahedronBuffer, &r.materialBuffer}) destroyBuffer(ctx, *b);
  for (Image& img : r.textures) destroyImage(ctx, img);
  for (VkSampler s : {r.samplerRepeat, r.samplerClamp, r.samplerShadow, r.samplerPoint}) vkDestroySampler(ctx.device, s, nullptr);
  vkDestroyPipelineLayout(ctx.device, r.pipelineLayout, nullptr);
  vkDestroyPipelineLayout(ctx.device, r.pipelineLayoutInput, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, r.sceneSetLayout, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, r.passSetLayout, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, r.passSetLayoutInput, nullptr);
  r = Renderer{};
}

}  // namespace gb
