// renderFrame: per-frame CPU work (view, draws, lights, frame data), target (re)creation,
// recording the frame graph, submission, timings, read-back and culling statistics.
#include "renderer/renderer.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <sstream>

#include "renderer/frame.h"
#include "renderer/light_culling.h"
#include "renderer/passes/passes.h"
#include "renderer/vk/check.h"

namespace gb {

// ---- targets -------------------------------------------------------------------------------

bool primitiveIdOn(const GpuContext& ctx, const RenderOptions& o) { return o.primitiveId && ctx.features.primitiveId; }

std::vector<Target> readableTargets(const Renderer& r, const RenderOptions& o) {
  std::vector<Target> out;
  for (const TargetInfo& info : targetTable()) {
    if (targetAbsence(info.target, o, r.scene->sun.enabled) != Absent::No) continue;
    if (info.target == Target::PrimitiveId && !primitiveIdOn(*r.ctx, o)) continue;
    out.push_back(info.target);
  }
  return out;
}

FrameRequest captureRequest(const std::vector<Target>& targets, const RenderOptions& o) {
  FrameRequest r;
  r.readback = targets;
  auto has = [&](Target t) { return std::find(targets.begin(), targets.end(), t) != targets.end(); };
  r.cullingStats = o.coverage && has(Target::CoverageMasked) && has(Target::Depth);
  return r;
}

static std::string targetsKey(const GpuContext& ctx, const Scene& s, const RenderOptions& o) {
  std::ostringstream k;
  k << o.width << 'x' << o.height << ' ' << name(o.normalFormat) << ' ' << name(o.depthFormat) << ' '
    << name(o.accumFormat) << ' ' << name(o.shadowFormat) << ' ' << (s.sun.enabled ? o.shadowMapSize : 1) << ' '
    << o.coverage << ' ' << transientGBuffer(o) << ' ' << primitiveIdOn(ctx, o) << ' '
    << name(o.position) << ' ' << ctx.deviceName;
  return k.str();
}

VkExtent2D targetExtent(const GpuContext& ctx, Target t, const Scene& s, const RenderOptions& o) {
  // Targets this frame does not compute keep a valid, tiny 1x1 image.
  bool unused = false;
  switch (t) {
    case Target::CoverageMasked:
    case Target::CoverageFull: unused = !o.coverage; break;
    case Target::PrimitiveId: unused = !primitiveIdOn(ctx, o); break;
    case Target::Position: unused = o.position == PositionSource::Depth; break;
    case Target::ShadowMap: unused = !s.sun.enabled; break;
    default: break;
  }
  if (unused) return {1, 1};
  if (targetInfo(t).size == SizeRule::ShadowMap) return {o.shadowMapSize, o.shadowMapSize};
  return {o.width, o.height};
}

bool targetTransient(Target t, const RenderOptions& o) {
  const bool placeholder = t == Target::Position && o.position == PositionSource::Depth;
  return targetInfo(t).role == TargetRole::GBuffer && transientGBuffer(o) && !placeholder;
}

// Usage flags from the target's role (renderer/core/targets.h).
static VkImageUsageFlags targetUsage(TargetRole role, bool transient) {
  const VkImageUsageFlags color = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
                                  VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  switch (role) {
    case TargetRole::GBuffer:
      return transient ? (VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT) : color;
    case TargetRole::DepthStencil:
      return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT |
             VK_IMAGE_USAGE_INPUT_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case TargetRole::ShadowMap:
      return VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT | VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    case TargetRole::Light: return color | VK_IMAGE_USAGE_STORAGE_BIT;
    case TargetRole::Display: return color;
    case TargetRole::Counter:
      return VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT |
             VK_IMAGE_USAGE_SAMPLED_BIT;
    case TargetRole::Id:
      return VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_SAMPLED_BIT;
  }
  GB_ASSERT(!"target role");
  return 0;
}

static ImageDesc targetDesc(const GpuContext& ctx, Target t, const Scene& s, const RenderOptions& o) {
  ImageDesc d;
  d.format = targetFormat(t, o);
  VkExtent2D e = targetExtent(ctx, t, s, o);
  d.width = e.width;
  d.height = e.height;
  d.name = targetName(t);
  d.transient = targetTransient(t, o);
  // An unused stored position is a 1x1 placeholder only ever bound for sampling.
  d.usage = t == Target::Position && o.position == PositionSource::Depth ? VkImageUsageFlags(VK_IMAGE_USAGE_SAMPLED_BIT)
                                                                          : targetUsage(targetInfo(t).role, d.transient);
  return d;
}

static void destroyTargets(Renderer& r) {
  GpuContext& ctx = *r.ctx;
  for (GraphTarget& t : r.targets) {
    destroyImage(ctx, t.image);
    t = GraphTarget{};
  }
  for (Buffer& b : r.readbackBuffers) destroyBuffer(ctx, b);
  clearFramebuffers(ctx, r.graphCache);
  r.shadowKey.clear();
  r.skyKey.clear();
  r.targetsValid = false;
}

static void ensureTargets(Renderer& r, const RenderOptions& o) {
  std::string key = targetsKey(*r.ctx, *r.scene, o);
  if (r.targetsValid && key == r.targetsKey) return;
  vkDeviceWaitIdle(r.ctx->device);
  destroyTargets(r);
  for (size_t i = 0; i < kTargetCount; ++i)
    r.targets[i].image = createImage(*r.ctx, targetDesc(*r.ctx, Target(i), *r.scene, o));
  r.targets[size_t(Target::ShadowMap)].keep = true;  // reused while the sun and geometry stay
  r.targetsValid = true;
  r.targetsKey = key;
}

// ---- pipelines and descriptors ---------------------------------------------------------------

VkPipeline graphicsPipeline(Renderer& r, const PassContext& pc, const std::string& id,
                            const std::function<void(GraphicsPipelineDesc&)>& fill) {
  std::string key = id + "@" + pc.compatKey + "#";
  for (const SpecConstant& c : commonSpec(r)) key += std::to_string(c.value) + ",";
  VkPipeline& p = r.pipelines[key];
  if (!p) {
    GraphicsPipelineDesc d;
    d.renderPass = pc.renderPass;
    d.subpass = pc.subpass;
    d.layout = r.pipelineLayout;
    d.spec = commonSpec(r);
    d.colorBlend.assign(pc.colorAttachments, BlendState{});
    fill(d);
    GB_ASSERT(d.colorBlend.size() == pc.colorAttachments);
    p = createGraphicsPipeline(*r.ctx, d);
  }
  return p;
}

VkPipeline computePipeline(Renderer& r, const std::string& shader) {
  std::string key = shader + "@compute#";
  std::vector<SpecConstant> spec = commonSpec(r);
  for (const SpecConstant& c : spec) key += std::to_string(c.value) + ",";
  VkPipeline& p = r.pipelines[key];
  if (!p) p = createComputePipeline(*r.ctx, shader, spec, r.pipelineLayout);
  return p;
}

std::vector<SpecConstant> commonSpec(const Renderer& r) {
  uint32_t normal = 0;
  switch (r.options.normalFormat) {
    case NormalFormat::Rgba16f: normal = gpu::kNormalRgba16f; break;
    case NormalFormat::Rgba8Snorm: normal = gpu::kNormalRgba8Snorm; break;
    case NormalFormat::OctRg16: normal = gpu::kNormalOctRg16; break;
    case NormalFormat::Rgb10a2: normal = gpu::kNormalRgb10a2; break;
  }
  uint32_t position = gpu::kPositionDepth;
  if (r.options.position != PositionSource::Depth)
    position = r.options.positionSpace == PositionSpace::World ? gpu::kPositionWorld : gpu::kPositionCamera;
  return {{gpu::kSpecEyeDepth, r.options.eyeDepth ? 1u : 0u},
          {gpu::kSpecPosition, position},
          {gpu::kSpecReversedZ, r.options.reversedZ ? 1u : 0u},
          {gpu::kSpecNormalEncoding, normal},
          {gpu::kSpecCoverage, r.options.coverage ? 1u : 0u}};
}

void bindDescriptors(Renderer& r, VkCommandBuffer cmd, VkPipelineLayout layout, std::initializer_list<PassImage> images,
                     VkPipelineBindPoint bindPoint) {
  vkCmdBindDescriptorSets(cmd, bindPoint, layout, gpu::kSetScene, 1, &r.sceneSet, 0, nullptr);
  if (images.size() == 0) return;
  std::vector<VkDescriptorImageInfo> infos;
  infos.reserve(images.size());
  std::vector<VkWriteDescriptorSet> writes;
  for (const PassImage& img : images) {
    infos.push_back({img.sampler, img.view, img.layout});
    VkWriteDescriptorSet w{VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET};
    w.dstBinding = img.binding;
    w.descriptorCount = 1;
    w.descriptorType = img.type;
    w.pImageInfo = &infos.back();
    writes.push_back(w);
  }
  r.ctx->cmdPushDescriptorSet(cmd, bindPoint, layout, gpu::kSetPass, uint32_t(writes.size()), writes.data());
}

VkCompareOp closerOrEqual(const Renderer& r) {
  return r.options.reversedZ ? VK_COMPARE_OP_GREATER_OR_EQUAL : VK_COMPARE_OP_LESS_OR_EQUAL;
}
VkCompareOp fartherOrEqual(const Renderer& r) {
  return r.options.reversedZ ? VK_COMPARE_OP_LESS_OR_EQUAL : VK_COMPARE_OP_GREATER_OR_EQUAL;
}
float farDepth(const Renderer& r) { return r.options.reversedZ ? 0.0f : 1.0f; }

// ---- per-frame CPU work -----------------------------------------------------------------------

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

  classifyLights(s, r.camera, o.time, stencilLayersOn(o, r.ctx->isCpu), r.lights);
  GB_ASSERT(r.lights.eye.size() <= r.lightBuffer.size / sizeof(gpu::PointLight));
  // (memcpy from an empty vector's null data() is undefined even for 0 bytes: UBSan reports it)
  if (!r.lights.eye.empty())
    std::memcpy(r.lightBuffer.mapped, r.lights.eye.data(), r.lights.eye.size() * sizeof(gpu::PointLight));
  if (!r.lights.visible.empty())
    std::memcpy(r.visibleBuffer.mapped, r.lights.visible.data(), r.lights.visible.size() * sizeof(uint32_t));

  gpu::FrameData f{};
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
  f.skyHorizon = glm::vec4(s.sky.horizon, 0.0f);
  f.skyGround = glm::vec4(s.sky.ground, 0.0f);
  f.params = glm::vec4(o.exposure, 0.05f, 1.0f / float(o.shadowMapSize), float(o.time));
  f.counts = glm::uvec4(uint32_t(r.lights.visible.size()), uint32_t(r.lights.visible.size()) - r.lights.stencilCount,
                        0u, 0u);
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

const FrameStats& renderFrame(Renderer& r, const RenderOptions& options, const FrameRequest& userRequest) {
  auto start = std::chrono::steady_clock::now();
  GpuContext& ctx = *r.ctx;
  // Culling statistics count from coverage_masked and the eye depth (forward has no eye-depth
  // target: its surface points come from the hardware depth).
  FrameRequest request = userRequest;
  const Target depthSource = options.method == Method::Forward ? Target::DepthStencil : Target::Depth;
  if (request.cullingStats && options.coverage)
    for (Target t : {Target::CoverageMasked, depthSource})
      if (std::find(request.readback.begin(), request.readback.end(), t) == request.readback.end())
        request.readback.push_back(t);
  ensureTargets(r, options);
  // Transient images have no memory to copy from, and forward frames never write the G-buffer.
  for (Target t : request.readback) {
    GB_ASSERT(!r.targets[size_t(t)].image.desc.transient);
    GB_ASSERT(options.method != Method::Forward || (t != Target::AlbedoSpecular && t != Target::NormalShadow &&
                                                    t != Target::Depth && t != Target::Position));
  }
  r.options = options;
  prepareFrame(r);

  FrameGraph graph;
  r.skyQueryActive = false;
  buildFrame(graph, r, request);
  if (r.skyQueryActive) {
    if (!r.occlusionPool) {
      VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      qci.queryType = VK_QUERY_TYPE_OCCLUSION;
      qci.queryCount = 1;
      VK_CHECK(vkCreateQueryPool(ctx.device, &qci, nullptr, &r.occlusionPool));
    }
    vkResetQueryPool(ctx.device, r.occlusionPool, 0, 1);
  }

  uint32_t queries = std::max(graph.timestampCount(), 2u);
  uint32_t& capacity = r.timestampCapacity;
  if (!r.timestampPool || capacity < queries) {
    if (r.timestampPool) vkDestroyQueryPool(ctx.device, r.timestampPool, nullptr);
    VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
    qci.queryType = VK_QUERY_TYPE_TIMESTAMP;
    qci.queryCount = capacity = std::max(queries, 64u);
    VK_CHECK(vkCreateQueryPool(ctx.device, &qci, nullptr, &r.timestampPool));
  }
  vkResetQueryPool(ctx.device, r.timestampPool, 0, capacity);
  r.statisticsActive = request.cullingStats && ctx.features.pipelineStatistics;
  if (r.statisticsActive) {
    if (!r.statisticsPool) {
      VkQueryPoolCreateInfo qci{VK_STRUCTURE_TYPE_QUERY_POOL_CREATE_INFO};
      qci.queryType = VK_QUERY_TYPE_PIPELINE_STATISTICS;
      qci.queryCount = 1;
      qci.pipelineStatistics = VK_QUERY_PIPELINE_STATISTIC_FRAGMENT_SHADER_INVOCATIONS_BIT;
      VK_CHECK(vkCreateQueryPool(ctx.device, &qci, nullptr, &r.statisticsPool));
    }
    vkResetQueryPool(ctx.device, r.statisticsPool, 0, 1);
  }

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
  VK_CHECK(vkQueueSubmit(ctx.queue, 1, &si, r.fence));
  VK_CHECK(vkWaitForFences(ctx.device, 1, &r.fence, VK_TRUE, UINT64_MAX));
  auto end = std::chrono::steady_clock::now();

  FrameStats& st = r.stats;
  st = FrameStats{};
  st.frameMs = std::chrono::duration<double, std::milli>(end - start).count();
  st.passes = graph.stats();
  st.lights = uint32_t(r.scene->lights.size());
  st.lightsVisible = uint32_t(r.lights.visible.size());
  st.lightsInside = uint32_t(r.lights.visible.size()) - r.lights.stencilCount;
  st.stencilLayers = r.lights.layerStarts.empty() ? 0u : uint32_t(r.lights.layerStarts.size() - 1);
  st.lightsCulled = r.lights.culledFrustum + r.lights.culledEmpty + r.lights.culledSubpixel;
  st.lightsCulledFrustum = r.lights.culledFrustum;
  st.lightsCulledEmpty = r.lights.culledEmpty;
  st.lightsCulledSubpixel = r.lights.culledSubpixel;
  if (r.skyQueryActive) {
    uint64_t v = 0;  // non-zero exactly when some sample passed (a non-precise query may overcount)
    VK_CHECK(vkGetQueryPoolResults(ctx.device, r.occlusionPool, 0, 1, sizeof(v), &v, sizeof(v),
                                   VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
    r.skyPixels = v;
    r.skyKey = skyVisibilityKey(r);
    st.skyPixels = int64_t(v);
  }
  if (ctx.features.timestamps) {
    double first = 1e300, last = -1e300;
    for (size_t i = 0; i < st.passes.size(); ++i) {
      if (st.passes[i].skipped) continue;
      uint64_t ts[2];
      VK_CHECK(vkGetQueryPoolResults(ctx.device, r.timestampPool, uint32_t(2 * i), 2, sizeof(ts), ts, sizeof(uint64_t),
                                     VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
      double period = ctx.properties.limits.timestampPeriod * 1e-6;
      st.passes[i].ms = double(ts[1] - ts[0]) * period;
      first = std::min(first, double(ts[0]) * period);
      last = std::max(last, double(ts[1]) * period);
    }
    if (last > first) st.gpuMs = last - first;
  }
  for (Target t : request.readback) r.readback[size_t(t)] = unpackReadback(r, t);

  if (request.cullingStats && options.coverage) {
    CullingStats& c = st.culling;
    c.valid = true;
    const CpuImage& masked = r.readback[size_t(Target::CoverageMasked)];
    for (size_t i = 0; i < size_t(masked.width) * masked.height; ++i) c.invocations += masked.raw(uint32_t(i % masked.width), uint32_t(i / masked.width), 0);
    c.idealPairs = idealPairs(r.camera, depthSource == Target::Depth ? r.readback[size_t(Target::Depth)]
                                                                  : eyeDepthFromHardware(r.camera, r.readback[size_t(depthSource)]),
                              r.lights.eye);
    c.workOverIdeal = c.idealPairs ? double(c.invocations) / double(c.idealPairs) : 0.0;
    bool pointLightsRan = false;
    for (const PassStat& p : st.passes) pointLightsRan |= p.name == "point_lights" && !p.skipped;
    if (r.statisticsActive && pointLightsRan) {
      uint64_t v = 0;
      VK_CHECK(vkGetQueryPoolResults(ctx.device, r.statisticsPool, 0, 1, sizeof(v), &v, sizeof(v),
                                     VK_QUERY_RESULT_64_BIT | VK_QUERY_RESULT_WAIT_BIT));
      c.pipelineInvocations = v;
    }
  }
  return st;
}

void destroyRenderer(Renderer& r) {
  if (!r.ctx) return;
  GpuContext& ctx = *r.ctx;
  vkDeviceWaitIdle(ctx.device);
  destroyTargets(r);
  destroyGraphCache(ctx, r.graphCache);
  for (auto& [k, p] : r.pipelines) vkDestroyPipeline(ctx.device, p, nullptr);
  if (r.timestampPool) vkDestroyQueryPool(ctx.device, r.timestampPool, nullptr);
  if (r.statisticsPool) vkDestroyQueryPool(ctx.device, r.statisticsPool, nullptr);
  if (r.occlusionPool) vkDestroyQueryPool(ctx.device, r.occlusionPool, nullptr);
  for (Buffer* b : {&r.vertexBuffer, &r.indexBuffer, &r.icosahedronBuffer, &r.frameBuffer, &r.drawBuffer,
                    &r.materialBuffer, &r.lightBuffer, &r.visibleBuffer})
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
