// Tone map: hdr -> final (sRGB). In the single-pass path hdr is read as a subpass input. Or in
// compute (tonemap_compute, TonemapPass): through final's UNORM storage view (Image::clearView),
// encoding sRGB in the shader (shaders/tonemap.comp).
#include "renderer/core/assert.h"
#include "renderer/passes/passes.h"

namespace gb {

void addToneMapPass(FrameGraph& g, Renderer& r) {
  Use hdr = hdrUse(singlePass(r) ? Access::InputAttachment : Access::SampledFragment);
  Use final{Target::Final, Access::ColorWrite, true};  // fully overwritten: never load the old one
  g.addPass("tonemap", {hdr, final}, [&r](PassContext& pc) {
    VkPipeline p = graphicsPipeline(r, pc, "tonemap", [&r](GraphicsPipelineDesc& d) {
      d.vertexShader = Shader::fullscreen_vert;
      d.fragmentShader = lightingShader(r, Shader::tonemap_frag, Shader::tonemap_input_frag);
      d.layout = lightingLayout(r);
    });
    const bool input = singlePass(r);
    bindDescriptors(r, pc.cmd, lightingLayout(r),
                    {{gpu::kBindingHdr, input ? VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT : VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER,
                      r.targets[size_t(Target::Hdr)].image.view, pc.layouts[size_t(Target::Hdr)],
                      input ? VK_NULL_HANDLE : r.samplerPoint}});
    bindPipeline(pc, p);
    vkCmdSetCullMode(pc.cmd, VK_CULL_MODE_NONE);
    vkCmdSetFrontFace(pc.cmd, VK_FRONT_FACE_COUNTER_CLOCKWISE);
    vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, 0);
    vkCmdDraw(pc.cmd, 3, 1, 0, 0);
  });
}

void addToneMapComputePass(FrameGraph& g, Renderer& r) {
  const std::vector<Use> uses = {hdrUse(Access::SampledCompute), {Target::Final, Access::StorageCompute, true}};
  g.addPass("tonemap_compute", uses, [&r](PassContext& pc) {
    const Image& final = r.targets[size_t(Target::Final)].image;
    GB_ASSERT(final.clearView && final.desc.clearFormat == VK_FORMAT_R8G8B8A8_UNORM);
    bindDescriptors(r, pc.cmd, r.pipelineLayout,
                    {{gpu::kBindingHdr, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER, r.targets[size_t(Target::Hdr)].image.view,
                      pc.layouts[size_t(Target::Hdr)], r.samplerPoint},
                     {gpu::kBindingClearTarget, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE, final.clearView, VK_IMAGE_LAYOUT_GENERAL}},
                    VK_PIPELINE_BIND_POINT_COMPUTE);
    vkCmdBindPipeline(pc.cmd, VK_PIPELINE_BIND_POINT_COMPUTE, computePipeline(r, Shader::tonemap_comp));
    vkCmdDispatch(pc.cmd, (final.desc.width + 7) / 8, (final.desc.height + 7) / 8, 1);
  });
}

}  // namespace gb
