// Compare masks (issue 17, section 4): a frame pair that differs only at silhouettes fails without
// a mask and passes with --mask silhouettes (the masked pixels reported apart); a difference away
// from them still fails; a user's mask image masks what it marks; an unreadable or wrongly sized
// mask, or silhouettes without primitive_id, is a usage error (exit 4) naming it.
#include <gtest/gtest.h>

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
  // 2 columns x 16 rows masked in hdr, all over the fail threshold.
  EXPECT_NE(masked.output.find("masked apart: 32 pixels, 32 over fail"), std::string::npos) << masked.output;
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
  const std::string plain = write(syntheticFrame(kW, kH), root + "/plain");
  RunResult noIds = runGblens("compare " + plain + " " + plain + " --mask silhouettes");
  EXPECT_EQ(noIds.exitCode, kCompareFileError);
  EXPECT_NE(noIds.output.find("--mask silhouettes"), std::string::npos) << noIds.output;
}

}  // namespace gb
