// The viewer's views decoded on the GPU (views/ui/view_decode.h) against the CPU decoder in double
// (views/analysis/visualize.cpp viewImage, an independent implementation): texel for texel, the
// same texels empty (no surface, nothing drawn) and NaN, the values within float's error; integer
// views bit for bit; the range statistics against imageRange. On gblens's own frame and on a
// G-buffer of other conventions (every normal encoding, packed and snorm formats, hardware depth
// without a background, a scaled linear depth with one, world positions in a Z-up world, NDC motion
// pointing up and to the next frame, 32-bit ids above float's integers, a shadow map's d16).
#include <algorithm>
#include <cmath>
#include <cstring>
#include <random>

#include <glm/gtc/matrix_transform.hpp>

#include "renderer/core/camera.h"
#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "renderer/scene/builtin.h"
#include "renderer/vk/check.h"
#include "tests/gpu/gpu_test.h"
#include "views/analysis/view_table.h"
#include "views/ui/view_decode.h"

namespace gb {

namespace {

// A decoded view image read back (SHADER_READ_ONLY, as decodeViewsOnGpu leaves it).
CpuImage readBack(GpuContext& ctx, const Image& image, const ViewDef& view) {
  CpuImage out = decodedViewImage(view.name, image.desc.width, image.desc.height, view.integer);
  Buffer buffer = createBuffer(ctx, out.data.size(), VK_BUFFER_USAGE_TRANSFER_DST_BIT, MemoryUse::Readback);
  submitOnce(ctx, [&](VkCommandBuffer cmd) {
    const VkImageSubresourceRange all = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    imageBarrier(cmd, image.image, all, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT, VK_PIPELINE_STAGE_2_COPY_BIT,
                 VK_ACCESS_2_TRANSFER_READ_BIT);
    VkBufferImageCopy copy{};
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageExtent = {image.desc.width, image.desc.height, 1};
    vkCmdCopyImageToBuffer(cmd, image.image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.buffer, 1, &copy);
    imageBarrier(cmd, image.image, all, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL,
                 VK_PIPELINE_STAGE_2_COPY_BIT, 0, VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT);
    hostReadBarrier(cmd, VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT);
  });
  std::memcpy(out.data.data(), buffer.mapped, out.data.size());
  destroyBuffer(ctx, buffer);
  return out;
}

uint32_t bitsAt(const CpuImage& img, uint32_t x, uint32_t y, uint32_t c) {
  uint32_t b;
  std::memcpy(&b, img.data.data() + (size_t(y) * img.width + x) * img.texelBytes() + 4 * c, 4);
  return b;
}

struct Differences {
  size_t values = 0, empties = 0, specials = 0;  // beyond the tolerance; empty in one only; NaN/Inf unlike
  double worst = 0.0;
};

// GPU against CPU, texel for texel: integer bits exactly, floats within `tolerance` x max(1, |cpu|).
Differences compareImages(const CpuImage& gpu, const CpuImage& cpu, double tolerance) {
  Differences d;
  for (uint32_t y = 0; y < cpu.height; ++y)
    for (uint32_t x = 0; x < cpu.width; ++x)
      for (uint32_t c = 0; c < cpu.channelCount(); ++c) {
        const uint32_t g = bitsAt(gpu, x, y, c), e = bitsAt(cpu, x, y, c);
        if (cpu.type == PixelType::U32) {
          d.values += g != e;
          continue;
        }
        if ((g == gpu::kEmptyTexel) != (e == gpu::kEmptyTexel)) {
          ++d.empties;
          continue;
        }
        float gf, ef;
        std::memcpy(&gf, &g, 4);
        std::memcpy(&ef, &e, 4);
        if (std::isnan(gf) || std::isnan(ef) || std::isinf(gf) || std::isinf(ef)) {
          d.specials += g != e;
          continue;
        }
        const double error = std::abs(double(gf) - double(ef)) / std::max(1.0, std::abs(double(ef)));
        d.worst = std::max(d.worst, error);
        d.values += error > tolerance;
      }
  return d;
}

// Every view of `f` decoded on the GPU and on the CPU; returns the number of views compared.
int expectEveryViewAsTheCpuDecodesIt(GpuContext& ctx, const FrameSnapshot& f, double tolerance) {
  const std::vector<ViewDef> views = layoutViews(f.layout);
  std::vector<int> which;
  for (size_t k = 0; k < views.size(); ++k) {
    if (!layoutImage(f, views[k].target)) continue;  // not in this frame (no texels to decode either way)
    const std::string refusal = gpuDecodeRefusal(ctx, f, views[k]);
    if (refusal.empty()) which.push_back(int(k));
    else ADD_FAILURE() << views[k].name << ": " << refusal;
  }
  ViewDecoder decoder;
  initViewDecoder(decoder, ctx);
  ViewImages images;
  // Every second view decoded again without its statistics: the same image, no statistics.
  std::vector<bool> half(views.size(), false);
  for (size_t i = 0; i < which.size(); i += 2) half[size_t(which[i])] = true;
  const std::vector<std::vector<RangeStats>> none = decodeViewsOnGpu(decoder, ctx, f, views, which, half, images);
  std::vector<CpuImage> without;
  for (int k : which) without.push_back(readBack(ctx, images.images[size_t(k)], views[size_t(k)]));
  const std::vector<std::vector<RangeStats>> ranges =
      decodeViewsOnGpu(decoder, ctx, f, views, which, std::vector<bool>(views.size(), true), images);
  for (int k : which) {
    const ViewDef& view = views[size_t(k)];
    const CpuImage cpu = viewImage(f, view);
    const CpuImage gpu = readBack(ctx, images.images[size_t(k)], view);
    const size_t at = size_t(std::find(which.begin(), which.end(), k) - which.begin());
    EXPECT_EQ(without[at].data, gpu.data) << view.name << ": decoded without its statistics";
    EXPECT_EQ(none[size_t(k)].empty(), !half[size_t(k)]) << view.name;
    const Differences d = compareImages(gpu, cpu, tolerance);
    EXPECT_EQ(d.values, 0u) << view.name << ": worst relative error " << d.worst;
    EXPECT_EQ(d.empties, 0u) << view.name << ": texels empty on one side only";
    EXPECT_EQ(d.specials, 0u) << view.name << ": NaN / Inf unlike the CPU's";
    // Each component's range is imageRange's over the image the GPU wrote (the same floats), and
    // counts as many valid, NaN and Inf texels as the CPU's image.
    const std::vector<RangeStats>& perComponent = ranges[size_t(k)];
    const size_t components = view.integer || view.visual == Visual::Motion ? 1u
                              : view.visual == Visual::Normal || view.visual == Visual::Position ? 4u
                                                                                                 : view.components;
    EXPECT_EQ(perComponent.size(), components) << view.name;
    if (perComponent.empty()) continue;
    for (uint32_t c = 0; c < perComponent.size(); ++c) {
      const uint32_t mask = view.visual == Visual::Motion ? 0x3u : 1u << c;
      const RangeStats mine = perComponent[c], there = imageRange(gpu, view, mask), cpuRange = imageRange(cpu, view, mask);
      EXPECT_EQ(mine.count, there.count) << view.name << " component " << c;
      EXPECT_EQ(mine.nan, there.nan) << view.name;
      EXPECT_EQ(mine.inf, there.inf) << view.name;
      EXPECT_EQ(mine.negative, there.negative) << view.name;
      const double rangeTolerance = view.visual == Visual::Motion ? 1e-5 * std::max(1.0, there.hi) : 0.0;  // float length vs hypot
      EXPECT_NEAR(mine.lo, there.lo, rangeTolerance) << view.name << " component " << c;
      EXPECT_NEAR(mine.hi, there.hi, rangeTolerance) << view.name << " component " << c;
      EXPECT_EQ(mine.count + mine.nan + mine.inf, cpuRange.count + cpuRange.nan + cpuRange.inf) << view.name;
    }
    EXPECT_EQ(selectRanges(perComponent, view, 0x1u).size(), 1u) << view.name;
  }
  destroyViewImages(images, ctx);
  destroyViewDecoder(decoder, ctx);
  return int(which.size());
}

}  // namespace

TEST_F(GpuTest, GblensOwnFramesViewsDecodeOnTheGpuAsOnTheCpu) {
  Scene scene = builtinTemple(48);
  RenderOptions o;
  o.width = 83;  // not a multiple of the 16 x 16 workgroups
  o.height = 47;
  o.shadowMapSize = 64;
  o.coverage = true;
  o.normalFormat = NormalFormat::OctRg16;
  o.position = PositionSource::Rgba32f;
  o.positionSpace = PositionSpace::Camera;
  o.primitiveId = true;
  o.motion = true;
  o.time = 0.5;
  const std::vector<Target> all = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth,       Target::DepthStencil,
                                   Target::ShadowMap,      Target::Hdr,          Target::Final,       Target::CoverageMasked,
                                   Target::CoverageFull,   Target::PrimitiveId,  Target::Position,    Target::Motion};
  const FrameSnapshot f = snapshot(scene, o, all);
  EXPECT_GE(expectEveryViewAsTheCpuDecodesIt(ctx(), f, 2e-5), 15);
}

namespace {

// A G-buffer written the way gblens's is not: sRGB in a linear unorm target, normals in every
// encoding and space, d24s8 hardware depth without a background, a scaled linear depth with one,
// world positions of a Z-up world, motion in NDC toward the next frame with +y up, 32-bit ids above
// 2^24, a d16 shadow map, snorm and 10-bit packed channels, NaN and Inf in the radiance.
const char* kForeignLayout = R"({"format": "gblens-layout", "version": 1, "name": "foreign", "size": [37, 21],
  "targets": [
    {"name": "gb0", "format": "rgba8_unorm", "quantities": [
      {"quantity": "albedo", "name": "Albedo", "channels": [0, 1, 2], "encoding": "srgb"},
      {"quantity": "occlusion", "name": "AO", "channels": [3], "scale": 0.5, "bias": 0.25}]},
    {"name": "gb1", "format": "rgb10a2_unorm", "quantities": [
      {"quantity": "normal", "name": "NWorld", "channels": [0, 1, 2], "encoding": "xyz_unorm", "space": "world"},
      {"quantity": "scalar", "name": "Flags", "channels": [3]}]},
    {"name": "gb2", "format": "rg16_snorm", "quantities": [
      {"quantity": "normal", "name": "NOct", "channels": [0, 1], "encoding": "octahedral"}]},
    {"name": "gb3", "format": "rgba8_unorm", "quantities": [
      {"quantity": "normal", "name": "NOct12", "channels": [0, 1, 2], "encoding": "octahedral", "bits": 12},
      {"quantity": "metallic", "name": "Metal", "channels": [3]}]},
    {"name": "gb4", "format": "rg8_unorm", "quantities": [
      {"quantity": "normal", "name": "NSphere", "channels": [0, 1], "encoding": "spheremap"}]},
    {"name": "gb5", "format": "rg16f", "quantities": [
      {"quantity": "normal", "name": "NLambert", "channels": [0, 1], "encoding": "lambert"}]},
    {"name": "gb6", "format": "rg8_snorm", "quantities": [
      {"quantity": "normal", "name": "NOctSnorm8", "channels": [0, 1], "encoding": "octahedral"}]},
    {"name": "gb7", "format": "rg16_unorm", "quantities": [
      {"quantity": "normal", "name": "NOctUnorm", "channels": [0, 1], "encoding": "octahedral_unorm"}]},
    {"name": "zbuf", "format": "d24s8", "quantities": [
      {"quantity": "depth", "name": "Z", "channels": [0], "encoding": "hardware"},
      {"quantity": "stencil", "name": "Mask", "channels": [1]}]},
    {"name": "lin", "format": "r32f", "quantities": [
      {"quantity": "depth", "name": "LinearDepth", "channels": [0], "encoding": "eye", "scale": 100, "background": 1}]},
    {"name": "ray", "format": "r16f", "quantities": [
      {"quantity": "depth", "name": "RayDepth", "channels": [0], "encoding": "radial", "background": 0}]},
    {"name": "pos", "format": "rgba32f", "quantities": [
      {"quantity": "position", "name": "P", "channels": [0, 1, 2], "space": "world"},
      {"quantity": "scalar", "name": "W", "channels": [3], "scale": -2, "bias": 1}]},
    {"name": "mv", "format": "rg16f", "quantities": [
      {"quantity": "motion", "name": "Velocity", "channels": [0, 1], "units": "ndc", "direction": "to_next", "y": "up"}]},
    {"name": "ids", "format": "r32_uint", "quantities": [{"quantity": "id", "name": "Object", "channels": [0]}]},
    {"name": "cnt", "format": "r8_uint", "quantities": [{"quantity": "count", "name": "Lights", "channels": [0]}]},
    {"name": "vec", "format": "rgba16_unorm", "quantities": [
      {"quantity": "vector", "name": "Aniso", "channels": [0, 1, 2, 3], "scale": 2, "bias": -1}]},
    {"name": "light", "format": "rgba16f", "quantities": [{"quantity": "radiance", "name": "Lit", "channels": [0, 1, 2, 3]}]},
    {"name": "sm", "format": "d16", "size": [19, 13], "quantities": [
      {"quantity": "depth", "name": "Sun", "channels": [0], "encoding": "hardware", "of": "sun", "background": 1}]}],
  "camera": {"view_from_world": [1,0,0,0, 0,0,-1,0, 0,1,0,0, -1.5,0.25,-6,1],
             "clip_from_view": [1.2,0,0,0, 0,2.1,0,0, 0,0,-1.002,-1, 0,0,-0.2002,0],
             "convention": "gl", "up": "z"}})";

// Stored texels: every code of small integer channels, floats over a few decades of both signs
// (NaN and Inf in the radiance), depths with their background or far value at every fifth texel.
void fillTexels(FrameSnapshot& f, std::mt19937& rng) {
  std::uniform_int_distribution<uint32_t> bits;
  std::uniform_real_distribution<float> unit(0.0f, 1.0f), wide(-40.0f, 40.0f);
  for (uint32_t t = 0; t < f.layout.targets.size(); ++t) {
    const LayoutTarget& lt = f.layout.targets[t];
    TargetImage& ti = f.images[t];
    describeImage(lt, ti.image);
    ti.image.width = ti.targetWidth = lt.width ? lt.width : f.layout.width;
    ti.image.height = ti.targetHeight = lt.height ? lt.height : f.layout.height;
    ti.image.data.resize(size_t(ti.image.width) * ti.image.height * ti.image.texelBytes());
    f.absences[t] = Absent::No;
    const size_t n = size_t(ti.image.width) * ti.image.height * ti.image.channelCount(), size = pixelTypeSize(ti.image.type);
    const bool depth = lt.format.depth, unorm10 = lt.format.packed10;
    for (size_t i = 0; i < n; ++i) {
      uint32_t v = bits(rng);
      const size_t texel = i / ti.image.channelCount(), channel = i % ti.image.channelCount();
      if (unorm10) v %= channel == 3 ? 4u : 1024u;
      if (ti.image.type == PixelType::F32 || ti.image.type == PixelType::F16) {
        float x = lt.name == "lin" ? unit(rng) : lt.name == "pos" || lt.name == "light" ? wide(rng) : unit(rng) * 2.0f - 1.0f;
        if (depth) x = channel == 1 ? float(bits(rng) % 256u) : texel % 5 == 0 ? 1.0f : unit(rng);  // far; stencil codes
        if (lt.name == "lin" && texel % 5 == 0) x = 1.0f;                                         // the background
        if (lt.name == "ray" && texel % 5 == 0) x = 0.0f;
        if (lt.name == "light" && texel % 17 == 3) x = texel % 2 ? NAN : INFINITY;
        if (ti.image.type == PixelType::F32) std::memcpy(&v, &x, 4);
        else v = floatToHalf(x);
      }
      if (lt.name == "sm" && texel % 5 == 0) v = 65535u;  // the shadow map's clear value
      if (lt.name == "ids" && texel % 7 == 0) v = 16777217u + uint32_t(texel);  // above float's integers
      std::memcpy(ti.image.data.data() + i * size, &v, size);
    }
  }
}

// The foreign G-buffer's frame: standard Z, or reversed Z with a left-handed view (D3D's), whose
// hardware depth's far value is 0, not 1.
FrameSnapshot foreignFrame(const Layout& layout, bool reversed, std::mt19937& rng) {
  FrameSnapshot f;
  f.setLayout(layout);
  CameraDesc desc;
  desc.worldFromEye = glm::inverse(glm::dmat4(glm::lookAt(glm::dvec3(3, 1, 5), glm::dvec3(0, 0.5, 0), glm::dvec3(0, 1, 0))));
  f.camera = makeCamera(desc, layout.width, layout.height, reversed);
  f.options.width = layout.width;
  f.options.height = layout.height;
  fillTexels(f, rng);
  if (reversed) {
    f.layout.camera.leftHanded = true;
    for (size_t i = 0; i < f.images[8].image.data.size(); i += 8) std::memset(f.images[8].image.data.data() + i, 0, 4);
  }
  return f;
}

Layout foreignLayout() {
  Layout layout;
  std::string error;
  EXPECT_TRUE(parseLayout(nlohmann::json::parse(kForeignLayout), "foreign.json", layout, error)) << error;
  return layout;
}

}  // namespace

TEST_F(GpuTest, AForeignGBuffersViewsDecodeOnTheGpuAsOnTheCpu) {
  const Layout layout = foreignLayout();
  std::mt19937 rng(34);
  for (bool reversed : {false, true}) {
    const FrameSnapshot f = foreignFrame(layout, reversed, rng);
    SCOPED_TRACE(reversed ? "reversed Z" : "standard Z");
    EXPECT_EQ(expectEveryViewAsTheCpuDecodesIt(ctx(), f, 2e-5), int(layoutViews(f.layout).size()));
  }
}

// More views than the decoder's 64 parameter slots (the foreign layout's 18 views four times over)
// are decoded in turns, each as the CPU decodes it.
TEST_F(GpuTest, MoreViewsThanParameterSlotsDecodeInTurns) {
  std::mt19937 rng(7);
  const FrameSnapshot f = foreignFrame(foreignLayout(), false, rng);
  std::vector<ViewDef> views;
  for (int copy = 0; copy < 4; ++copy)
    for (const ViewDef& v : layoutViews(f.layout)) views.push_back(v);
  std::vector<int> which(views.size());
  for (size_t k = 0; k < which.size(); ++k) which[k] = int(k);
  ASSERT_GT(which.size(), 64u);
  ViewDecoder decoder;
  initViewDecoder(decoder, ctx());
  ViewImages images;
  const std::vector<std::vector<RangeStats>> ranges =
      decodeViewsOnGpu(decoder, ctx(), f, views, which, std::vector<bool>(views.size(), true), images);
  for (int k : which) {
    const Differences d = compareImages(readBack(ctx(), images.images[size_t(k)], views[size_t(k)]), viewImage(f, views[size_t(k)]), 2e-5);
    EXPECT_EQ(d.values + d.empties + d.specials, 0u) << views[size_t(k)].name << " (view " << k << ")";
    EXPECT_FALSE(ranges[size_t(k)].empty()) << k;
  }
  destroyViewImages(images, ctx());
  destroyViewDecoder(decoder, ctx());
}

}  // namespace gb
