// RenderDoc's format descriptions (as its Python module reports them for the Vulkan formats) map to
// the TexelFormat gblens holds them in, and formats gblens cannot hold map to none. The RenderDoc
// round trip (tests/cli/test_renderdoc.cpp) exercises the formats gblens renders by default; this
// table covers the others.
#include <gtest/gtest.h>

#include <string>

#include "views/import/renderdoc_replay.h"

namespace gb {

TEST(RenderDocFormats, EachFormatGblensHoldsIsRecognised) {
  struct Case {
    RdcFormat rdc;
    std::optional<TexelFormat> want;
  };
  const Case cases[] = {
      {{"R8G8B8A8_SRGB", "Regular", "UNormSRGB", 4, 1, false}, TexelFormat::Rgba8Srgb},
      {{"R8G8B8A8_UNORM", "Regular", "UNorm", 4, 1, false}, TexelFormat::Rgba8Unorm},
      {{"R8G8B8A8_SNORM", "Regular", "SNorm", 4, 1, false}, TexelFormat::Rgba8Snorm},
      {{"R16G16B16A16_SNORM", "Regular", "SNorm", 4, 2, false}, TexelFormat::Rgba16Snorm},
      {{"R10G10B10A2_UNORM", "R10G10B10A2", "UNorm", 4, 1, false}, TexelFormat::Rgb10a2Unorm},
      {{"R16G16B16A16_FLOAT", "Regular", "Float", 4, 2, false}, TexelFormat::Rgba16f},
      {{"R32G32B32A32_FLOAT", "Regular", "Float", 4, 4, false}, TexelFormat::Rgba32f},
      {{"R32_FLOAT", "Regular", "Float", 1, 4, false}, TexelFormat::R32f},
      {{"R32_UINT", "Regular", "UInt", 1, 4, false}, TexelFormat::R32Uint},
      {{"D32S8", "D32S8", "Depth", 2, 1, false}, TexelFormat::D32fS8},
      {{"D24S8", "D24S8", "Depth", 2, 1, false}, TexelFormat::D24S8},
      {{"D32", "Regular", "Depth", 1, 4, false}, TexelFormat::D32f},
      {{"D16", "Regular", "Depth", 1, 2, false}, TexelFormat::D16},
      // 8-bit BGRA: the replay script swaps R and B back (as the gblens layer does live).
      {{"B8G8R8A8_UNORM", "Regular", "UNorm", 4, 1, true}, TexelFormat::Rgba8Unorm},
      {{"B8G8R8A8_SRGB", "Regular", "UNormSRGB", 4, 1, true}, TexelFormat::Rgba8Srgb},
      // Not held: another channel order, count or type; block compression; packed floats.
      {{"B10G10R10A2_UNORM", "R10G10B10A2", "UNorm", 4, 1, true}, std::nullopt},
      {{"R16G16_FLOAT", "Regular", "Float", 2, 2, false}, std::nullopt},
      {{"R32G32B32_FLOAT", "Regular", "Float", 3, 4, false}, std::nullopt},
      {{"R8G8B8A8_UINT", "Regular", "UInt", 4, 1, false}, std::nullopt},
      {{"R16G16B16A16_UNORM", "Regular", "UNorm", 4, 2, false}, std::nullopt},
      {{"R11G11B10_FLOAT", "R11G11B10", "Float", 3, 1, false}, std::nullopt},
      {{"BC7_UNORM", "BC7", "UNorm", 4, 1, false}, std::nullopt},
      {{"S8", "S8", "UInt", 1, 1, false}, std::nullopt},
  };
  for (const Case& c : cases) {
    auto named = [](std::optional<TexelFormat> f) { return std::string(f ? texelFormatInfo(*f).name : "none"); };
    EXPECT_EQ(named(texelFormatOf(c.rdc)), named(c.want)) << c.rdc.name;
  }
}

}  // namespace gb
