// renderFrame: per-frame CPU work (view, draws, lights, frame data), target (re)creation,
// recording the frame graph, submission, timings, read-back and culling statistics.
#include "renderer/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>

#include "renderer/cluster_buffers.h"
#include "renderer/core/method_choice.h"
#include "renderer/frame.h"
#include "renderer/gpu_lights.h"
#include "renderer/gpu_scene.h"
#include "renderer/light_culling.h"
#include "renderer/passes/passes.h"
#include "renderer/render_targets.h"
#include "renderer/target_readback.h"
#include "renderer/vk/check.h"

namespace gb {

// ---- per-frame CPU work -----------------------------------------------------------------------

// Lights classified on the CPU (light_culling.h) and written to the light buffers.
static void uploadCpuLights(Renderer& r) {
  const RenderOptions& o = r.options;
  classifyLights(*r.scene, r.camera, o.time, stencilLayersOn(o, r.method, r.ctx->isCpu), r.lights);
  // (memcpy from an empty vector's null data() is undefined even for 0 bytes: UBSan reports it)
  if (!r.lights.eye.empty())
    std::memcpy(r.lightBuffer.mapped, r.lights.eye.data(), r.lights.eye.size() * sizeof(gpu::PointLight));
  if (!r.lights.visible.empty())
    std::memcpy(r.visibleBuffer.mapped, r.lights.visible.data(), r.lights.visible.size() * sizeof(uint32_t));
  gpu::LightCounts counts{};
  const uint32_t visible = uint32_t(r.lights.visible.size());
  counts.counts = glm::uvec4(visible, r.lights.culledFrustum, r.lights.culledEmpty, r.lights.culledSubpixel);
  counts.fairyDraw = glm::uvec4(6u, visible, 0u, 0u);
  std::memcpy(r.lightCountBuffer.mapped, &counts, sizeof(counts));
}

static void prepareFrame(Renderer& r) {
  const Scene& s = *r.scene;
  const RenderOptions& o = r.options;
  GB_ASSERT(!s.cameras.empty());
  const CameraDesc& cam = s.cameras[size_t(o.camera) < s.cameras.size() ? size_t(o.camera) : 0];
  r.camera = makeCamera(cam, o.width, o.height, o.reversedZ);
  r.lightClipFromWorld = shadowClipFromWorld(s);

  // Draws: camera-relative transforms formed in double.
  auto* draws = static_cast<gpu::DrawData*>(r.drawBuffer.mapped);
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
  r.lightsOnGpu = lightsOnGpu(*r.ctx, o, r.method, r.lightSetupReason);
  GB_ASSERT(s.lights.size() <= r.lightBuffer.size / sizeof(gpu::PointLight));
  if (r.lightsOnGpu) {
    prepareGpuLights(r, f);  // light_setup and light_compact do the rest
    r.visibleBound = uint32_t(s.lights.size());
  } else {
    uploadCpuLights(r);
    r.visibleBound = uint32_t(r.lights.visible.size());
    if (r.clusterGrid) writeClusterGrid(r);  // the lights of each cell of the cluster grid
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
  clusterFrameData(r.camera, r.visibleBound, f);
  if (r.clusterGrid) gridFrameData(r.clusters.grid.shape, f);
  std::memcpy(r.frameBuffer.mapped, &f, sizeof(f));
  r.frameData = f;
}

void runAfterFrame(Renderer& r, const std::function<void(FrameGraph&)>& build, const std::vector<Target>& handOff) {
  GB_ASSERT(r.targetsValid);
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

static VkQueryPool createQueryPool(GpuContext& ctx, VkQueryType type, uint32_t count,
                                   VkQueryPipelineStatisticFlags statistics = 0) {
  VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
  qci.queryType = type;
  qci.queryCount = count;
  qci.pipelineStatistics = statistics;
  VkQueryPool pool;
  VK_CHECK(vkCreateQueryPool(ctx.device, &qci, nullptr, &pool));
  return pool;
}

// Timestamps for every pass of `graph`, the skybox's occlusion query and the point-light
// pass's pipeline statistics when this frame uses them: created on first use, reset each frame.
static void resetQueries(Renderer& r, const FrameGraph& graph, const FrameRequest& request) {
  GpuContext& ctx = *r.ctx;
  if (r.skyQueryActive) {
    if (!r.occlusionPool) r.occlusionPool = createQueryPool(ctx, VK_QUERY_TYPE_OCCLUSION, 1);
    vkResetQueryPool(ctx.device, r.occlusionPool, 0, 1);
  }
  uint32_t queries = std::max(graph.timestampCount(), 2u);
  if (!r.timestampPool || r.timestampCapacity < queries) {
    if (r.timestampPool) vkDestroyQueryPool(ctx.device, r.timestampPool, nullptr);
    r.timestampCapacity = std::max(queries, 64u);
    r.timestampPool = createQueryPool(ctx, VK_QUERY_TYPE_TIMESTAMP, r.timestampCapacity);
  }
  vkResetQueryPool(ctx.device, r.timestampPool, 0, r.timestampCapacity);
  r.statisticsActive = request.cullingStats && ctx.features.pipelineStatistics;
  if (r.statisticsActive) {
    if (!r.statisticsPool)
      r.statisticsPool = createQueryPool(ctx, VK_QUERY_TYPE_PIPELINE_STATISTICS, 1,
                                         VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT);
    vkResetQueryPool(ctx.device, r.statisticsPool, 0, 1);
  }
}

static void recordAndSubmit(Renderer& r, FrameGraph& graph) {
  GpuContext& ctx = *r.ctx;
  VK_CHECK(vkResetCommandBuffer(r.cmd, 0));
  VkCommandBufferBeginInfo bi{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  bi.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(r.cmd, &bi));
  graph.record(ctx, r.cmd, r.targets, r.graphCache, ctx.features.timestamps ? r.timestampPool : VK_NULL_HANDLE);
  VK_CHECK(vkEndCommandBuffer(r.cmd));
  VkSubmitInfo si{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  si.commandBufferCount = 1;
  si.pCommandBuffers = &r.cmd;
  VK_CHECK(vkResetFences(ctx.device, 1, &r.fence));
  r.submitted = std::chrono::steady_clock::now();
  VK_CHECK(vkQueueSubmit(ctx.queue, 1, &si, r.fence));
  VK_CHECK(vkWaitForFences(ctx.device, 1, &r.fence, VK_TRUE, UINT64_MAX));
}

static uint64_t queryResult(GpuContext& ctx, VkQueryPool pool, uint32_t query) {
  uint64_t v = 0;
  VK_CHECK(vkGetQueryPoolResults(ctx.device, pool, query, 1, sizeof(v), &v, sizeof(v),
                                 VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
  return v;
}

// Light counts, the sky count and per-pass GPU times of the frame just submitted.
static void collectStats(Renderer& r, FrameStats& st) {
  GpuContext& ctx = *r.ctx;
  const FrameLights& l = r.lights;
  st.lights = uint32_t(r.scene->lights.size());
  st.lightsVisible = uint32_t(l.visible.size());
  st.lightsInside = uint32_t(l.visible.size()) - l.stencilCount;
  st.stencilLayers = l.layerStarts.empty() ? 0u : uint32_t(l.layerStarts.size() - 1);
  st.lightsCulled = l.culledFrustum + l.culledEmpty + l.culledSubpixel;
  st.lightsCulledFrustum = l.culledFrustum;
  st.lightsCulledEmpty = l.culledEmpty;
  st.lightsCulledSubpixel = l.culledSubpixel;
  if (r.skyQueryActive) {
    // Non-zero exactly when some sample passed (a non-precise query may overcount).
    r.skyPixels = queryResult(ctx, r.occlusionPool, 0);
    r.skyKey = skyVisibilityKey(r);
    st.skyPixels = int64_t(r.skyPixels);
  }
  if (!ctx.features.timestamps) return;
  const double period = ctx.properties.limits.timestampPeriod * 1e-6;
  double first = 1e300, last = -1e300;
  for (size_t i = 0; i < st.passes.size(); ++i) {
    if (st.passes[i].skipped) continue;
    double t0 = double(queryResult(ctx, r.timestampPool, uint32_t(2 * i))) * period;
    double t1 = double(queryResult(ctx, r.timestampPool, uint32_t(2 * i + 1))) * period;
    st.passes[i].ms = t1 - t0;
    first = std::min(first, t0);
    last = std::max(last, t1);
  }
  if (last > first) st.gpuMs = last - first;
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

const FrameStats& renderFrame(Renderer& r, const RenderOptions& options, const FrameRequest& userRequest) {
  auto start = std::chrono::steady_clock::now();
  const MethodChoice choice =
      chooseMethod(options, r.ctx->isCpu ? DeviceKind::Cpu : DeviceKind::Gpu, r.scene->lights.size());
  GB_ASSERT(choice.method != Method::Auto && (options.method != Method::Auto || choice.method != Method::Forward));
  const FrameRequest request = completeRequest(userRequest, options, choice.method);
  ensureTargets(r, options);
  r.computeClear = computeClears(*r.ctx, options, choice.method, r.clearReason);
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

  FrameGraph graph;
  r.skyQueryActive = false;
  buildFrame(graph, r, request);
  resetQueries(r, graph, request);
  const auto recordStart = std::chrono::steady_clock::now();
  const uint64_t compiled = r.graphCache.compilations, reused = r.graphCache.reuses;
  recordAndSubmit(r, graph);

  FrameStats& st = r.stats;
  st = FrameStats{};
  st.frameMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  st.cpuMs = std::chrono::duration<double, std::milli>(r.submitted - start).count();
  st.recordMs = std::chrono::duration<double, std::milli>(r.submitted - recordStart).count();
  st.groupsCompiled = uint32_t(r.graphCache.compilations - compiled);
  st.groupsReused = uint32_t(r.graphCache.reuses - reused);
  st.passes = graph.stats();
  st.method = name(r.method);
  st.methodReason = r.methodReason;
  collectStats(r, st);
  st.lightSetup = r.lightsOnGpu ? "gpu" : "cpu";
  st.lightSetupReason = r.lightSetupReason;
  // Light setup on the GPU: its counts, and the lights themselves when the frame is inspected.
  if (r.lightsOnGpu) readGpuLights(r, st, !request.readback.empty() || request.cullingStats);
  if (r.method == Method::Clustered) {
    st.clusters = r.clusterGrid ? gridClusterStats(r) : collectClusterStats(r);
    st.clusterAssign = r.clusterGrid ? "cpu" : "gpu";
    st.clusterAssignReason = r.clusterAssignReason;
  }
  for (Target t : request.readback) r.readback[size_t(t)] = unpackReadback(r, t);
  if (request.cullingStats && options.coverage) st.culling = cullingStats(r, st);
  return st;
}

void initRenderer(Renderer& r, GpuContext& ctx, const Scene& scene) {
  r.ctx = &ctx;
  r.scene = &scene;
  uploadScene(r);
  createFrameBuffers(r);
  createDescriptors(r);
  writeSceneSet(r);
  sortDraws(r);
  VkCommandBufferAllocateInfo cai{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  cai.commandPool = ctx.commandPool;
  cai.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  cai.commandBufferCount = 1;
  VK_CHECK(vkAllocateCommandBuffers(ctx.device, &cai, &r.cmd));
  setName(ctx, uint64_t(r.cmd), VK_OBJECT_TYPE_COMMAND_BUFFER, "frame");
  VkFenceCreateInfo fci{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VK_CHECK(vkCreateFence(ctx.device, &fci, nullptr, &r.fence));
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
  if (r.timestampPool) vkDestroyQueryPool(ctx.device, r.timestampPool, nullptr);
  if (r.statisticsPool) vkDestroyQueryPool(ctx.device, r.statisticsPool, nullptr);
  if (r.occlusionPool) vkDestroyQueryPool(ctx.device, r.occlusionPool, nullptr);
  for (Buffer* b : {&r.vertexBuffer, &r.indexBuffer, &r.icosahedronBuffer, &r.frameBuffer, &r.drawBuffer,
                    &r.materialBuffer, &r.lightBuffer, &r.visibleBuffer, &r.lightCountBuffer})
    destroyBuffer(ctx, *b);
  for (Image& img : r.textures) destroyImage(ctx, img);
  for (VkSampler s : {r.samplerRepeat, r.samplerClamp, r.samplerShadow, r.samplerPoint}) vkDestroySampler(ctx.device, s, nullptr);
  vkDestroyDescriptorPool(ctx.device, r.descriptorPool, nullptr);
  vkDestroyPipelineLayout(ctx.device, r.pipelineLayout, nullptr);
  vkDestroyPipelineLayout(ctx.device, r.pipelineLayoutInput, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, r.sceneSetLayout, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, r.passSetLayout, nullptr);
  vkDestroyDescriptorSetLayout(ctx.device, r.passSetLayoutInput, nullptr);
  vkFreeCommandBuffers(ctx.device, ctx.commandPool, 1, &r.cmd);
  vkDestroyFence(ctx.device, r.fence, nullptr);
  r = Renderer{};
}

}  // namespace gb
