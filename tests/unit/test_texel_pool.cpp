// A stream's frames decoded into the buffers of frames already shown (TexelPool, import.h): the
// second frame's texels are the bytes written for it, decoded as computed here (rgba8 bytes,
// rgb10a2 fields, D24 depth / 16777215 and the stencil byte), in the first frame's buffers, at a
// size large enough that the unpacking is split over threads; a larger frame after them still
// decodes whole; a B8G8R8A8 attachment's R and B swap back at every texel.
#include <gtest/gtest.h>

#include <cstring>

#include "renderer/core/texels.h"
#include "views/import/import.h"

namespace gb {
namespace {

using json = nlohmann::json;

// Frame `seed`'s texel bits at texel i: distinct per texel and per frame.
uint32_t bits(uint32_t seed, size_t i) { return uint32_t(i * 2654435761u) ^ (seed * 0x9E3779B9u); }

struct Frame {
  uint32_t w = 0, h = 0;
  std::vector<uint8_t> albedo, normal, depth;  // rgba8_unorm, rgb10a2_unorm, d24s8 (depth plane, then stencil)
};

Frame makeFrame(uint32_t seed, uint32_t w, uint32_t h) {
  Frame f{w, h, {}, {}, {}};
  const size_t n = size_t(w) * h;
  f.albedo.resize(n * 4), f.normal.resize(n * 4), f.depth.resize(n * 5);
  for (size_t i = 0; i < n; ++i) {
    const uint32_t a = bits(seed, i), b = bits(seed + 7, i), d = bits(seed + 13, i);
    std::memcpy(&f.albedo[i * 4], &a, 4);
    std::memcpy(&f.normal[i * 4], &b, 4);
    std::memcpy(&f.depth[i * 4], &d, 4);
    f.depth[n * 4 + i] = uint8_t(d >> 24 ^ d);
  }
  return f;
}

Layout layoutOf(uint32_t w, uint32_t h) {
  auto target = [](const char* name, const char* format, json quantity) {
    return json{{"name", name}, {"format", format}, {"source", {{"live", name}}}, {"quantities", {quantity}}};
  };
  const json layout = {
      {"format", "gblens-layout"},
      {"version", 1},
      {"size", {w, h}},
      {"targets",
       {target("albedo", "rgba8_unorm", {{"quantity", "albedo"}, {"name", "A"}, {"channels", {0, 1, 2}}}),
        target("normal", "rgb10a2_unorm", {{"quantity", "normal"}, {"name", "N"}, {"channels", {0, 1, 2}}, {"encoding", "xyz_unorm"}}),
        target("depth", "d24s8", {{"quantity", "scalar"}, {"name", "D"}, {"channels", {0}}})}}};
  Layout l;
  std::string error;
  EXPECT_TRUE(parseLayout(layout, "pool.json", l, error)) << error;
  return l;
}

FrameSnapshot import(const Frame& f, TexelPool* pool) {
  ImportInput in;
  in.layout = layoutOf(f.w, f.h);
  in.pool = pool;
  in.liveTexels["albedo"] = {f.albedo.data(), f.albedo.size(), f.w, f.h, 1, 0};
  in.liveTexels["normal"] = {f.normal.data(), f.normal.size(), f.w, f.h, 1, 0};
  in.liveTexels["depth"] = {f.depth.data(), f.depth.size(), f.w, f.h, 1, 0};
  FrameSnapshot out;
  std::string error;
  EXPECT_TRUE(importFrame(in, out, error)) << error;
  return out;
}

// Every texel of the snapshot is frame `seed`'s, decoded here.
void expectFrame(const FrameSnapshot& s, uint32_t seed, uint32_t w, uint32_t h) {
  ASSERT_EQ(s.images.size(), 3u);
  const CpuImage &albedo = s.images[0].image, &normal = s.images[1].image, &depth = s.images[2].image;
  ASSERT_EQ(albedo.width, w);
  ASSERT_EQ(depth.height, h);
  const size_t n = size_t(w) * h;
  for (size_t i = 0; i < n; ++i) {
    const uint32_t x = uint32_t(i % w), y = uint32_t(i / w);
    const uint32_t a = bits(seed, i), b = bits(seed + 7, i), d = bits(seed + 13, i);
    for (uint32_t c = 0; c < 4; ++c) ASSERT_EQ(albedo.raw(x, y, c), (a >> (8 * c)) & 0xFF) << i;
    for (uint32_t c = 0; c < 3; ++c) ASSERT_EQ(normal.raw(x, y, c), (b >> (10 * c)) & 0x3FF) << i;
    ASSERT_EQ(normal.raw(x, y, 3), b >> 30) << i;
    ASSERT_EQ(float(depth.value(x, y, 0)), float(double(d & 0xFFFFFF) / 16777215.0)) << i;
    ASSERT_EQ(depth.value(x, y, 1), double(uint8_t(d >> 24 ^ d))) << i;
  }
}

TEST(TexelPool, TheNextFrameIsDecodedInTheBuffersOfTheFrameGivenBack) {
  constexpr uint32_t w = 1280, h = 820;  // over a million texels: the unpacking runs on several threads
  TexelPool pool;
  FrameSnapshot first = import(makeFrame(1, w, h), &pool);
  expectFrame(first, 1, w, h);
  std::vector<const uint8_t*> buffers;
  for (const TargetImage& t : first.images) buffers.push_back(t.image.data.data());
  pool.give(std::move(first), 6);
  EXPECT_EQ(pool.spare.size(), 3u);

  const FrameSnapshot second = import(makeFrame(2, w, h), &pool);
  expectFrame(second, 2, w, h);
  EXPECT_TRUE(pool.spare.empty());
  for (const TargetImage& t : second.images)  // each buffer is one of the first frame's
    EXPECT_NE(std::find(buffers.begin(), buffers.end(), t.image.data.data()), buffers.end()) << t.image.name;
  // The same texels as a frame decoded into fresh buffers.
  const FrameSnapshot fresh = import(makeFrame(2, w, h), nullptr);
  for (size_t t = 0; t < 3; ++t) EXPECT_EQ(second.images[t].image.data, fresh.images[t].image.data) << t;
}

TEST(TexelPool, AFrameLargerThanTheBuffersGivenBackIsDecodedWhole) {
  TexelPool pool;
  pool.give(import(makeFrame(3, 64, 48), &pool), 6);
  const FrameSnapshot larger = import(makeFrame(4, 1200, 900), &pool);
  expectFrame(larger, 4, 1200, 900);
  EXPECT_EQ(pool.spare.size(), 3u);  // none was large enough: all still spare
  pool.give(FrameSnapshot(larger), 4);
  EXPECT_EQ(pool.spare.size(), 4u);  // `keep` bounds what is kept
  const FrameSnapshot smaller = import(makeFrame(5, 64, 48), &pool);
  expectFrame(smaller, 5, 64, 48);
}

// A B8G8R8A8 attachment's texels reordered to RGBA, at a size split over threads: each texel's
// bytes as written, R and B exchanged.
TEST(TexelPool, RedAndBlueSwapBackAtEveryTexel) {
  const Frame f = makeFrame(6, 1280, 820);
  CpuImage img = unpackTexels(TexelFormat::Rgba8Unorm, f.albedo.data(), f.w, f.h);
  swapRedBlue(img);
  for (size_t i = 0; i < size_t(f.w) * f.h; ++i) {
    const uint8_t* in = &f.albedo[i * 4];
    const uint8_t* out = &img.data[i * 4];
    ASSERT_TRUE(out[0] == in[2] && out[1] == in[1] && out[2] == in[0] && out[3] == in[3]) << i;
  }
}

}  // namespace
}  // namespace gb
