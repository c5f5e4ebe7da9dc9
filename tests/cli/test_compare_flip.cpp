// FLIP in `gblens compare` (issue 17, section 4): a pair differing in final and hdr is reported
// with LDR-FLIP and HDR-FLIP entries (text and JSON); --fail-flip / --warn-flip decide on the mean
// (exit 2 / 1, a looser value 0, none: reported only); a malformed value is a usage error (exit 4,
// as compare's other thresholds) naming the flag; -o writes the magma maps; --mask pools apart.
#include <OpenImageIO/imageio.h>
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "renderer/core/targets.h"
#include "tests/support/capture_util.h"
#include "views/analysis/compare.h"
#include "views/capture/image_io.h"

namespace gb {
namespace {

constexpr uint32_t kW = 96, kH = 54;

std::string write(const FrameSnapshot& f, const std::string& dir) {
  std::string error;
  EXPECT_TRUE(writeCapture(dir, f, CaptureMeta{}, error)) << error;
  return dir;
}

// Pixel (x, y) of a PNG as RGB bytes.
std::array<int, 3> pngPixel(const std::string& file, uint32_t x, uint32_t y, int& width) {
  auto in = OIIO::ImageInput::open(file);
  if (!in) return {-1, -1, -1};
  const OIIO::ImageSpec& s = in->spec();
  width = s.width;
  std::vector<uint8_t> px(size_t(s.width) * s.height * s.nchannels);
  in->read_image(0, 0, 0, s.nchannels, OIIO::TypeDesc::UINT8, px.data());
  const uint8_t* p = &px[(size_t(y) * s.width + x) * s.nchannels];
  return {p[0], p[1], p[2]};
}

}  // namespace

TEST(CompareFlip, ThresholdsOnTheMeanExitCodesAndMaps) {
  const std::string root = freshDir("compare_flip");
  FrameSnapshot a = syntheticFrame(kW, kH), b = a;
  // A 10x10 patch at (20..29, 20..29): red in final (stored sRGB bytes), brighter in hdr.
  for (uint32_t y = 20; y < 30; ++y)
    for (uint32_t x = 20; x < 30; ++x) {
      for (uint32_t c = 0; c < 3; ++c) setTexel(b.target(Target::Final).image, x, y, c, c == 0 ? 255.0 : 0.0);
      setTexel(b.target(Target::Hdr).image, x, y, 0, 8.0);
    }
  const std::string ca = write(a, root + "/a"), cb = write(b, root + "/b");
  // The ordinary metrics loose, so FLIP alone decides.
  const std::string loose = " --fail 100 --warn 100";

  RunResult same = runGblens("compare " + ca + " " + ca + " --fail-flip 0");
  EXPECT_EQ(same.exitCode, kComparePass) << same.output;
  EXPECT_NE(same.output.find("LDR-FLIP mean 0 "), std::string::npos) << same.output;

  RunResult reported = runGblens("compare " + ca + " " + cb + loose + " --json " + root + "/r.json");
  EXPECT_EQ(reported.exitCode, kComparePass) << reported.output;  // no FLIP threshold: reported only
  EXPECT_NE(reported.output.find("no threshold (reported only)"), std::string::npos) << reported.output;
  const nlohmann::json j = nlohmann::json::parse(readText(root + "/r.json"));
  ASSERT_EQ(j["flip"].size(), 2u) << j.dump(2);
  double means[2];
  for (int i = 0; i < 2; ++i) {
    const nlohmann::json& f = j["flip"][i];
    EXPECT_EQ(f["target"], i == 0 ? "final" : "hdr");
    EXPECT_EQ(f["method"], i == 0 ? "LDR-FLIP" : "HDR-FLIP");
    means[i] = f["mean"].get<double>();
    // 100 of 5184 pixels differ; FLIP spreads a little past them (the filters' reach) and is at
    // most 1, so the mean lies between a few pixels' worth and ~ (10 + 2*10)^2 / 5184.
    EXPECT_GT(means[i], 0.002) << f.dump();
    EXPECT_LT(means[i], 0.2) << f.dump();
    EXPECT_GT(f["max"].get<double>(), 0.5);
    EXPECT_EQ(f["min"].get<double>(), 0.0);
    EXPECT_LE(f["weighted_quartile_1"].get<double>(), f["weighted_median"].get<double>());
    EXPECT_LE(f["weighted_median"].get<double>(), f["weighted_quartile_3"].get<double>());
    EXPECT_EQ(f["histogram"]["values"].size(), 100u);
    EXPECT_EQ(f["pixels"], kW * kH);
  }

  const std::string lowest = std::to_string(std::min(means[0], means[1]) / 2);
  const std::string highest = std::to_string(std::max(means[0], means[1]) * 2);
  EXPECT_EQ(runGblens("compare " + ca + " " + cb + loose + " --fail-flip " + lowest).exitCode, kCompareFail);
  EXPECT_EQ(runGblens("compare " + ca + " " + cb + loose + " --fail-flip " + highest).exitCode, kComparePass);
  EXPECT_EQ(runGblens("compare " + ca + " " + cb + loose + " --warn-flip " + lowest).exitCode, kCompareWarn);
  EXPECT_EQ(runGblens("compare " + ca + " " + cb + loose + " --fail-flip " + highest + " --fail-flip hdr=" + lowest).exitCode,
            kCompareFail);

  for (const char* bad : {"abc", "-1", "depth=0.1"}) {
    RunResult r = runGblens("compare " + ca + " " + cb + " --fail-flip " + bad);
    EXPECT_EQ(r.exitCode, kCompareFileError) << r.output;
    EXPECT_NE(r.output.find("--fail-flip " + std::string(bad)), std::string::npos) << r.output;
  }
  RunResult badPpd = runGblens("compare " + ca + " " + cb + " --flip-ppd 0");
  EXPECT_EQ(badPpd.exitCode, kCompareFileError);
  EXPECT_NE(badPpd.output.find("--flip-ppd"), std::string::npos) << badPpd.output;

  // -o: the magma maps, black-purple (magma's 0) far from the patch, bright on it.
  EXPECT_EQ(runGblens("compare " + ca + " " + cb + loose + " -o " + root + "/diff").exitCode, kComparePass);
  for (const char* name : {"flip_final.png", "flip_hdr.png"}) {
    int width = 0;
    const std::array<int, 3> far = pngPixel(root + "/diff/" + name, 80, 45, width), on = pngPixel(root + "/diff/" + name, 25, 25, width);
    EXPECT_EQ(width, int(std::max(kW, kLegendMinWidth))) << name;  // the map at the top left, its legend below
    EXPECT_EQ(far, (std::array<int, 3>{0, 0, 4})) << name;
    EXPECT_GT(on[0] + on[1] + on[2], 200) << name;
  }

  // A mask over the patch and the filters' reach: the unmasked pixels' mean is 0, so the strict
  // threshold passes; the masked ones are reported apart.
  Rgba8Image mask{kW, kH, std::vector<uint8_t>(size_t(kW) * kH * 4, 0)};
  for (uint32_t y = 8; y < 42; ++y)
    for (uint32_t x = 8; x < 42; ++x) mask.pixels[(size_t(y) * kW + x) * 4] = 255;
  std::string error;
  ASSERT_TRUE(writePng(root + "/mask.png", mask, error)) << error;
  RunResult masked = runGblens("compare " + ca + " " + cb + " --fail 100 --warn 100 --fail-flip 0 --mask " + root + "/mask.png");
  EXPECT_EQ(masked.exitCode, kComparePass) << masked.output;
  EXPECT_NE(masked.output.find("over 1156 px (masked)"), std::string::npos) << masked.output;
}

}  // namespace gb
