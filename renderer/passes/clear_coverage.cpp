// Clear coverage: zero both coverage counters before the light passes count into them.
#include "renderer/passes/passes.h"

namespace gb {

void addClearCoveragePass(FrameGraph& g, Renderer& r) {
  g.addPass("clear_coverage",
            {{Target::CoverageMasked, Access::TransferDst, true}, {Target::CoverageFull, Access::TransferDst, true}},
            [&r](PassContext& pc) {
              VkClearColorValue zero{};
              VkImageSubresourceRange range{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
              for (Target t : {Target::CoverageMasked, Target::CoverageFull})
                vkCmdClearColorImage(pc.cmd, r.targets[size_t(t)].image.image, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                                     &zero, 1, &range);
            });
}

}  // namespace gb
