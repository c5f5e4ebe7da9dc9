// Compare masks (issue 17, section 4; issue 26, "Measured" 4): a frame pair that differs only at
// silhouettes fails without a mask and passes with --mask silhouettes (the masked pixels reported
// apart); a difference away from them still fails; a user's mask image masks what it marks; mistakes
// are usage errors (exit 4) naming the part, and --mask silhouettes without primitive ids says so
// before any work. Every figure of a line covers one set of pixels (checked against sums computed
// here); the written mask image's count equals the report's counts; -o writes every group's heat
// map (with its legend) and the mask; --exclude leaves a mismatched target out.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <cmath>

#include "renderer/core/targets.h"
#include "tests/support/capture_util.h"
#include "views/analysis/compare.h"
#include "views/capture/image_io.h"

namespace gb {
namespace {

constexpr uint32_t kW = 32, kH = 16;

// The synthetic frame with a primitive_id target: id 1 on the left half, id 2 on the right, so the
// silhouette pixels are columns 15 and 16.
FrameSnapshot twoObjects() {
  FrameSnapshot f = syntheticFrame(kW, kH);
  TargetImage& id = f.target(Target::PrimitiveId);
  describeReadback(Target::PrimitiveId, f.options, id.image);
  id.image.width = id.targetWidth = kW;
  id.image.height = id.targetHeight = kH;
  id.image.data.assign(size_t(kW) * kH * id.image.texelBytes(), 0);
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) setTexel(id.image, x, y, 0, x < kW / 2 ? 1.0 : 2.0);
  f.setAbsence(Target::PrimitiveId, Absent::No);
  return f;
}

std::string write(const FrameSnapshot& f, const std::string& dir) {
  std::string error;
  EXPECT_TRUE(writeCapture(dir, f, CaptureMeta{}, error)) << error;
  return dir;
}

// An image file's pixels as RGBA bytes (OpenImageIO), with its size.
std::vector<uint8_t> readPng(const std::string& file, int& width, int& height) {
  auto in = OIIO::ImageInput::open(file);
  if (!in) return {};
  width = in->spec().width, height = in->spec().height;
  std::vector<uint8_t> px(size_t(width) * height * in->spec().nchannels);
  in->read_image(0, 0, 0, in->spec().nchannels, OIIO::TypeDesc::UINT8, px.data());
  if (in->spec().nchannels == 4) return px;
  std::vector<uint8_t> rgba(size_t(width) * height * 4, 255);
  for (size_t i = 0; i < size_t(width) * height; ++i)
    for (int c = 0; c < std::min(3, in->spec().nchannels); ++c) rgba[i * 4 + c] = px[i * in->spec().nchannels + c];
  return rgba;
}

}  // namespace

TEST(CompareMasks, OnlyTheMaskedPixelsAreReportedApart) {
  const std::string root = freshDir("compare_masks");
  FrameSnapshot a = twoObjects(), edges = a, elsewhere = a;
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x : {15u, 16u}) setTexel(edges.target(Target::Hdr).image, x, y, 0, 5.0);
  setTexel(elsewhere.target(Target::Hdr).image, 3, 7, 0, 5.0);
  const std::string ca = write(a, root + "/a"), ce = write(edges, root + "/edges"), co = write(elsewhere, root + "/other");

  EXPECT_EQ(runGblens("compare " + ca + " " + ce).exitCode, kCompareFail);
  RunResult masked = runGblens("compare " + ca + " " + ce + " --mask silhouettes");
  EXPECT_EQ(masked.exitCode, kComparePass) << masked.output;
  // 2 columns x 16 rows masked in hdr, all over the fail threshold; the line says whose pixels.
  EXPECT_NE(masked.output.find("over 32 px (masked); 32 over fail (deciding nothing)"), std::string::npos) << masked.output;
  EXPECT_NE(masked.output.find("mask silhouettes: 32 of 512 px"), std::string::npos) << masked.output;
  EXPECT_EQ(runGblens("compare " + ca + " " + co + " --mask silhouettes").exitCode, kCompareFail);

  // A user's mask image: column 3 marked.
  Rgba8Image mask;
  mask.width = kW, mask.height = kH;
  mask.pixels.assign(size_t(kW) * kH * 4, 0);
  for (uint32_t y = 0; y < kH; ++y) mask.pixels[(size_t(y) * kW + 3) * 4] = 255;
  std::string error;
  ASSERT_TRUE(writePng(root + "/mask.png", mask, error)) << error;
  EXPECT_EQ(runGblens("compare " + ca + " " + co + " --mask " + root + "/mask.png").exitCode, kComparePass);
  EXPECT_EQ(runGblens("compare " + ca + " " + ce + " --mask silhouettes," + root + "/mask.png").exitCode, kComparePass);

  // Mistakes: exit 4, naming the part.
  RunResult missing = runGblens("compare " + ca + " " + ce + " --mask " + root + "/nope.png");
  EXPECT_EQ(missing.exitCode, kCompareFileError);
  EXPECT_NE(missing.output.find("nope.png"), std::string::npos) << missing.output;
  mask.width = 8;
  mask.pixels.resize(size_t(8) * kH * 4);
  ASSERT_TRUE(writePng(root + "/small.png", mask, error)) << error;
  RunResult small = runGblens("compare " + ca + " " + ce + " --mask " + root + "/small.png");
  EXPECT_EQ(small.exitCode, kCompareFileError);
  EXPECT_NE(small.output.find("the captures are 32x16"), std::string::npos) << small.output;
  // Without primitive ids: said before any group is compared (no progress line before it).
  const std::string plain = write(syntheticFrame(kW, kH), root + "/plain");
  RunResult noIds = runGblens("compare " + plain + " " + plain + " --mask silhouettes");
  EXPECT_EQ(noIds.exitCode, kCompareFileError);
  EXPECT_NE(noIds.output.find("--mask silhouettes"), std::string::npos) << noIds.output;
  EXPECT_EQ(noIds.output.find("gblens compare:   0%"), std::string::npos) << noIds.output;
  // Progress on stderr, as bench and stress print theirs; none with -q.
  EXPECT_NE(masked.output.find("gblens compare: 100% done"), std::string::npos) << masked.output;
  EXPECT_EQ(runGblens("compare " + ca + " " + ce + " -q").output.find("gblens compare:"), std::string::npos);
}

// Every figure of a line covers the pixels the line names: hdr differs at masked and unmasked pixels
// by known amounts, and the unmasked, masked and all-pixel figures equal sums computed here from the
// written mask image (an independent count, not the report's).
TEST(CompareMasks, FiguresCoverThePixelsTheyName) {
  const std::string root = freshDir("compare_masks_figures");
  FrameSnapshot a = twoObjects(), b = a;
  const CpuImage& hdrA = a.target(Target::Hdr).image;
  CpuImage& hdr = b.target(Target::Hdr).image;
  for (uint32_t y = 0; y < kH; ++y) setTexel(hdr, 15, y, 1, hdrA.value(15, y, 1) + 0.5);  // masked: silhouette column
  for (uint32_t y = 0; y < 4; ++y) setTexel(hdr, 4, y, 2, hdrA.value(4, y, 2) + 0.125);  // unmasked
  const std::string ca = write(a, root + "/a"), cb = write(b, root + "/b");
  RunResult r = runGblens("compare " + ca + " " + cb + " --mask silhouettes --fail 1 --warn 1 -o " + root + "/diff --json " +
                          root + "/r.json");
  ASSERT_EQ(r.exitCode, kComparePass) << r.output;
  int w = 0, h = 0;
  const std::vector<uint8_t> maskPx = readPng(root + "/diff/mask.png", w, h);
  ASSERT_EQ(w, int(kW));
  ASSERT_EQ(h, int(kH));
  // Per set: pixels, max, mean and RMSE over components of |A - B|, from the captures' own values.
  struct Sums { uint64_t pixels = 0; double max = 0, sum = 0, sq = 0, samples = 0; } sets[3];  // all, unmasked, masked
  for (uint32_t y = 0; y < kH; ++y)
    for (uint32_t x = 0; x < kW; ++x) {
      const uint8_t* p = &maskPx[(size_t(y) * kW + x) * 4];
      const bool isMasked = p[0] || p[1] || p[2];
      for (Sums* s : {&sets[0], &sets[isMasked ? 2 : 1]}) {
        ++s->pixels;
        for (uint32_t c = 0; c < 4; ++c) {
          const double d = std::abs(hdr.value(x, y, c) - hdrA.value(x, y, c));
          s->max = std::max(s->max, d), s->sum += d, s->sq += d * d, s->samples += 1;
        }
      }
    }
  EXPECT_EQ(sets[2].pixels, 32u);  // the silhouette columns 15 and 16
  const nlohmann::json j = nlohmann::json::parse(readText(root + "/r.json"));
  EXPECT_EQ(j["mask"]["pixels"], sets[2].pixels);
  for (const nlohmann::json& g : j["groups"]) {
    if (g["key"] != "hdr") continue;
    for (auto [figures, s] : {std::pair{g, &sets[1]}, {g["masked"], &sets[2]}, {g["all"], &sets[0]}}) {
      SCOPED_TRACE(figures["covers"].get<std::string>());
      EXPECT_EQ(figures["pixels"], s->pixels);
      const nlohmann::json& m = figures["metrics"];
      EXPECT_NEAR(m["max_abs"].get<double>(), s->max, 1e-12);
      EXPECT_NEAR(m["mean_abs"].get<double>(), s->sum / s->samples, 1e-12);
      EXPECT_NEAR(m["rmse"].get<double>(), std::sqrt(s->sq / s->samples), 1e-12);
      EXPECT_NEAR(m["psnr_db"].get<double>(), 20.0 * std::log10(1.0 / std::sqrt(s->sq / s->samples)), 1e-9);
    }
    EXPECT_EQ(g["covers"], "unmasked");
    EXPECT_NEAR(g["max_error"].get<double>(), 0.125, 1e-3);  // the unmasked difference, not the masked 0.5
  }
  // The line's counts: unmasked and masked pixels as counted over the mask image.
  EXPECT_NE(r.output.find("over " + std::to_string(sets[1].pixels) + " px (unmasked)"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("over " + std::to_string(sets[2].pixels) + " px (masked)"), std::string::npos) << r.output;

  // -o: a heat map for every compared group, equal or not, with its legend strip below the map.
  for (const nlohmann::json& g : j["groups"]) {
    const std::vector<uint8_t> px = readPng(g["heatmap"].get<std::string>(), w, h);
    ASSERT_EQ(h, int(kH + kLegendHeight)) << g["key"];
    EXPECT_GE(w, int(kLegendMinWidth));
    int bright = 0;  // the legend's text and colour bar
    for (int y = int(kH); y < h; ++y)
      for (int x = 0; x < w; ++x) bright += px[(size_t(y) * w + x) * 4] > 200 || px[(size_t(y) * w + x) * 4 + 1] > 200;
    EXPECT_GT(bright, 50) << g["key"];
    if (g["key"] == "hdr") {  // the largest error red, an equal pixel black
      const uint8_t* hot = &px[(size_t(0) * w + 15) * 4];
      const uint8_t* cold = &px[(size_t(10) * w + 8) * 4];
      EXPECT_GT(hot[0], 200) << "hot";
      EXPECT_EQ(cold[0] + cold[1] + cold[2], 0) << "cold";
    }
  }
}

// A changed shadow-map size makes the run a mismatch; --exclude shadow_map leaves it out (listed as
// skipped); a name of no target is a usage error.
TEST(CompareMasks, ExcludeLeavesATargetOut) {
  const std::string root = freshDir("compare_exclude");
  FrameSnapshot a = syntheticFrame(kW, kH), b = a;
  for (auto [f, size] : {std::pair{&a, 64u}, {&b, 32u}}) {  // --shadow-map-size 64 and 32
    TargetImage& sm = f->target(Target::ShadowMap);
    describeReadback(Target::ShadowMap, f->options, sm.image);
    sm.image.width = sm.targetWidth = sm.image.height = sm.targetHeight = size;
    sm.image.data.assign(size_t(size) * size * sm.image.texelBytes(), 0);
    f->setAbsence(Target::ShadowMap, Absent::No);
    f->options.shadowMapSize = size;  // the manifest says the size its image has
  }
  const std::string ca = write(a, root + "/a"), cb = write(b, root + "/b");
  EXPECT_EQ(runGblens("compare " + ca + " " + cb).exitCode, kCompareMismatch);
  RunResult excluded = runGblens("compare " + ca + " " + cb + " --exclude shadow_map");
  EXPECT_EQ(excluded.exitCode, kComparePass) << excluded.output;
  EXPECT_NE(excluded.output.find("skipped  shadow_map: excluded (--exclude)"), std::string::npos) << excluded.output;
  RunResult unknown = runGblens("compare " + ca + " " + cb + " --exclude shadowmap");
  EXPECT_EQ(unknown.exitCode, kCompareFileError);
  EXPECT_NE(unknown.output.find("--exclude shadowmap: no target"), std::string::npos) << unknown.output;
}

}  // namespace gb
