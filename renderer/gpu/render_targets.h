// The frame's targets on the GPU (render_targets.cpp): sizes, transience, re-creation, and what
// a frame can read back.
#pragma once
#include <vector>

#include "renderer/core/method_choice.h"
#include "renderer/gpu/renderer_state.h"

namespace gb {

// A target's size under these options (1x1 for a target the frame does not compute), and whether
// it lives only in tile memory (single-pass G-buffer nobody reads).
VkExtent2D targetExtent(const GpuContext& ctx, Target t, const Scene& scene, const RenderOptions& o);
bool targetTransient(Target t, const RenderOptions& o);

// clear_gbuffer clears the G-buffer's colour targets in compute (GBufferClear) rather than the
// render pass: forced, or auto on a GPU device for the compute methods (on the H100 it saved
// 0.5 ms at 1080p and 2.1 ms at 4K there, and cost deferred 0.2-0.8 ms); `reason` says why, for
// the frame's pass list. clearViews: the targets get the storage views it needs (on a GPU device
// whatever the method, so switching methods keeps the targets).
bool clearViews(const GpuContext& ctx, const RenderOptions& o);
bool computeClears(const GpuContext& ctx, const RenderOptions& o, Method ran, std::string& reason);

// How a frame of these options fills its G-buffer on this renderer (never auto) and why, for the
// frame's stats and pass list: chooseGBuffer for the kind of device, then raster where the scene or
// the device refuses visibility (visibilityRefusal; a named --gbuffer visibility the commands
// refuse first, the viewer gets the G-buffer pass with the refusal as its reason).
GBufferChoice frameGBuffer(const Renderer& r, const RenderOptions& o);
// The options with the G-buffer kind that runs (frameGBuffer) in place of the one asked: what
// the frame records (Renderer::options, snapshots, captures) and what its targets are made for,
// so that nothing after it reads --gbuffer auto.
RenderOptions frameOptions(const Renderer& r, const RenderOptions& o);

// The tone map runs in compute (tonemap_compute) rather than as a raster pass (TonemapPass):
// forced, or auto on a GPU device for tiled and clustered; `reason` says why, for the frame's pass
// list. finalStorageView: final gets the UNORM storage view it writes through (on a GPU device
// whatever the method, so switching methods keeps the targets).
bool finalStorageView(const GpuContext& ctx, const RenderOptions& o);
bool computeToneMap(const GpuContext& ctx, const RenderOptions& o, Method ran, std::string& reason);

// The primitive_id target is written this frame (requested, and the device has gl_PrimitiveID).
bool primitiveIdOn(const GpuContext& ctx, const RenderOptions& o);

// The targets a frame of these options can read back on this renderer's device (targetAbsence()
// is Absent::No; primitive_id also needs gl_PrimitiveID). `o` as the frame records them
// (frameOptions; an uploaded frame's own): --gbuffer auto reads as raster here.
std::vector<Target> readableTargets(const Renderer& r, const RenderOptions& o);

// The request of a capture of `targets`: those are read back and nothing else; culling statistics
// only when they need no extra read-back (coverage on, coverage_masked and depth asked).
FrameRequest captureRequest(const std::vector<Target>& targets, const RenderOptions& options);

// Creates the targets for these options, or keeps them when size, formats and usage are the same
// (targetsCurrent).
void ensureTargets(Renderer& r, const RenderOptions& o);
bool targetsCurrent(const Renderer& r, const RenderOptions& o);
void destroyTargets(Renderer& r);

}  // namespace gb
