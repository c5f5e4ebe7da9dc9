// A headless frame source: a Vulkan context, a scene on the GPU and its renderer, created
// together and torn down by the destructor. Commands, the bench and the stress suite render
// through it and get FrameSnapshots (renderer/core/snapshot.h); nothing here shows Vulkan.
#pragma once
#include <memory>
#include <string>
#include <vector>

#include "renderer/core/frame_stats.h"
#include "renderer/core/snapshot.h"

namespace gb {

struct GpuContext;
struct Renderer;
struct Scene;

struct SessionOptions {
  std::string device;     // --device NAME|INDEX ("" : first GPU, else the CPU device)
  bool validate = false;  // --validate (GBLENS_VALIDATE=1 also turns it on)
  bool quiet = false;     // do not print the chosen device
};

class HeadlessSession {
 public:
  // The context alone; useScene() before rendering.
  explicit HeadlessSession(const SessionOptions& options);
  HeadlessSession(const Scene& scene, const SessionOptions& options);
  ~HeadlessSession();
  HeadlessSession(const HeadlessSession&) = delete;
  HeadlessSession& operator=(const HeadlessSession&) = delete;

  // Renders `scene` from now on (the previous scene's GPU data is released). The scene must
  // outlive its use: releaseScene() (or another useScene) before it goes.
  void useScene(const Scene& scene);
  void releaseScene();
  const Scene& scene() const;

  // "" when a frame of these options fits the device; else one line naming --size (renderer/gpu/frame_memory.h).
  std::string tooLarge(const RenderOptions& options, uint64_t readback = 0) const;
  // Bytes of every target of such a frame, and of reading all of them back.
  uint64_t targetBytes(const RenderOptions& options) const;
  // "" unless --gbuffer visibility cannot run with these options, scene and device: then one line
  // saying why (renderer/gpu/visibility_scene.h; the renderer would rasterize the G-buffer instead).
  std::string refused(const RenderOptions& options) const;
  uint64_t readbackBytes(const RenderOptions& options) const;
  // The options as a frame of them runs here: --gbuffer auto resolved for this device and scene
  // (frameOptions, renderer/gpu/render_targets.h), for what a command checks before rendering
  // (which targets exist). The calls here that take options resolve them themselves.
  RenderOptions frameOptions(const RenderOptions& options) const;

  // One frame; the request's targets are read back.
  const FrameStats& render(const RenderOptions& options, const FrameRequest& request = {});
  // A burst of frames in flight (renderBurst: the throughput; nothing read back).
  FrameBurst renderBurst(const RenderOptions& options, int frames);
  // One more frame with the coverage counters on, for its culling counts (renderCountingFrame).
  const FrameStats& renderCounting(const RenderOptions& options, const FrameRequest& request = {});
  // One frame of `targets`, as a snapshot (render + snapshot), with the device's sRGB decode table.
  FrameSnapshot renderSnapshot(const RenderOptions& options, const std::vector<Target>& targets);
  // The last frame: `fresh` are the targets it read back; the others are absent with the reason.
  FrameSnapshot snapshot(const std::vector<Target>& fresh) const;
  // The targets a frame of these options can read back on this device (primitive_id needs
  // gl_PrimitiveID; method forward has no G-buffer).
  std::vector<Target> readableTargets(const RenderOptions& options) const;

  const std::string& deviceName() const;
  const std::string& driverName() const;
  bool cpuDevice() const;
  bool primitiveIdAvailable() const;
  uint32_t maxImageDimension() const;
  // Validation messages seen so far (printed with a summary line when there are any).
  int reportValidation() const;

  // For code that drives the renderer itself (the bench's timing, the viewer's tools).
  GpuContext& context() { return *ctx_; }
  Renderer& renderer() { return *renderer_; }

 private:
  std::unique_ptr<GpuContext> ctx_;
  std::unique_ptr<Renderer> renderer_;
  bool sceneInUse_ = false;
};

// One frame of `targets` on this renderer as a snapshot, with the device's sRGB decode table
// (HeadlessSession::renderSnapshot; the bench's own renderers).
FrameSnapshot renderSnapshot(Renderer& r, const RenderOptions& options, const std::vector<Target>& targets);

// Copies a renderer's last frame into a snapshot (plain fields only). `fresh` names the targets
// read back by the last renderFrame(); Renderer::readback may hold stale images of other targets
// from earlier frames, which are left out. Images are whole (origin 0, 0).
FrameSnapshot snapshotFromRenderer(const Renderer& r, const std::vector<Target>& fresh);

}  // namespace gb
