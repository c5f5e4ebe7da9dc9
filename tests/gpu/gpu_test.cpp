// GpuTest: the shared Vulkan context with validation, one renderer per scene of a test.
#include "tests/gpu/gpu_test.h"

#include <cstdlib>

namespace gb {

GpuContext& GpuTest::ctx() {
  static GpuContext* context = [] {
    // Synchronization validation between submissions too, not only within a command buffer:
    // frames in flight share buffers and targets across submissions. The layer (1.3.239) takes
    // this alpha check only from its environment (no VK_EXT_layer_settings yet); ':' separates.
    setenv("VK_LAYER_ENABLES",
           "VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT:"
           "VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT",
           0);
    ContextOptions o;
    o.validation = true;  // every test runs with validation layers, whatever the environment
    o.quiet = true;
    auto* c = new GpuContext(createContext(o));
    std::atexit([] {});  // the context lives for the process; the driver cleans up at exit
    return c;
  }();
  return *context;
}

void GpuTest::SetUp() {
  ctx();
  errorsBefore_ = validationLog().errors;
  warningsBefore_ = validationLog().warnings;
}

void GpuTest::TearDown() {
  for (auto& [scene, r] : renderers_) destroyRenderer(*r);
  renderers_.clear();
  ValidationLog& log = validationLog();
  int errors = log.errors - errorsBefore_, warnings = log.warnings - warningsBefore_;
  if (errors || warnings) {
    std::string all;
    for (auto& m : log.messages) all += m + "\n";
    ADD_FAILURE() << errors << " validation error(s), " << warnings << " warning(s):\n" << all;
  }
}

Renderer& GpuTest::renderer(const Scene& scene) {
  for (auto& [s, r] : renderers_)
    if (s == &scene) return *r;
  renderers_.emplace_back(&scene, std::make_unique<Renderer>());
  initRenderer(*renderers_.back().second, ctx(), scene);
  return *renderers_.back().second;
}

const FrameStats& GpuTest::render(const Scene& scene, const RenderOptions& options, const FrameRequest& request) {
  return renderFrame(renderer(scene), options, request);
}

FrameSnapshot GpuTest::snapshot(const Scene& scene, const RenderOptions& o, const std::vector<Target>& targets) {
  return renderSnapshot(renderer(scene), o, targets);
}

std::function<FrameSnapshot(const RenderOptions&, const std::vector<Target>&)> GpuTest::source(const Scene& scene) {
  Renderer* r = &renderer(scene);
  return [r](const RenderOptions& o, const std::vector<Target>& t) { return renderSnapshot(*r, o, t); };
}

bool passRan(const FrameStats& st, const std::string& name) {
  for (const PassStat& p : st.passes)
    if (p.name == name) return !p.skipped;
  return false;
}

size_t differingTexels(const CpuImage& a, const CpuImage& b) {
  EXPECT_TRUE(a.width == b.width && a.height == b.height);
  size_t n = 0;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x)
      for (uint32_t c = 0; c < a.channelCount(); ++c) n += a.raw(x, y, c) != b.raw(x, y, c);
  return n;
}

}  // namespace gb
