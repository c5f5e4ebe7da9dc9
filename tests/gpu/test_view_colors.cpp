// Every visualisation of the views at known pixels, drawn by the viewer's shader from a decoded view
// image, against colours computed independently: matplotlib's viridis table (false colour), Python's
// colorsys for the stencil hues, Wellons' lowbias32 evaluated in Python for ids, Baker et al.'s colour
// wheel worked by hand for motion, the sRGB curve for exposure, log scales by hand.
#include <cmath>
#include <cstring>

#include "renderer/scene/builtin.h"
#include "tests/gpu/gpu_test.h"
#include "tests/gpu/view_canvas.h"
#include "views/analysis/visualize.h"
#include "views/ui/view_params.h"

namespace gb {

namespace {

// A decoded view image: RGBA32F texels (or R32_UINT), one row.
CpuImage row(const std::vector<std::array<float, 4>>& texels) {
  CpuImage img;
  img.name = "test";
  img.width = uint32_t(texels.size());
  img.height = 1;
  img.channels = {"0", "1", "2", "3"};
  img.data.resize(texels.size() * 16);
  std::memcpy(img.data.data(), texels.data(), img.data.size());
  return img;
}
CpuImage uintRow(const std::vector<uint32_t>& values) {
  CpuImage img;
  img.name = "test";
  img.width = uint32_t(values.size());
  img.height = 1;
  img.type = PixelType::U32;
  img.encoding = Encoding::Uint;
  img.channels = {"v"};
  img.data.resize(values.size() * 4);
  std::memcpy(img.data.data(), values.data(), img.data.size());
  return img;
}

ViewDef viewOfVisual(Visual visual, uint32_t components, bool integer = false) {
  ViewDef d;
  d.name = "test";
  d.visual = visual;
  d.components = components;
  d.channels = components >= 3 ? 0x7 : (1u << components) - 1;
  d.integer = integer;
  return d;
}

}  // namespace

class ViewColors : public GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    initViewMapper(mapper, renderer(scene));
  }
  void TearDown() override {
    destroyViewMapper(mapper, renderer(scene));
    GpuTest::TearDown();
  }
  // Draws `image` as view `def` with settings `s` and range [black, white]; the canvas bytes.
  std::vector<uint8_t> draw(const CpuImage& image, const ViewDef& def, const ViewSettings& s, float black, float white) {
    ViewImages uploaded;
    uploadViewImages(uploaded, ctx(), {image});
    Canvas canvas(ctx(), image.width, image.height);
    ResolvedRange range;
    range.black = black, range.white = white;
    const gpu::ViewParams params = viewParams(def, s, ViewGpuSource{}, range, Placement{0, 0, 1}, false, std::nullopt, {1, 1});
    std::vector<uint8_t> out = canvas.draw(mapper, renderer(scene), viewImageOf(uploaded, 0), params);
    canvas.destroy(ctx());
    destroyViewImages(uploaded, ctx());
    return out;
  }
  void expectColour(const std::vector<uint8_t>& out, size_t x, std::array<int, 3> expected, const char* what) {
    for (int c = 0; c < 3; ++c)
      EXPECT_NEAR(int(out[x * 4 + size_t(c)]), expected[size_t(c)], 1) << what << " texel " << x << " channel " << c;
  }
  Scene scene = builtinTemple(4);  // a renderer's context for the view pipelines; nothing is rendered
  ViewMapper mapper;
};

TEST_F(ViewColors, DepthInFalseColourAndOnALogScale) {
  ViewDef depth = viewOfVisual(Visual::Depth, 1);
  ViewSettings s;
  s.channels = 0x1;
  s.falseColor = true;
  // Near (black point) is the bright end: viridis(1), the middle viridis(0.5), far viridis(0),
  // matplotlib's values #fde725, #21918c, #440154.
  std::vector<uint8_t> out = draw(row({{1, 0, 0, 0}, {3, 0, 0, 0}, {5, 0, 0, 0}}), depth, s, 1.0f, 5.0f);
  expectColour(out, 0, {253, 231, 37}, "near");
  expectColour(out, 1, {33, 145, 140}, "middle");
  expectColour(out, 2, {68, 1, 84}, "far");
  // Log scale between 1 and 100: 10 sits halfway, grey 1 - 0.9 * 0.5 = 0.55 -> 140.
  s.falseColor = false;
  s.log = true;
  out = draw(row({{10, 0, 0, 0}}), depth, s, 1.0f, 100.0f);
  expectColour(out, 0, {140, 140, 140}, "log");
  // An empty texel (no surface) is black, not a colour of the map.
  float empty;
  const uint32_t bits = gpu::kEmptyTexel;
  std::memcpy(&empty, &bits, 4);
  out = draw(row({{empty, empty, empty, empty}}), depth, s, 1.0f, 100.0f);
  expectColour(out, 0, {0, 0, 0}, "empty");
}

TEST_F(ViewColors, StencilValuesAndBitsGetTheirHues) {
  ViewDef stencil = viewOfVisual(Visual::Stencil, 1, true);
  ViewSettings s;
  s.channels = 0x1;
  // colorsys.hsv_to_rgb(v * 0.618033988749895 % 1, 1, 1): 1 -> (0, 74, 255), 128 -> (255, 166, 0),
  // 255 -> (0, 104, 255); 0 is black.
  std::vector<uint8_t> out = draw(uintRow({0, 1, 128, 255}), stencil, s, 0.0f, 255.0f);
  expectColour(out, 0, {0, 0, 0}, "0");
  expectColour(out, 1, {0, 74, 255}, "1");
  expectColour(out, 2, {255, 166, 0}, "128");
  expectColour(out, 3, {0, 104, 255}, "255");
  // Isolating bit 7: 255 shows as 128, 1 as 0.
  s.stencilBits = 0x80;
  out = draw(uintRow({1, 255}), stencil, s, 0.0f, 255.0f);
  expectColour(out, 0, {0, 0, 0}, "1 & 0x80");
  expectColour(out, 1, {255, 166, 0}, "255 & 0x80");
}

TEST_F(ViewColors, IdsGetHashedColours) {
  ViewDef id = viewOfVisual(Visual::Id, 1, true);
  ViewSettings s;
  s.channels = 0x1;
  // lowbias32 in Python: 1 -> 0x688990c0, 1000 -> 0x53df6d52; colour 0.2 + 0.8 * (bytes 0, 1, 2) / 255.
  std::vector<uint8_t> out = draw(uintRow({0, 1, 1000}), id, s, 0.0f, 1.0f);
  expectColour(out, 0, {0, 0, 0}, "id 0");
  expectColour(out, 1, {205, 166, 161}, "id 1");
  expectColour(out, 2, {117, 138, 229}, "id 1000");
}

TEST_F(ViewColors, MotionOnBakersColourWheel) {
  ViewDef motion = viewOfVisual(Visual::Motion, 2);
  motion.negativeSuspicious = false;  // as the view table defines motion views: negative is a direction
  ViewSettings s;
  // Worked from the wheel's segments (RY 15, YG 6, GC 4, CB 11, BM 13, MR 6; 55 hues; hue =
  // (atan2(-y, -x) / pi + 1) / 2 * 54), white = 1:
  // (-1, 0): angle 0 -> hue 27 = CB step 2 = (0, 1 - 2/11, 1) -> (0, 209, 255);
  // (0, -1): 0.5 -> hue 40.5, between BM 4 and 5 = (4.5/13, 0, 1) -> (88, 0, 255);
  // (0, 1): -0.5 -> hue 13.5, between RY 13 and 14 = (1, 0.9, 0) -> (255, 230, 0);
  // (0, 0.5): half saturation: 1 - 0.5 (1 - c) = (1, 0.95, 0.5) -> (255, 242, 128).
  std::vector<uint8_t> out = draw(row({{-1, 0, 0, 0}, {0, -1, 0, 0}, {0, 1, 0, 0}, {0, 0.5f, 0, 0}}), motion, s, 0.0f, 1.0f);
  expectColour(out, 0, {0, 209, 255}, "left");
  expectColour(out, 1, {88, 0, 255}, "up");
  expectColour(out, 2, {255, 230, 0}, "down");
  expectColour(out, 3, {255, 242, 128}, "down, half");
}

TEST_F(ViewColors, HdrExposureScalesBeforeTheSrgbCurve) {
  ViewDef colour = viewOfVisual(Visual::Color, 3);
  colour.hdr = true;
  ViewSettings s;
  s.channels = 0x7;
  s.exposure = 1.0f;
  // (0.25, 0.5, 1) x 2 = (0.5, 1, 2): sRGB(0.5) = 0.7354 -> 188; 1 and above -> 255.
  std::vector<uint8_t> out = draw(row({{0.25f, 0.5f, 1.0f, 1.0f}}), colour, s, 0.0f, 1.0f);
  expectColour(out, 0, {188, 255, 255}, "EV +1");
}

}  // namespace gb
