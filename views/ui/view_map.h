// The viewer's views on the GPU: a target mapped for people straight into a rectangle of the
// window (nearest texel at any zoom, parameters chosen by views/), and the automatic ranges of
// views (min/max over valid texels, NaN/Inf/negative counts) reduced by a compute pass. Nothing
// is computed for a view that is not shown.
#pragma once
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "renderer/frame/renderer.h"
#include "views/analysis/visualize.h"
#include "views/ui/view_params.h"

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

// A live view's source: one of gblens's targets (its stencil aspect for a stencil quantity).
struct ViewSource {
  Target target = Target::Final;
  bool stencil = false;
};
// The live target holding a view of gblens's own layout (its layout target's name is the target's),
// with the channels its components are in; nothing when the view's target is not one of gblens's,
// or the view is none of the layout's quantities (a reference map).
std::optional<ViewSource> nativeSource(const Layout& layout, const ViewDef& view, ViewGpuSource* gpu = nullptr);

// What the GPU samples for a view: an image view in a layout readable by fragment shaders.
struct ViewImage {
  VkImageView view = VK_NULL_HANDLE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  bool uint = false;  // integer texels (usampler2D)
  bool valid() const { return view != VK_NULL_HANDLE; }
};
ViewImage targetImage(const Renderer& r, const ViewSource& source);

// Decoded view images (a capture's views, views/analysis/visualize.h viewImage) on the GPU.
struct ViewImages {
  std::vector<Image> images;  // one per view; empty where the frame has nothing to show
  Buffer staging;             // the last upload's (kept: a stream uploads every frame shown)
};
// `leave`: views whose images another writer fills (view_decode.h), left as they are.
void uploadViewImages(ViewImages& out, GpuContext& ctx, const std::vector<CpuImage>& decoded,
                      const std::vector<bool>& leave = {});
// `image` made (or kept, when it is one) a decoded view image of this size: RGBA32F (integer views
// R32_UINT), sampled, written by uploads or by compute (RGBA32F through a storage view in RGBA32_UINT,
// Image::clearView, so that the bits viewImage writes, kEmptyTexel's NaN among them, are stored as they are).
void ensureViewImage(GpuContext& ctx, Image& image, bool integer, uint32_t width, uint32_t height, const std::string& name);
void destroyViewImages(ViewImages& images, GpuContext& ctx);
ViewImage viewImageOf(const ViewImages& images, size_t view);

struct RangeRequest {
  ViewSource source;
  uint32_t channel = 0;
  uint32_t predicate = gpu::kRangeAll;  // kRange*: which texels count
  float background = 0.0f;              // kRangeNotValue
};

// One compute pass after the frame; `handOff` targets are left readable by fragment shaders.
std::vector<RangeStats> computeRanges(ViewMapper& m, Renderer& r, const std::vector<RangeRequest>& requests,
                                      const std::vector<Target>& handOff);

// Records one view into the current render pass: `viewport` is the view's rectangle in
// framebuffer pixels (params.transform places the image in it), `scissor` its visible part.
// `r` gives the pipelines' specialisation (normal encoding) and the scene set (marks); `source` must
// be readable by fragment shaders. With params.mode.x == kViewMapDiff, `b` is the frame compared with.
void drawView(ViewMapper& m, Renderer& r, VkCommandBuffer cmd, VkRenderPass renderPass, VkFormat attachmentFormat,
              const ViewImage& source, const gpu::ViewParams& params, VkRect2D viewport, VkRect2D scissor,
              const ViewImage* b = nullptr);

// Inverse of the shaders' orderedFromFloat (view_range.comp).
float floatFromOrdered(uint32_t ordered);

}  // namespace gb
