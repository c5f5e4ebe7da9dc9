// The viewer's views on the GPU: a target mapped for people straight into a rectangle of the
// window (nearest texel at any zoom, parameters chosen by views/), and the automatic ranges of
// views (min/max over valid texels, NaN/Inf/negative counts) reduced by a compute pass. Nothing
// is computed for a view that is not shown.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "renderer/renderer.h"
#include "views/analysis/view_table.h"

namespace gb {

struct ViewMapper {
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;  // set 1, pushed: source, eye depth, results
  VkPipelineLayout layout = VK_NULL_HANDLE;          // set 0 = the renderer's scene set
  // A view pipeline: its shader variant, the render pass it draws in (none: compute) and the
  // specialization constants' values.
  struct PipelineKey {
    Shader shader;
    VkRenderPass renderPass;
    std::vector<uint32_t> spec;
    auto operator<=>(const PipelineKey&) const = default;
  };
  std::map<PipelineKey, VkPipeline> pipelines;
  Buffer results;  // RangeResult per request, host-visible
};

void initViewMapper(ViewMapper& m, Renderer& r);
void destroyViewMapper(ViewMapper& m, Renderer& r);

struct RangeRequest {
  ViewSource source;
  uint32_t channel = 0;
  uint32_t predicate = gpu::kRangeAll;  // kRange*: which texels count
};
struct RangeStats {
  uint64_t count = 0, nan = 0, inf = 0, negative = 0;  // count: valid finite texels
  double lo = 0.0, hi = 0.0;                            // meaningful when count > 0
};

// One compute pass after the frame; `handOff` targets are left readable by fragment shaders.
std::vector<RangeStats> computeRanges(ViewMapper& m, Renderer& r, const std::vector<RangeRequest>& requests,
                                      const std::vector<Target>& handOff);

// Records one view into the current render pass: `viewport` is the view's rectangle in
// framebuffer pixels (params.transform places the image in it), `scissor` its visible part.
// The source target must be readable by fragment shaders (FrameRequest::sampleAfter).
// With params.mode.x == kViewMapDiff, `b` holds the frame compared with (the same target is read).
void drawView(ViewMapper& m, Renderer& r, VkCommandBuffer cmd, VkRenderPass renderPass, VkFormat attachmentFormat,
              const ViewSource& source, const gpu::ViewParams& params, VkRect2D viewport, VkRect2D scissor,
              Renderer* b = nullptr);

// Inverse of the shaders' orderedFromFloat (view_range.comp).
float floatFromOrdered(uint32_t ordered);

}  // namespace gb
