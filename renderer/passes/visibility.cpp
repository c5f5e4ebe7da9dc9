// Visibility (--gbuffer visibility): the scene drawn as the G-buffer pass draws it (the same vertex
// positions, depth test, stencil 128 and alpha test), writing only depth/stencil and the visibility
// id (renderer/core/visibility.h: draw + 1 and gl_PrimitiveID); gbuffer_resolve does the rest.
#include "renderer/gpu/gpu_scene.h"
#include "renderer/passes/passes.h"

namespace gb {

void addVisibilityPass(FrameGraph& g, Renderer& r) {
  // 0: no geometry. Cleared by clear_gbuffer in compute where r.computeClear (a render-pass clear
  // of the id cost 0.58 ms at 4K on an H200, the raster back end's speed; docs/perf-gpu.md).
  Use id{Target::Visibility, Access::ColorWrite, !r.computeClear};
  id.clearValue.color = {{0.0f, 0.0f, 0.0f, 0.0f}};
  Use depth{Target::DepthStencil, Access::DepthStencilWrite, true};
  depth.clearValue.depthStencil = {farDepth(r), 0};
  g.addPass("visibility", {id, depth}, [&r](PassContext& pc) {
    auto describe = [&](DrawVariantBits v) {
      return [&r, v](GraphicsPipelineDesc& d) {
        d.vertexShader = Shader::visibility_vert;
        d.fragmentShader = Shader::visibility_frag;
        d.vertexInput = VertexInput::SceneVertex;
        sceneGeometryDepthStencil(r, d);
        d.spec.push_back({gpu::kSpecAlphaTest, v.alpha ? 1u : 0u});
        d.spec.push_back({gpu::kSpecBaseColorTexture, v.baseTexture ? 1u : 0u});
        d.spec.push_back({gpu::kSpecVisibilityBits, r.visibilityPacking.triangleBits});
      };
    };
    bindDescriptors(r, pc.cmd, r.pipelineLayout, {});
    // The G-buffer pass's variants (drawVariant), so the draw order and the alpha test are its own;
    // the normal texture changes nothing here.
    for (uint32_t v = 0; v < kDrawVariants; ++v) {
      if (r.drawVariants[v] == r.drawVariants[v + 1]) continue;
      const std::string pipeline = "visibility" + drawVariantName(v) + ".bits" +
                                   std::to_string(r.visibilityPacking.triangleBits);
      bindPipeline(pc, graphicsPipeline(r, pc, pipeline, describe(drawVariantBits(v))));
      vkCmdSetStencilReference(pc.cmd, VK_STENCIL_FACE_FRONT_AND_BACK, gpu::kStencilGeometry);
      drawInstances(r, pc.cmd, r.drawVariants[v], r.drawVariants[v + 1], false);
    }
  });
}

}  // namespace gb
