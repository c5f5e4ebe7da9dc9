// --gbuffer visibility against the raster G-buffer, target by target, on lavapipe (validation on):
// the visibility pass draws what the G-buffer pass draws (hardware depth and stencil bit for bit),
// gbuffer_resolve rebuilds the rest from the triangle. Where the two may differ, and why:
// - albedo: the raster pass samples with implicit quad derivatives, the resolve with textureGrad
//   at analytic ones: textured pixels may land one 8-bit step apart (filtering rounding, LOD);
//   untextured albedo and specular are the same numbers through the same conversion.
// - eye depth and normals: the rasterizer interpolates at vertices snapped to its sub-pixel grid
//   (2^-subPixelPrecisionBits) in its own precision, the resolve at the exact float vertices: they
//   differ by the value's change per pixel times the snap, then by the storage's rounding.
// - hdr: what those differences do to the shading.
#include <cmath>
#include <list>

#include "renderer/core/camera.h"
#include "renderer/core/codec.h"
#include "renderer/core/visibility.h"
#include "renderer/reference/reference.h"
#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"
#include "tests/gpu/visibility_test.h"
#include "tests/support/test_paths.h"
#include "views/analysis/accuracy.h"

namespace gb {

namespace {

const std::vector<Target> kVisibilityCompared = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth,
                                       Target::DepthStencil,   Target::Hdr,          Target::PrimitiveId};

// A textured, normal-mapped floor under a sun: the resolve's textureGrad and normal-map paths.
Scene visibilityFloor() {
  Scene scene = floorScene(10.0, 0.5f);
  Texture base;
  base.name = "checker";
  base.width = base.height = 16;
  for (int i = 0; i < 256; ++i) {
    const uint8_t v = ((i % 16) / 4 + (i / 64)) % 2 ? 230 : 40;
    base.rgba8.insert(base.rgba8.end(), {v, uint8_t(255 - v), 128, 255});
  }
  Texture normal;
  normal.name = "tilted";
  normal.width = normal.height = 4;
  normal.srgb = false;
  for (int i = 0; i < 16; ++i) normal.rgba8.insert(normal.rgba8.end(), {200, 90, 220, 255});
  scene.textures = {base, normal};
  scene.materials[0].baseColorTexture = 0;
  scene.materials[0].normalTexture = 1;
  scene.materials[0].normalScale = 0.8f;
  scene.sun.enabled = true;
  scene.sun.toSun = glm::normalize(glm::dvec3(0.3, 1.0, 0.2));
  setCamera(scene, {1.0, 3.0, 6.0}, {0.0, 0.0, 0.0});
  return scene;
}

// The largest change of channel-function f from pixel (x, y) to a 4-neighbour on the same triangle.
template <class F>
double sameTriangleChange(const CpuImage& ids, uint32_t x, uint32_t y, F f) {
  double g = 0.0;
  const int dx[4] = {1, -1, 0, 0}, dy[4] = {0, 0, 1, -1};
  for (int k = 0; k < 4; ++k) {
    const int nx = int(x) + dx[k], ny = int(y) + dy[k];
    if (nx < 0 || ny < 0 || nx >= int(ids.width) || ny >= int(ids.height)) continue;
    if (ids.raw(uint32_t(nx), uint32_t(ny), 0) != ids.raw(x, y, 0)) continue;
    g = std::max(g, f(uint32_t(nx), uint32_t(ny)));
  }
  return g;
}

double visibilityAngleDeg(glm::dvec3 a, glm::dvec3 b) {
  return glm::degrees(std::atan2(glm::length(glm::cross(a, b)), glm::dot(a, b)));
}

// What the comparison measured (printed: docs/architecture.md quotes them).
struct VisibilityFigures {
  uint64_t exactOff = 0;  // hardware depth, stencil, primitive_id, and the background: must be 0
  uint64_t surface = 0, albedoOff = 0, albedoOffUntextured = 0, normalOverBound = 0, depthOverBound = 0;
  int albedoMaxSteps = 0, specularMaxSteps = 0;
  double normalMaxDeg = 0.0, depthMaxRelative = 0.0, hdrMaxRelative = 0.0, hdrMeanRelative = 0.0;
  double hdrMaxRelativeSameAlbedo = 0.0;  // where the albedo texels are equal
  uint64_t hdrOver = 0;                   // over what the albedo and normal differences explain
};

// One line of what a comparison measured (the figures docs/architecture.md quotes).
void printFigures(const VisibilityFigures& fig, const char* what, NormalFormat format) {
  std::printf(
      "visibility vs raster, %s (%s normals): %llu surface px; albedo max %d steps, %llu px off (%llu untextured); "
      "specular max %d; normal max %.5f deg, %llu px over the bound; eye depth max %.3g relative, %llu px over the "
      "bound; hdr max %.3g mean %.3g relative, where albedo is equal max %.3g, %llu px over the bound\n",
      what, name(format), (unsigned long long)fig.surface, fig.albedoMaxSteps,
      (unsigned long long)fig.albedoOff, (unsigned long long)fig.albedoOffUntextured, fig.specularMaxSteps,
      fig.normalMaxDeg, (unsigned long long)fig.normalOverBound, fig.depthMaxRelative,
      (unsigned long long)fig.depthOverBound, fig.hdrMaxRelative, fig.hdrMeanRelative, fig.hdrMaxRelativeSameAlbedo,
      (unsigned long long)fig.hdrOver);
}

}  // namespace

class Visibility : public GpuTest {
 protected:
  double snap() const { return std::ldexp(1.0, -int(ctx().properties.limits.subPixelPrecisionBits)); }

  // Raster and visibility frames of `scene` under `o`, compared target by target.
  VisibilityFigures compare(const Scene& scene, RenderOptions o, const char* what) {
    o.gbuffer = GBufferKind::Raster;
    EXPECT_TRUE(passRan(render(scene, o, {kVisibilityCompared}), "gbuffer"));
    std::vector<CpuImage> raster;
    for (Target t : kVisibilityCompared) raster.push_back(renderer(scene).readback[size_t(t)]);
    o.gbuffer = GBufferKind::Visibility;
    const FrameStats& st = render(scene, o, {kVisibilityCompared});
    EXPECT_TRUE(passRan(st, "visibility") && passRan(st, "gbuffer_resolve") && !passRan(st, "gbuffer")) << what;
    const Renderer& r = renderer(scene);
    auto vis = [&](Target t) -> const CpuImage& { return r.readback[size_t(t)]; };
    const CpuImage &albedo = raster[0], &normal = raster[1], &depth = raster[2], &ds = raster[3], &hdr = raster[4],
                   &ids = raster[5];
    VisibilityFigures fig;
    double hdrSum = 0.0;
    // The scene's untextured materials, by primitive_id: the instance whose ids hold it.
    const std::vector<uint32_t> first = firstPrimitiveIds(scene);
    auto textured = [&](uint32_t id) {
      size_t i = std::upper_bound(first.begin(), first.end(), id) - first.begin() - 1;
      return scene.materials[scene.meshes[scene.instances[i].mesh].material].baseColorTexture >= 0;
    };
    for (uint32_t y = 0; y < o.height; ++y)
      for (uint32_t x = 0; x < o.width; ++x) {
        for (uint32_t c = 0; c < 2; ++c)  // hardware depth and stencil: the same rasterization
          fig.exactOff += ds.raw(x, y, c) != vis(Target::DepthStencil).raw(x, y, c);
        fig.exactOff += ids.raw(x, y, 0) != vis(Target::PrimitiveId).raw(x, y, 0);
        if (ids.raw(x, y, 0) == 0) {  // no geometry: zero in both
          for (uint32_t c = 0; c < 4; ++c) fig.exactOff += albedo.raw(x, y, c) != vis(Target::AlbedoSpecular).raw(x, y, c);
          for (uint32_t c = 0; c < 4; ++c) fig.exactOff += normal.raw(x, y, c) != vis(Target::NormalShadow).raw(x, y, c);
          fig.exactOff += depth.raw(x, y, 0) != vis(Target::Depth).raw(x, y, 0);
          continue;
        }
        ++fig.surface;
        int steps = 0;
        for (uint32_t c = 0; c < 3; ++c)
          steps = std::max(steps, std::abs(int(albedo.raw(x, y, c)) - int(vis(Target::AlbedoSpecular).raw(x, y, c))));
        fig.albedoMaxSteps = std::max(fig.albedoMaxSteps, steps);
        fig.albedoOff += steps > 0;
        fig.albedoOffUntextured += steps > 0 && !textured(ids.raw(x, y, 0));
        fig.specularMaxSteps = std::max(
            fig.specularMaxSteps, std::abs(int(albedo.raw(x, y, 3)) - int(vis(Target::AlbedoSpecular).raw(x, y, 3))));
        // Normals: one storage step each side plus the normal's change per pixel times the snap.
        const glm::dvec3 a = decodeNormalTexel(normal, x, y, o.normalFormat).unit;
        const glm::dvec3 b = decodeNormalTexel(vis(Target::NormalShadow), x, y, o.normalFormat).unit;
        const double angle = visibilityAngleDeg(a, b);
        const double change = sameTriangleChange(ids, x, y, [&](uint32_t nx, uint32_t ny) {
          return visibilityAngleDeg(a, decodeNormalTexel(normal, nx, ny, o.normalFormat).unit);
        });
        fig.normalMaxDeg = std::max(fig.normalMaxDeg, angle);
        fig.normalOverBound += angle > 2.0 * normalStepDeg(o.normalFormat) + 2.0 * snap() * change;
        // Eye depth: a few ulps plus its change per pixel times the snap.
        const double da = depth.value(x, y, 0), db = vis(Target::Depth).value(x, y, 0);
        const double depthChange =
            sameTriangleChange(ids, x, y, [&](uint32_t nx, uint32_t ny) { return std::abs(depth.value(nx, ny, 0) - da); });
        fig.depthMaxRelative = std::max(fig.depthMaxRelative, std::abs(da - db) / da);
        fig.depthOverBound += std::abs(da - db) > 4.0 * ulp(da) + 2.0 * snap() * depthChange;
        // Lit HDR: per channel, the albedo's relative difference (one sRGB step is 0.4% at 255, 10%
        // near 10), 64 x the normals' angle (the specular lobe's x^32 doubles a relative change of
        // n.h), 1e-3 for the rest (the shadow term, accumulation).
        double rel = 0.0;
        bool over = false;
        for (uint32_t c = 0; c < 3; ++c) {
          const double ha = hdr.value(x, y, c), hb = vis(Target::Hdr).value(x, y, c);
          const double r = std::abs(ha - hb) / std::max(std::max(ha, hb), 1e-3);
          const double aa = albedo.value(x, y, c), ab = vis(Target::AlbedoSpecular).value(x, y, c);
          const double albedoRel = std::abs(aa - ab) / std::max(std::max(aa, ab), 1e-6);
          over |= r > albedoRel + 64.0 * glm::radians(angle) + 1e-3;
          rel = std::max(rel, r);
        }
        fig.hdrMaxRelative = std::max(fig.hdrMaxRelative, rel);
        hdrSum += rel;
        if (steps == 0) fig.hdrMaxRelativeSameAlbedo = std::max(fig.hdrMaxRelativeSameAlbedo, rel);
        fig.hdrOver += over;
      }
    fig.hdrMeanRelative = fig.surface ? hdrSum / double(fig.surface) : 0.0;
    printFigures(fig, what, o.normalFormat);
    return fig;
  }

  // The largest angle (degrees) of storing a unit normal in the format (as test_accuracy.cpp).
  static double normalStepDeg(NormalFormat f) {
    switch (f) {
      case NormalFormat::Rgba16f: return glm::degrees(std::sqrt(3.0) * std::ldexp(1.0, -11));
      case NormalFormat::Rgba8Snorm: return glm::degrees(std::sqrt(3.0) * 0.5 / 127.0);
      case NormalFormat::OctRg16: return glm::degrees(std::sqrt(18.0) * 0.5 / 32767.0);
      case NormalFormat::Rgb10a2: return glm::degrees(std::sqrt(3.0) * 2.0 * 0.5 / 1023.0);
    }
    return 0.0;
  }
  static double ulp(double v) {
    return double(std::nextafter(float(std::abs(v)), INFINITY)) - double(float(std::abs(v)));
  }

  // The bounds every scene and format holds (the file's comment says why).
  static void expectWithinBounds(const VisibilityFigures& f, NormalFormat format, const char* what) {
    EXPECT_EQ(f.exactOff, 0u) << what;
    EXPECT_GT(f.surface, 2000u) << what;
    EXPECT_LE(f.albedoMaxSteps, 1) << what;          // one 8-bit step at most, anywhere
    EXPECT_EQ(f.albedoOffUntextured, 0u) << what;    // untextured: the same numbers, the same conversion
    EXPECT_LE(f.albedoOff, f.surface * 3 / 10) << what;  // textured pixels one step off: filtering rounding
    EXPECT_EQ(f.specularMaxSteps, 0) << what;
    EXPECT_LE(f.normalMaxDeg, 2.0 * normalStepDeg(format) + 0.01) << what;  // a code step either side
    EXPECT_LE(f.normalOverBound, f.surface / 1000) << what;  // tiny triangles: no neighbour to bound the change
    // The raster pass's own plane-equation rounding on large triangles exceeds the snap bound on
    // 0.27% of the temple's pixels (test_visibility's error test: the resolve's depth is the one
    // nearer the reference).
    EXPECT_LE(f.depthMaxRelative, 1e-5) << what;
    EXPECT_LE(f.depthOverBound, f.surface / 200) << what;
    EXPECT_LE(f.hdrMeanRelative, 3e-3) << what;
    EXPECT_LE(f.hdrOver, f.surface / 1000) << what;
  }
};

TEST_F(Visibility, TempleMatchesTheRasterGBufferTargetByTarget) {
  const Scene scene = builtinTemple(16);
  RenderOptions o = visibilityOptions();
  for (NormalFormat f : {NormalFormat::OctRg16, NormalFormat::Rgba16f, NormalFormat::Rgba8Snorm, NormalFormat::Rgb10a2}) {
    o.normalFormat = f;
    expectWithinBounds(compare(scene, o, "builtin:temple"), f, name(f));
  }
}

TEST_F(Visibility, NormalSphereAndATexturedNormalMappedFloorMatchTheRasterGBuffer) {
  const Scene sphere = normalSphereScene(16);
  expectWithinBounds(compare(sphere, visibilityOptions(), "builtin:normal-sphere"), NormalFormat::OctRg16, "normal-sphere");
  const Scene floor = visibilityFloor();
  RenderOptions o = visibilityOptions();
  o.lights = 0;
  expectWithinBounds(compare(floor, o, "textured floor"), o.normalFormat, "floor");
}

// glTF files of the corpus that take the resolve's other paths: an alpha-tested cut-out, mirrored
// instances (the front face flips), a second UV set (the two UV sets of materialUvs).
TEST_F(Visibility, GltfCutoutsMirrorsAndUvSetsMatchTheRasterGBuffer) {
  std::list<Scene> scenes;  // alive for the test: its renderers are kept per scene
  for (const char* file : {"cutout_quad.gltf", "mirrored.gltf", "two_uv_sets.gltf"}) {
    const Scene& scene = scenes.emplace_back(loadScene(std::string(GBLENS_SOURCE_DIR) + "/tests/data/gltf/valid/" + file, 4));
    VisibilityFigures f = compare(scene, visibilityOptions(), file);
    EXPECT_EQ(f.exactOff, 0u) << file;
    EXPECT_LE(f.albedoMaxSteps, 1) << file;
    EXPECT_EQ(f.albedoOffUntextured, 0u) << file;
    EXPECT_LE(f.normalMaxDeg, 2.0 * normalStepDeg(NormalFormat::OctRg16) + 0.01) << file;
    EXPECT_LE(f.depthMaxRelative, 1e-5) << file;
    EXPECT_LE(f.hdrOver, f.surface / 1000) << file;
  }
}

}  // namespace gb
