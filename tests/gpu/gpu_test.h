// Test fixture for everything that touches the GPU: one Vulkan context per test process with
// validation layers and synchronization validation (between submissions too) always on; any
// validation message during a test fails it.
#pragma once
#include <gtest/gtest.h>

#include <functional>
#include <memory>

#include "renderer/frame/renderer.h"
#include "renderer/frame/session.h"
#include "renderer/scene/scene.h"
#include "renderer/vk/context.h"
#include "tests/support/scenes.h"

namespace gb {

// Whether the frame ran pass `name` (listed and not skipped).
bool passRan(const FrameStats& st, const std::string& name);
// Texels (per channel) whose stored bits differ between a and b (same size).
size_t differingTexels(const CpuImage& a, const CpuImage& b);

class GpuTest : public ::testing::Test {
 public:
  static GpuContext& ctx();

  // Renders one frame of `scene` (a renderer per scene, kept for the test) and returns its stats.
  const FrameStats& render(const Scene& scene, const RenderOptions& options, const FrameRequest& request = {});
  // The renderer used for `scene` by render().
  Renderer& renderer(const Scene& scene);
  // One frame of `scene` with `targets` read back, as a snapshot (renderer/frame/session.h).
  FrameSnapshot snapshot(const Scene& scene, const RenderOptions& options, const std::vector<Target>& targets);
  // That renderer as a frame source for analysis (views/analysis/accuracy.h).
  std::function<FrameSnapshot(const RenderOptions&, const std::vector<Target>&)> source(const Scene& scene);

 protected:
  void SetUp() override;
  void TearDown() override;

 private:
  int errorsBefore_ = 0, warningsBefore_ = 0;
  std::vector<std::pair<const Scene*, std::unique_ptr<Renderer>>> renderers_;
};

}  // namespace gb
