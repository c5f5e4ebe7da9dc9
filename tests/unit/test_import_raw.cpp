// Raw dumps whose size the layout does not explain are refused (issue 36, item 5): a 32x24 r32f dump
// is 768 floats, 3,072 bytes; 3,172 bytes (100 appended, or a 100-byte chunk inserted mid-file that
// shifts every texel after it) is refused, unless the layout states an offset or a row stride that
// explains it. Texels are checked against the values written, computed here.
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>

#include "tests/support/capture_util.h"
#include "views/import/import.h"

namespace gb {
namespace {

using json = nlohmann::json;
constexpr uint32_t kRawW = 32, kRawH = 24;

// The value written at texel (x, y): distinct everywhere, exact in float.
float texel(uint32_t x, uint32_t y) { return float(y * 100 + x); }

// Rows of 32 floats, each followed by `pad` bytes of 0xEE.
std::string dump(size_t pad = 0, bool padLast = true) {
  std::string bytes;
  for (uint32_t y = 0; y < kRawH; ++y) {
    for (uint32_t x = 0; x < kRawW; ++x) {
      const float v = texel(x, y);
      bytes.append(reinterpret_cast<const char*>(&v), 4);
    }
    if (y + 1 < kRawH || padLast) bytes.append(pad, char(0xEE));
  }
  return bytes;
}

// Imports `bytes` as d.bin through a layout with `source`; "" or the refusal. `image` gets the texels.
std::string import(const std::string& dir, const std::string& bytes, const json& source, CpuImage* image = nullptr,
                   const json& more = json()) {
  std::ofstream(dir + "/d.bin", std::ios::binary | std::ios::trunc) << bytes;
  json targets = {{{"name", "depth"}, {"format", "r32f"}, {"source", source},
                   {"quantities", {{{"quantity", "depth"}, {"name", "D"}, {"channels", {0}}, {"encoding", "eye"}}}}}};
  if (!more.is_null()) targets.push_back(more);
  json layout = {{"format", "gblens-layout"}, {"version", 1}, {"size", {kRawW, kRawH}}, {"targets", targets}};
  ImportInput in;
  std::string error;
  if (!parseLayout(layout, dir + "/l.json", in.layout, error)) return "layout: " + error;
  in.layoutDir = dir;
  FrameSnapshot f;
  if (!importFrame(in, f, error)) return error;
  if (image) *image = f.images[0].image;
  return "";
}

// Every texel of `image` is texel(x, y).
void expectTexels(const CpuImage& image) {
  ASSERT_EQ(image.width, kRawW);
  ASSERT_EQ(image.height, kRawH);
  for (uint32_t y = 0; y < kRawH; ++y)
    for (uint32_t x = 0; x < kRawW; ++x) {
      float v = 0.0f;
      std::memcpy(&v, &image.data[(size_t(y) * kRawW + x) * 4], 4);
      ASSERT_EQ(v, texel(x, y)) << x << "," << y;
    }
}

TEST(ImportRaw, ASizeTheLayoutDoesNotExplainIsRefused) {
  const std::string dir = freshDir("import_raw");
  const json plain = {{"file", "d.bin"}, {"raw", true}};
  CpuImage image;
  ASSERT_EQ(dump().size(), 3072u);
  EXPECT_EQ(import(dir, dump(), plain, &image), "");
  expectTexels(image);

  // 100 bytes appended, or inserted after the fifth row: the same 3,172 bytes, both refused.
  std::string inserted = dump();
  inserted.insert(5 * kRawW * 4, std::string(100, char(0x55)));
  for (const std::string& bytes : {dump() + std::string(100, '\0'), inserted}) {
    const std::string e = import(dir, bytes, plain);
    EXPECT_NE(e.find("d.bin: 3172 bytes, the layout explains 3072 (offset 0 + r32f 32x24)"), std::string::npos) << e;
    EXPECT_NE(e.find("source.offset or source.row_stride"), std::string::npos) << e;
  }
  // Short: refused as before.
  EXPECT_NE(import(dir, dump().substr(0, 3000), plain).find("needs 3072"), std::string::npos);

  // An offset explains a header; the texels are read after it.
  EXPECT_EQ(import(dir, std::string(100, 'H') + dump(), {{"file", "d.bin"}, {"raw", true}, {"offset", 100}}, &image), "");
  expectTexels(image);
  // A row stride explains padded rows (128 bytes of texels, 160 a row), the last row padded or not.
  const json strided = {{"file", "d.bin"}, {"raw", true}, {"row_stride", 160}};
  for (bool padLast : {true, false}) {
    SCOPED_TRACE(padLast);
    EXPECT_EQ(import(dir, dump(32, padLast), strided, &image), "");
    expectTexels(image);
  }
  EXPECT_NE(import(dir, dump(32) + "x", strided).find("3841 bytes, the layout explains 3840"), std::string::npos);
  EXPECT_NE(import(dir, dump(), {{"file", "d.bin"}, {"raw", true}, {"row_stride", 100}}).find("100 is less than a row's 128"),
            std::string::npos);

  // Two dumps in one file at their offsets: the file is the second's end.
  const json second = {{"name", "depth2"}, {"format", "r32f"}, {"source", {{"file", "d.bin"}, {"raw", true}, {"offset", 3072}}},
                       {"quantities", {{{"quantity", "depth"}, {"name", "D2"}, {"channels", {0}}, {"encoding", "eye"}}}}};
  EXPECT_EQ(import(dir, dump() + dump(), plain, &image, second), "");
  expectTexels(image);
  EXPECT_NE(import(dir, dump() + dump() + "tail", plain, nullptr, second).find("6148 bytes, the layout explains 6144"),
            std::string::npos);
}

}  // namespace
}  // namespace gb
