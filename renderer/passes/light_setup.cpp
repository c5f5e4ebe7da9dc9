// Light setup on the GPU (--light-setup; renderer/gpu/gpu_lights.h): light_upload copies new light
// descriptions from the frame slot into the buffer light_setup reads; light_setup animates, moves to
// eye space and culls every scene light in double (shaders/light_setup.comp), light_compact
// writes the visible list in scene-light order and the counts (shaders/light_compact.comp).
#include "renderer/passes/passes.h"

namespace gb {

static void pushLightSetup(Renderer& r, const PassContext& pc) {
  pushComputeBuffers(r, pc.cmd,
                     {{gpu::kBindingLightDescs, r.gpuLights.descs.buffer},
                      {gpu::kBindingLightScratch, r.gpuLights.scratch.buffer}});
}

void addLightUploadPass(FrameGraph& g, Renderer& r) {
  const Buffer& staging = frameSlot(r).lightDescStaging;
  g.addPass("light_upload", {}, [&r](PassContext& pc) {
    const VkBufferCopy copy{0, 0, r.gpuLights.uploadBytes};
    vkCmdCopyBuffer(pc.cmd, frameSlot(r).lightDescStaging.buffer, r.gpuLights.descs.buffer, 1, &copy);
  }, {{staging.buffer, BufferAccess::TransferRead}, {r.gpuLights.descs.buffer, BufferAccess::TransferWrite}});
}

void addLightSetupPasses(FrameGraph& g, Renderer& r) {
  const uint32_t groups = uint32_t((r.scene->lights.size() + gpu::kLightSetupGroup - 1) / gpu::kLightSetupGroup);
  g.addPass("light_setup", {}, [&r, groups](PassContext& pc) {
    pushLightSetup(r, pc);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::light_setup_comp));
    vkCmdDispatch(pc.cmd, groups, 1, 1);
  }, {{r.gpuLights.descs.buffer, BufferAccess::ComputeRead}, {r.gpuLights.scratch.buffer, BufferAccess::ComputeReadWrite},
      {frameSlot(r).lightBuffer.buffer, BufferAccess::ComputeReadWrite}});
  g.addPass("light_compact", {}, [&r, groups](PassContext& pc) {
    pushLightSetup(r, pc);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::light_compact_comp));
    vkCmdDispatch(pc.cmd, groups, 1, 1);
  }, {{r.gpuLights.scratch.buffer, BufferAccess::ComputeRead}, {frameSlot(r).lightBuffer.buffer, BufferAccess::ComputeRead},
      {frameSlot(r).visibleBuffer.buffer, BufferAccess::ComputeReadWrite},
      {frameSlot(r).visiblePositionBuffer.buffer, BufferAccess::ComputeReadWrite},
      {frameSlot(r).lightCountBuffer.buffer, BufferAccess::ComputeReadWrite}});
}

}  // namespace gb
