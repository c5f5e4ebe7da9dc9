// The views of a stored frame (a streamed one: gblens attach) decoded on the GPU from its texels
// (shaders/view_decode.comp): the decoded view images viewImage makes on the CPU, and their
// automatic-range statistics, for the views on screen. The probe, hover, region statistics and
// captures still decode on the CPU, in double (views/analysis); these images are what is drawn.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "renderer/core/snapshot.h"
#include "renderer/vk/resources.h"
#include "views/analysis/visualize.h"
#include "views/ui/view_map.h"

namespace gb {

struct ViewDecoder {
  VkDescriptorSetLayout setLayout = VK_NULL_HANDLE;  // pushed: texels, surface texels, image, params, results
  VkPipelineLayout layout = VK_NULL_HANDLE;
  // One pipeline per (integer view, specialisation): a view's kind and storage are constants of its shader.
  std::map<std::vector<uint32_t>, VkPipeline> pipelines;
  Buffer texels;   // the targets the views read, host-visible (kept between frames)
  Buffer params;   // ViewDecodeParams per view
  Buffer results;  // RangeResult slots: four per view
};

void initViewDecoder(ViewDecoder& d, GpuContext& ctx);
void destroyViewDecoder(ViewDecoder& d, GpuContext& ctx);

// Why the GPU does not decode this view of `f` ("" when it does): what stays on the CPU (a sample
// spread, a target larger than the device's storage buffer range).
std::string gpuDecodeRefusal(const GpuContext& ctx, const FrameSnapshot& f, const ViewDef& view);

// Decodes views[k] for each k of `which` (each held by the frame, none refused) into images.images[k]
// (made or kept: viewImage's format and size, left readable by fragment shaders), in one submission.
// Returns, per view (views.size()), for those of `which` whose `ranges[k]` is set, its range
// statistics per component its mappings can select: what imageRange gives for each one-component
// mask (motion: the vectors' lengths, one entry; integers one); empty for the others (the statistics cost more than the decoding on lavapipe:
// asked for only where a view's range is automatic).
std::vector<std::vector<RangeStats>> decodeViewsOnGpu(ViewDecoder& d, GpuContext& ctx, const FrameSnapshot& f,
                                                      const std::vector<ViewDef>& views, const std::vector<int>& which,
                                                      const std::vector<bool>& ranges, ViewImages& images);

// The statistics of the components a mapping's mask selects (what imageRange combines).
std::vector<RangeStats> selectRanges(const std::vector<RangeStats>& perComponent, const ViewDef& view, uint32_t mask);

}  // namespace gb
