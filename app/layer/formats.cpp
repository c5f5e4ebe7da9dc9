// The attachment formats the layer can stream, each with the layout storage format
// (docs/layout-format.md) its copied texels are: one table. A format not here is reported, never
// streamed as something else. B8G8R8A8 is streamed as rgba8 with R and B swapped back.
#include <string>

#include "app/layer/layer.h"

namespace gbl {

namespace {

#define GBL_F(f, storage, bytes, depth, stencil, bgra) {VK_FORMAT_##f, "VK_FORMAT_" #f, storage, bytes, depth, stencil, bgra}
const FormatInfo kFormats[] = {
    GBL_F(R8_UNORM, "r8_unorm", 1, false, false, false),
    GBL_F(R8_SNORM, "r8_snorm", 1, false, false, false),
    GBL_F(R8_UINT, "r8_uint", 1, false, false, false),
    GBL_F(R8G8_UNORM, "rg8_unorm", 2, false, false, false),
    GBL_F(R8G8_SNORM, "rg8_snorm", 2, false, false, false),
    GBL_F(R8G8_UINT, "rg8_uint", 2, false, false, false),
    GBL_F(R8G8B8A8_UNORM, "rgba8_unorm", 4, false, false, false),
    GBL_F(R8G8B8A8_SNORM, "rgba8_snorm", 4, false, false, false),
    GBL_F(R8G8B8A8_UINT, "rgba8_uint", 4, false, false, false),
    GBL_F(R8G8B8A8_SRGB, "rgba8_srgb", 4, false, false, false),
    GBL_F(B8G8R8A8_UNORM, "rgba8_unorm", 4, false, false, true),
    GBL_F(B8G8R8A8_SRGB, "rgba8_srgb", 4, false, false, true),
    GBL_F(A2B10G10R10_UNORM_PACK32, "rgb10a2_unorm", 4, false, false, false),
    GBL_F(R16_UNORM, "r16_unorm", 2, false, false, false),
    GBL_F(R16_SNORM, "r16_snorm", 2, false, false, false),
    GBL_F(R16_UINT, "r16_uint", 2, false, false, false),
    GBL_F(R16_SFLOAT, "r16f", 2, false, false, false),
    GBL_F(R16G16_UNORM, "rg16_unorm", 4, false, false, false),
    GBL_F(R16G16_SNORM, "rg16_snorm", 4, false, false, false),
    GBL_F(R16G16_UINT, "rg16_uint", 4, false, false, false),
    GBL_F(R16G16_SFLOAT, "rg16f", 4, false, false, false),
    GBL_F(R16G16B16A16_UNORM, "rgba16_unorm", 8, false, false, false),
    GBL_F(R16G16B16A16_SNORM, "rgba16_snorm", 8, false, false, false),
    GBL_F(R16G16B16A16_UINT, "rgba16_uint", 8, false, false, false),
    GBL_F(R16G16B16A16_SFLOAT, "rgba16f", 8, false, false, false),
    GBL_F(R32_UINT, "r32_uint", 4, false, false, false),
    GBL_F(R32_SFLOAT, "r32f", 4, false, false, false),
    GBL_F(R32G32_UINT, "rg32_uint", 8, false, false, false),
    GBL_F(R32G32_SFLOAT, "rg32f", 8, false, false, false),
    GBL_F(R32G32B32A32_UINT, "rgba32_uint", 16, false, false, false),
    GBL_F(R32G32B32A32_SFLOAT, "rgba32f", 16, false, false, false),
    GBL_F(D16_UNORM, "d16", 2, true, false, false),
    GBL_F(D32_SFLOAT, "d32f", 4, true, false, false),
    GBL_F(D24_UNORM_S8_UINT, "d24s8", 4, true, true, false),
    GBL_F(D32_SFLOAT_S8_UINT, "d32s8", 4, true, true, false),
    // Attachments no storage format holds: named in reports, never streamed.
    GBL_F(X8_D24_UNORM_PACK32, "", 4, true, false, false),
    GBL_F(B10G11R11_UFLOAT_PACK32, "", 4, false, false, false),
    GBL_F(A2R10G10B10_UNORM_PACK32, "", 4, false, false, false),
    GBL_F(R5G6B5_UNORM_PACK16, "", 2, false, false, false),
    GBL_F(R32G32B32_SFLOAT, "", 12, false, false, false),
    GBL_F(S8_UINT, "", 1, false, true, false),
};
#undef GBL_F

}  // namespace

const FormatInfo& formatInfo(VkFormat f) {
  for (const FormatInfo& i : kFormats)
    if (i.format == f) return i;
  static const FormatInfo unknown{};
  return unknown;
}

std::string formatName(VkFormat f) {
  const FormatInfo& i = formatInfo(f);
  return i.format == f && f != VK_FORMAT_UNDEFINED ? i.vkName : "VkFormat " + std::to_string(int(f));
}

}  // namespace gbl
