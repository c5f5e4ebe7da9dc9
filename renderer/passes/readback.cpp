// Read-back: copy the requested targets to host memory (only those). Sample-after: leave
// targets readable by the viewer's own fragment shaders.
#include "renderer/passes/passes.h"
#include "renderer/readback/target_readback.h"

namespace gb {

void addReadbackPass(FrameGraph& g, Renderer& r, const std::vector<Target>& targets) {
  std::vector<Use> uses;
  for (Target t : targets) uses.push_back({t, Access::TransferSrc});
  g.addPass("readback", uses, [&r, targets](PassContext& pc) {
    for (Target t : targets) recordReadback(r, pc.cmd, t);
  });
}

void addSampleAfterPass(FrameGraph& g, const std::vector<Target>& targets) {
  std::vector<Use> uses;
  for (Target t : targets) uses.push_back({t, Access::SampledFragment});
  g.addPass("hand_off", uses, nullptr);
}

}  // namespace gb
