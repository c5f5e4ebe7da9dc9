// Light setup on the GPU (--light-setup; passes light_setup and light_compact): what the CPU
// does per frame instead of classifying every light (upload the scene's lights when their
// generation changed, fill the double-precision camera fields), and the lights read back from the GPU's
// buffers when someone asks for them (snapshots, culling statistics).
#pragma once
#include <string>

#include "renderer/gpu/renderer_state.h"

namespace gb {

// Whether this frame sets its lights up on the GPU, and why (or why not). `clusterGrid`: why the
// frame fills the cluster grid on the CPU (clusterGridOn), which needs the lights there; null if not.
bool lightsOnGpu(const GpuContext& ctx, const RenderOptions& o, Method method, const std::string* clusterGrid,
                 std::string& reason);

// The frame's light data when they are set up on the GPU: stages the scene's lights for
// light_upload when the scene or its lights' generation differ from the last upload (O(1)
// otherwise: nothing per light on the CPU) and fills FrameData's double-precision fields.
void prepareGpuLights(Renderer& r, gpu::FrameData& f);

// After the slot's fence: the counts its light_compact wrote (FrameStats).
void readGpuLightCounts(const FrameSlot& s, FrameStats& st);
// After the last frame's fence: its eye-space lights and visible list into r.lights (as the CPU
// path leaves them), for snapshots and culling statistics.
void readGpuLights(Renderer& r);

// The lights of the last frame as the CPU path describes them: r.lights, or read from the GPU's
// buffers when it set them up (snapshotFromRenderer).
FrameLights frameLights(const Renderer& r);

void destroyGpuLights(Renderer& r);

}  // namespace gb
