// Light setup on the GPU (--light-setup; renderer/gpu_lights.h): light_setup animates, moves to
// eye space and culls every scene light in double (shaders/light_setup.comp), light_compact
// writes the visible list in scene-light order and the counts (shaders/light_compact.comp).
#include "renderer/passes/passes.h"

namespace gb {

static void pushLightSetup(Renderer& r, const PassContext& pc) {
  pushComputeBuffers(r, pc.cmd,
                     {{gpu::kBindingLightDescs, r.gpuLights.descs.buffer},
                      {gpu::kBindingLightScratch, r.gpuLights.scratch.buffer}});
}

void addLightSetupPasses(FrameGraph& g, Renderer& r) {
  const uint32_t groups = uint32_t((r.scene->lights.size() + gpu::kLightSetupGroup - 1) / gpu::kLightSetupGroup);
  g.addPass("light_setup", {}, [&r, groups](PassContext& pc) {
    pushLightSetup(r, pc);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::light_setup_comp));
    vkCmdDispatch(pc.cmd, groups, 1, 1);
  }, {{r.gpuLights.descs.buffer, BufferAccess::ComputeRead}, {r.gpuLights.scratch.buffer, BufferAccess::ComputeReadWrite},
      {r.lightBuffer.buffer, BufferAccess::ComputeReadWrite}});
  g.addPass("light_compact", {}, [&r, groups](PassContext& pc) {
    pushLightSetup(r, pc);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::light_compact_comp));
    vkCmdDispatch(pc.cmd, groups, 1, 1);
  }, {{r.gpuLights.scratch.buffer, BufferAccess::ComputeRead}, {r.visibleBuffer.buffer, BufferAccess::ComputeReadWrite},
      {r.lightCountBuffer.buffer, BufferAccess::ComputeReadWrite}});
}

}  // namespace gb
