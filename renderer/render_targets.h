// The frame's targets on the GPU (render_targets.cpp): sizes, transience, re-creation, and what
// a frame can read back.
#pragma once
#include <vector>

#include "renderer/renderer.h"

namespace gb {

// A target's size under these options (1x1 for a target the frame does not compute), and whether
// it lives only in tile memory (single-pass G-buffer nobody reads).
VkExtent2D targetExtent(const GpuContext& ctx, Target t, const Scene& scene, const RenderOptions& o);
bool targetTransient(Target t, const RenderOptions& o);

// The primitive_id target is written this frame (requested, and the device has gl_PrimitiveID).
bool primitiveIdOn(const GpuContext& ctx, const RenderOptions& o);

// The targets a frame of these options can read back on this renderer's device (targetAbsence()
// is Absent::No; primitive_id also needs gl_PrimitiveID).
std::vector<Target> readableTargets(const Renderer& r, const RenderOptions& o);

// The request of a capture of `targets`: those are read back and nothing else; culling statistics
// only when they need no extra read-back (coverage on, coverage_masked and depth asked).
FrameRequest captureRequest(const std::vector<Target>& targets, const RenderOptions& options);

// Creates the targets for these options, or keeps them when size, formats and usage are the same.
void ensureTargets(Renderer& r, const RenderOptions& o);
void destroyTargets(Renderer& r);

}  // namespace gb
