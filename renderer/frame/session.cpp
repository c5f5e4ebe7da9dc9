// HeadlessSession and snapshotFromRenderer (see session.h).
#include "renderer/frame/session.h"

#include <algorithm>

#include "renderer/core/layout_json.h"
#include "renderer/frame/renderer.h"
#include "renderer/gpu/frame_memory.h"
#include "renderer/gpu/gpu_lights.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/gpu/visibility_scene.h"
#include "renderer/readback/srgb_probe.h"
#include "renderer/vk/check.h"

namespace gb {

HeadlessSession::HeadlessSession(const SessionOptions& o) {
  ContextOptions co;
  co.validation = o.validate;
  co.device = o.device;
  co.quiet = o.quiet;
  ctx_ = std::make_unique<GpuContext>(createContext(co));
  renderer_ = std::make_unique<Renderer>();
}

HeadlessSession::HeadlessSession(const Scene& scene, const SessionOptions& o) : HeadlessSession(o) { useScene(scene); }

HeadlessSession::~HeadlessSession() {
  releaseScene();
  destroyContext(*ctx_);
}

void HeadlessSession::useScene(const Scene& scene) {
  releaseScene();
  initRenderer(*renderer_, *ctx_, scene);
  sceneInUse_ = true;
}

void HeadlessSession::releaseScene() {
  if (!sceneInUse_) return;
  destroyRenderer(*renderer_);
  *renderer_ = Renderer{};
  sceneInUse_ = false;
}

const Scene& HeadlessSession::scene() const {
  GB_ASSERT(sceneInUse_);
  return *renderer_->scene;
}

std::string HeadlessSession::tooLarge(const RenderOptions& o, uint64_t readback) const {
  return frameTooLarge(*ctx_, scene(), frameOptions(o), readback);
}
std::string HeadlessSession::refused(const RenderOptions& o) const {
  GB_ASSERT(sceneInUse_);
  return visibilityRefusal(*renderer_, o);
}
uint64_t HeadlessSession::targetBytes(const RenderOptions& o) const {
  return frameMemory(*ctx_, scene(), frameOptions(o)).targets;
}
uint64_t HeadlessSession::readbackBytes(const RenderOptions& o) const {
  return frameMemory(*ctx_, scene(), frameOptions(o)).readback;
}
RenderOptions HeadlessSession::frameOptions(const RenderOptions& o) const {
  GB_ASSERT(sceneInUse_);
  return gb::frameOptions(*renderer_, o);
}

const FrameStats& HeadlessSession::render(const RenderOptions& o, const FrameRequest& request) {
  GB_ASSERT(sceneInUse_);
  return renderFrame(*renderer_, o, request);
}

FrameBurst HeadlessSession::renderBurst(const RenderOptions& o, int frames) {
  GB_ASSERT(sceneInUse_);
  return gb::renderBurst(*renderer_, o, frames);
}

const FrameStats& HeadlessSession::renderCounting(const RenderOptions& o, const FrameRequest& request) {
  GB_ASSERT(sceneInUse_);
  return renderCountingFrame(*renderer_, o, request);
}

FrameSnapshot HeadlessSession::renderSnapshot(const RenderOptions& o, const std::vector<Target>& targets) {
  GB_ASSERT(sceneInUse_);
  return gb::renderSnapshot(*renderer_, o, targets);
}

FrameSnapshot renderSnapshot(Renderer& r, const RenderOptions& o, const std::vector<Target>& targets) {
  FrameRequest request;
  request.readback = targets;
  renderFrame(r, o, request);
  probeSrgbDecode(r);  // measured once per renderer: what albedo reads decode to
  return snapshotFromRenderer(r, targets);
}

FrameSnapshot HeadlessSession::snapshot(const std::vector<Target>& fresh) const {
  return snapshotFromRenderer(*renderer_, fresh);
}

std::vector<Target> HeadlessSession::readableTargets(const RenderOptions& o) const {
  GB_ASSERT(sceneInUse_);
  return gb::readableTargets(*renderer_, frameOptions(o));
}
const std::string& HeadlessSession::deviceName() const { return ctx_->deviceName; }
const std::string& HeadlessSession::driverName() const { return ctx_->driverName; }
bool HeadlessSession::cpuDevice() const { return ctx_->isCpu; }
bool HeadlessSession::primitiveIdAvailable() const { return ctx_->features.primitiveId; }
uint32_t HeadlessSession::maxImageDimension() const { return ctx_->properties.limits.maxImageDimension2D; }
int HeadlessSession::reportValidation() const { return gb::reportValidation(*ctx_); }

FrameSnapshot snapshotFromRenderer(const Renderer& r, const std::vector<Target>& fresh) {
  GB_ASSERT(r.scene);
  FrameSnapshot s;
  s.options = r.options;
  s.method = r.method;
  s.clusterGrid = r.method == Method::Clustered && r.clusterGrid;
  s.setLayout(nativeLayout(r.options));
  s.camera = r.unjitteredCamera;  // the jitter is the frame's options' (frameJitter, camera_motion.h)
  s.lightClipFromWorld = r.lightClipFromWorld;
  s.sun = r.scene->sun;
  s.sky = r.scene->sky;
  const FrameLights lights = frameLights(r);  // read from the GPU when it set them up
  s.eyeLights = lights.eye;
  s.visibleLights = lights.visible;
  s.stencilCount = lights.stencilCount;
  s.layerStarts = lights.layerStarts;
  s.lightDescs = r.scene->lights;
  s.frameData = r.frameData;
  s.srgbDecode = r.srgbDecode;
  for (const TargetInfo& info : targetTable()) {
    const Target t = info.target;
    Absent why = targetAbsence(t, r.options, r.scene->sun.enabled);
    if (why == Absent::No && (std::find(fresh.begin(), fresh.end(), t) == fresh.end() || r.readback[size_t(t)].empty()))
      why = Absent::NotReadBack;
    s.setAbsence(t, why);
    if (why != Absent::No) continue;
    TargetImage& ti = s.target(t);
    ti.image = r.readback[size_t(t)];
    ti.targetWidth = ti.image.width;
    ti.targetHeight = ti.image.height;
  }
  return s;
}

}  // namespace gb
