// Clear G-buffer: zero the G-buffer's colour targets in compute, before the gbuffer render pass
// loads and draws them (GBufferClear). Render-pass clears go through the raster back end, which a
// compute GPU such as the H100 has little of (docs/perf-gpu.md); a compute write runs at memory
// speed. Each target through its unsigned storage view (renderer/vk/resources.h clearView). Under
// --gbuffer visibility the target the render pass would clear is the visibility id (gbuffer_resolve
// writes every pixel of the others).
#include "renderer/core/assert.h"
#include "renderer/passes/passes.h"

namespace gb {

static std::vector<Target> clearedTargets(const Renderer& r) {
  return r.visibility ? std::vector<Target>{Target::Visibility} : gbufferColourTargets(r);
}

void addClearGBufferPass(FrameGraph& g, Renderer& r) {
  std::vector<Use> uses;
  for (Target t : clearedTargets(r)) uses.push_back({t, Access::StorageCompute});
  g.addPass("clear_gbuffer", uses, [&r](PassContext& pc) {
    for (Target t : clearedTargets(r)) {
      const Image& image = r.targets[size_t(t)].image;
      GB_ASSERT(image.clearView);
      const Shader shader = image.desc.clearFormat == VK_FORMAT_R32_UINT      ? Shader::clear_target_r32ui_comp
                            : image.desc.clearFormat == VK_FORMAT_R32G32_UINT ? Shader::clear_target_rg32ui_comp
                                                                              : Shader::clear_target_rgba32ui_comp;
      bindDescriptors(r, pc.cmd, r.pipelineLayout,
                      {{gpu::kBindingClearTarget, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, image.clearView, VK_IMAGE_LAYOUT_GENERAL}},
                      VK_PIPELINE_BIND_POINT_COMPUTE);
      vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, shader));
      vkCmdDispatch(pc.cmd, (image.desc.width + 7) / 8, (image.desc.height + 7) / 8, 1);
    }
  });
}

}  // namespace gb
