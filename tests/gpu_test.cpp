// GpuTest: the shared Vulkan context with validation, and test scenes built in code.
#include "tests/gpu_test.h"

#include "renderer/camera.h"
#include "renderer/geometry.h"

namespace gb {

GpuContext& GpuTest::ctx() {
  static GpuContext* context = [] {
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

Scene floorScene(double halfSize, float specular) {
  Scene s;
  s.source = "test:floor";
  MaterialDesc m;
  m.name = "grey";
  m.baseColor = glm::vec4(0.5f, 0.5f, 0.5f, 1.0f);
  m.specular = specular;
  s.materials.push_back(m);
  MeshBuilder b{s};
  b.begin("floor", 0);
  float h = float(halfSize);
  b.quad({-h, 0, h}, {2 * h, 0, 0}, {0, 0, -2 * h});
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
  s.sun.enabled = false;
  s.sky.ambient = glm::vec3(0.0f);
  computeBounds(s);
  setCamera(s, {0, 5, 5}, {0, 0, 0});
  return s;
}

void addBox(Scene& s, glm::vec3 lo, glm::vec3 hi, int material) {
  MeshBuilder b{s};
  b.begin("box", material);
  b.box(lo, hi);
  b.end();
  s.instances.push_back({b.meshIndex, glm::dmat4(1.0), true});
  computeBounds(s);
}

void setCamera(Scene& s, glm::dvec3 eye, glm::dvec3 target, double yfov, double znear, double zfar) {
  s.cameras = {lookAtCamera("test", eye, target, yfov, znear, zfar)};
}

}  // namespace gb
