// Clustered lighting from the cluster grid (method clustered, --cluster-assign cpu): one full-screen
// fragment pass in the lighting render pass reads the G-buffer and the CPU's grid (cells, their
// lights) and writes hdr = sun + ambient + the lights of the pixel's cell, or the sky
// (shaders/clustered_grid.frag). On a CPU device a fragment pass is far cheaper than the compute
// passes of the GPU assignment (docs/performance.md).
#include "renderer/passes/passes.h"

namespace gb {

void addClusterGridLightingPass(FrameGraph& g, Renderer& r) {
  std::vector<Use> uses = gbufferReads(r);
  uses.push_back(hdrUse(Access::ColorWrite));  // every pixel is written: geometry, sky or zero
  uses.push_back({Target::CoverageMasked, Access::StorageFragment});  // bound even when off (1x1)
  const FrameSlot& slot = frameSlot(r);  // the grid the CPU wrote for this frame
  g.addPass("clustered_lighting", uses, [&r](PassContext& pc) {
    VkPipeline p = graphicsPipeline(r, pc, "clustered_grid", [&r](GraphicsPipelineDesc& d) {
      d.vertexShader = Shader::fullscreen_vert;
      d.fragmentShader = Shader::clustered_grid_frag;
      d.layout = r.pipelineLayout;
    });
    const GraphTarget& coverage = r.targets[size_t(Target::CoverageMasked)];
    const FrameSlot& slot = frameSlot(r);
    bindGBuffer(r, pc,
                {{gpu::kBindingCoverage, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, coverage.image.view, VK_IMAGE_LAYOUT_GENERAL}},
                VK_PIPELINE_BIND_POINT_GRAPHICS,
                {{gpu::kBindingGridCells, slot.gridCells.buffer}, {gpu::kBindingGridLights, slot.gridLights.buffer}});
    bindPipeline(pc, p);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);
    vkCmdDraw(pc.cmd, 3, 1, 0, 0);
  }, {{slot.gridCells.buffer, BufferAccess::FragmentRead}, {slot.gridLights.buffer, BufferAccess::FragmentRead}});
}

}  // namespace gb
