// Test fixture for everything that touches the GPU: one Vulkan context per test process with
// validation layers (and synchronization validation) always on; any validation message
// during a test fails it.
#pragma once
#include <gtest/gtest.h>

#include <memory>

#include "renderer/renderer.h"
#include "renderer/scene.h"
#include "renderer/vk/context.h"

namespace gb {

class GpuTest : public ::testing::Test {
 public:
  static GpuContext& ctx();

  // Renders one frame of `scene` (a renderer per scene, kept for the test) and returns its stats.
  const FrameStats& render(const Scene& scene, const RenderOptions& options, const FrameRequest& request = {});
  // The renderer used for `scene` by render().
  Renderer& renderer(const Scene& scene);

 protected:
  void SetUp() override;
  void TearDown() override;

 private:
  int errorsBefore_ = 0, warningsBefore_ = 0;
  std::vector<std::pair<const Scene*, std::unique_ptr<Renderer>>> renderers_;
};

// Small scenes for tests, built in code.
Scene floorScene(double halfSize = 10.0, float specular = 0.0f);  // one quad at y = 0, no lights, no sun
void addBox(Scene& scene, glm::vec3 lo, glm::vec3 hi, int material = 0);
void setCamera(Scene& scene, glm::dvec3 eye, glm::dvec3 target, double yfov = 0.9, double znear = 0.1,
               double zfar = 100.0);

}  // namespace gb
