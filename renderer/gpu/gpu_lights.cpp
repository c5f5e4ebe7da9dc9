// Light setup on the GPU, the CPU's side (see gpu_lights.h).
#include "renderer/gpu/gpu_lights.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "renderer/core/assert.h"
#include "renderer/vk/check.h"

namespace gb {

bool lightsOnGpu(const GpuContext& ctx, const RenderOptions& o, Method method, const std::string* clusterGrid,
                 std::string& reason) {
  if (o.lightSetup == LightSetup::Cpu) return reason = "lights set up on the CPU (--light-setup cpu)", false;
  if (method != Method::Tiled && method != Method::Clustered)
    return reason = std::string("lights set up on the CPU: method ") + name(method) +
                    " draws them in the near-plane and stencil classes the CPU sorts",
           false;
  if (clusterGrid) return reason = "lights set up on the CPU: the cluster grid is filled there (" + *clusterGrid + ")", false;
  if (o.coverage)
    return reason = "lights set up on the CPU: coverage on (light_coverage draws the CPU's near-plane classes)", false;
  if (!ctx.features.float64) return reason = "lights set up on the CPU: the device has no shaderFloat64", false;
  if (o.lightSetup == LightSetup::Auto && ctx.isCpu)
    return reason = "lights set up on the CPU: a CPU device (faster there, docs/performance.md)", false;
  reason = o.lightSetup == LightSetup::Gpu ? "--light-setup gpu" : "auto: a GPU device";
  return true;
}

static glm::uvec2 bits(double v) {
  glm::uvec2 b;
  std::memcpy(&b, &v, sizeof v);
  return b;
}
static glm::uvec4 bits(double a, double b) { return glm::uvec4(bits(a), bits(b)); }

static gpu::LightDesc toGpu(const PointLightDesc& l) {
  gpu::LightDesc d{};
  d.centerXY = bits(l.center.x, l.center.y);
  d.centerZOrbit = bits(l.center.z, l.orbitRadius);
  d.speedPhase = bits(l.orbitSpeed, l.phase);
  d.bobRadius = bits(l.bob, l.radius);
  const glm::dvec3 color = glm::dvec3(l.color) * l.intensity;  // as classifyLights
  const bool empty = !(l.radius > 0.0) || !(l.intensity > 0.0) || glm::dot(color, color) <= 0.0 || !std::isfinite(l.radius);
  d.color = glm::vec4(glm::vec3(color), empty ? 1.0f : 0.0f);
  return d;
}

static bool sameLights(const std::vector<PointLightDesc>& a, const std::vector<PointLightDesc>& b) {
  if (a.size() != b.size()) return false;
  for (size_t i = 0; i < a.size(); ++i) {
    const PointLightDesc &x = a[i], &y = b[i];
    if (x.center != y.center || x.orbitRadius != y.orbitRadius || x.orbitSpeed != y.orbitSpeed || x.phase != y.phase ||
        x.bob != y.bob || x.radius != y.radius || x.color != y.color || x.intensity != y.intensity)
      return false;
  }
  return true;
}

// Whether `descs` holds this scene's lights: the scene and its lights' generation are those of
// the last upload (O(1): every edit of Scene::lights draws a new generation, light_list.h). With
// validation on, the lights are compared too, and an edit the generation missed (made through a
// reference kept across a frame) stops the program.
static bool uploaded(const Renderer& r) {
  const GpuLights& g = r.gpuLights;
  const bool same = g.descs.buffer && g.scene == r.scene && g.generation == r.scene->lights.generation();
  if (same && r.ctx->validation) GB_ASSERT(sameLights(g.checkCopy, r.scene->lights));
  return same;
}

// New light descriptions into the current slot's staging buffer (the slot's previous frame is
// retired: nothing reads it); light_upload copies them into `descs` on the GPU, after everything
// submitted before, so a frame in flight still reads the descriptions it was recorded with.
static void stageLights(Renderer& r) {
  const LightList& lights = r.scene->lights;
  GpuLights& g = r.gpuLights;
  const size_t n = std::max<size_t>(lights.size(), 1);
  const size_t groups = (n + gpu::kLightSetupGroup - 1) / gpu::kLightSetupGroup;
  if (g.descs.size < n * sizeof(gpu::LightDesc)) {
    if (g.descs.buffer) {
      vkDeviceWaitIdle(r.ctx->device);  // frames in flight use them
      destroyBuffer(*r.ctx, g.descs);
      destroyBuffer(*r.ctx, g.scratch);
    }
    g.descs = createBuffer(*r.ctx, n * sizeof(gpu::LightDesc),
                           VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Device,
                           "light_descs");
    g.scratch = createBuffer(*r.ctx, (n + groups * 4) * sizeof(uint32_t), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                             MemoryUse::Device, "light_scratch");
  }
  Buffer& staging = frameSlot(r).lightDescStaging;
  if (staging.size < n * sizeof(gpu::LightDesc)) {
    if (staging.buffer) destroyBuffer(*r.ctx, staging);
    staging = createBuffer(*r.ctx, n * sizeof(gpu::LightDesc), VK_BUFFER_USAGE_TRANSFER_SRC_BIT, MemoryUse::Upload,
                           "light_descs.staging");
  }
  auto* descs = static_cast<gpu::LightDesc*>(staging.mapped);
  for (size_t i = 0; i < lights.size(); ++i) descs[i] = toGpu(lights[i]);
  g.uploadBytes = lights.size() * sizeof(gpu::LightDesc);
  g.scene = r.scene;
  g.generation = lights.generation();
  if (r.ctx->validation) g.checkCopy = lights.vector();
  g.uploads++;
}

void prepareGpuLights(Renderer& r, gpu::FrameData& f) {
  const LightList& lights = r.scene->lights;
  r.gpuLights.uploadBytes = 0;
  if (!uploaded(r)) stageLights(r);
  for (int row = 0; row < 3; ++row) {
    const glm::dmat4& m = r.camera.eyeFromWorld;  // column-major: m[column][row]
    f.eyeFromWorld64[2 * row] = bits(m[0][row], m[1][row]);
    f.eyeFromWorld64[2 * row + 1] = bits(m[2][row], m[3][row]);
  }
  const glm::dmat4& p = r.camera.clipFromEye;
  f.projection64[0] = bits(p[0][0], p[1][1]);
  f.projection64[1] = bits(p[2][0], p[2][1]);
  f.depthRange64 = bits(r.camera.znear, r.camera.zfar);
  f.time64 = glm::uvec4(bits(r.options.time), uint32_t(lights.size()), 0u);
  r.lights = FrameLights{};
  if (lights.empty()) {  // no light_setup pass runs: the counts are zero
    const gpu::LightCounts zero{};
    std::memcpy(frameSlot(r).lightCountBuffer.mapped, &zero, sizeof zero);
  }
}

static gpu::LightCounts gpuCounts(const FrameSlot& s) {
  gpu::LightCounts c;
  std::memcpy(&c, s.lightCountBuffer.mapped, sizeof c);
  return c;
}

FrameLights frameLights(const Renderer& r) {
  if (!r.lightsOnGpu) return r.lights;
  const FrameSlot& s = frameSlot(r);  // the last frame's
  GB_ASSERT(!s.pending);
  FrameLights l;
  const gpu::LightCounts c = gpuCounts(s);
  const size_t n = r.scene->lights.size();
  l.eye.resize(n);
  if (n) std::memcpy(l.eye.data(), s.lightBuffer.mapped, n * sizeof(gpu::PointLight));
  l.visible.resize(c.counts.x);
  if (c.counts.x) std::memcpy(l.visible.data(), s.visibleBuffer.mapped, c.counts.x * sizeof(uint32_t));
  l.stencilCount = c.counts.x;  // no near-plane class: the compute methods need none
  l.culledFrustum = c.counts.y;
  l.culledEmpty = c.counts.z;
  l.culledSubpixel = c.counts.w;
  return l;
}

void readGpuLightCounts(const FrameSlot& s, FrameStats& st) {
  const gpu::LightCounts c = gpuCounts(s);
  st.lightsVisible = c.counts.x;
  st.lightsInside = 0;
  st.stencilLayers = 0;
  st.lightsCulledFrustum = c.counts.y;
  st.lightsCulledEmpty = c.counts.z;
  st.lightsCulledSubpixel = c.counts.w;
  st.lightsCulled = c.counts.y + c.counts.z + c.counts.w;
}

void readGpuLights(Renderer& r) {
  r.lights = frameLights(r);
  r.lightsOnGpu = false;  // r.lights now holds them
}

void destroyGpuLights(Renderer& r) {
  for (Buffer* b : {&r.gpuLights.descs, &r.gpuLights.scratch})
    if (b->buffer) destroyBuffer(*r.ctx, *b);
  r.gpuLights = GpuLights{};
}

}  // namespace gb
