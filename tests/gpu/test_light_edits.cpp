// Light setup on the GPU uploads the scene's lights only when their generation changed
// (renderer/gpu/gpu_lights.cpp, LightList): an edit through each mutable path of Scene::lights shows
// in the next frame exactly as a fresh renderer of the edited scene draws it, an unchanged scene
// uploads nothing, and the renderer's reads never change the generation.
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

namespace {

// A bright static light over the temple's floor, in view of camera 0.
PointLightDesc brightLight(const glm::vec3& color) {
  PointLightDesc l;
  l.center = {0.5, 1.0, 2.0};
  l.radius = 6.0;
  l.color = color;
  l.intensity = 8.0;
  return l;
}

// hdr and final of `scene` from a renderer made for this frame alone.
std::vector<CpuImage> freshFrame(GpuContext& ctx, const Scene& scene, const RenderOptions& o,
                                 const std::vector<Target>& targets) {
  Renderer fresh;
  initRenderer(fresh, ctx, scene);
  renderFrame(fresh, o, {targets});
  std::vector<CpuImage> out;
  for (Target t : targets) out.push_back(fresh.readback[size_t(t)]);
  destroyRenderer(fresh);
  return out;
}

}  // namespace

TEST_F(GpuTest, EveryLightEditReachesTheNextFrameAndNothingElseUploads) {
  if (!ctx().features.float64) GTEST_SKIP() << "no shaderFloat64: light setup stays on the CPU";
  Scene scene = builtinTemple(64);
  scene.generatedLights = false;
  RenderOptions o;
  o.width = 96;
  o.height = 54;
  o.method = Method::Clustered;
  o.lightSetup = LightSetup::Gpu;
  o.time = 1.5;
  const std::vector<Target> targets = {Target::Hdr, Target::Final};
  Renderer& r = renderer(scene);
  const std::vector<std::pair<std::string, std::function<void(LightList&)>>> edits = {
      {"index", [](LightList& l) { l[5] = brightLight({1.0f, 0.2f, 0.1f}); }},
      {"iteration", [](LightList& l) {
         for (PointLightDesc& d : l) d.intensity *= 3.0;  // every light
       }},
      {"iterator", [](LightList& l) { *(l.begin() + 9) = brightLight({0.1f, 1.0f, 0.3f}); }},
      {"assignment", [](LightList& l) {
         std::vector<PointLightDesc> v = l.vector();
         v[20] = brightLight({0.2f, 0.3f, 1.0f});
         l = v;
       }},
      {"push_back", [](LightList& l) { l.push_back(brightLight({1.0f, 1.0f, 0.2f})); }},
      {"erase", [](LightList& l) { l.erase(l.cend() - 1); }},  // the pushed light goes again
  };
  render(scene, o, {targets});
  for (const auto& [what, edit] : edits) {
    const std::vector<CpuImage> before = {r.readback[size_t(Target::Hdr)], r.readback[size_t(Target::Final)]};
    const uint64_t uploads = r.gpuLights.uploads;
    edit(scene.lights);
    const uint64_t generation = scene.lights.generation();
    render(scene, o, {targets});
    EXPECT_EQ(r.gpuLights.uploads, uploads + 1) << what;
    EXPECT_EQ(scene.lights.generation(), generation) << what << ": the renderer's reads changed the generation";
    EXPECT_GT(differingTexels(r.readback[size_t(Target::Hdr)], before[0]), 0u) << what << ": the edit shows nowhere";
    const std::vector<CpuImage> expected = freshFrame(ctx(), scene, o, targets);
    for (size_t i = 0; i < targets.size(); ++i)
      EXPECT_EQ(differingTexels(r.readback[size_t(targets[i])], expected[i]), 0u)
          << what << ": " << targetName(targets[i]) << " differs from a fresh renderer's frame of the edited scene";
    // Unchanged lights, another time and camera position: no upload.
    o.time += 0.25;
    render(scene, o);
    EXPECT_EQ(r.gpuLights.uploads, uploads + 1) << what << ": an unchanged scene uploaded its lights";
    o.time -= 0.25;
  }
}

}  // namespace gb
