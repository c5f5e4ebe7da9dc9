// The visibility id's packing per scene and the options it cannot run with.
#include "renderer/core/visibility.h"

namespace gb {

bool visibilityPacking(uint64_t draws, uint64_t maxTriangles, VisibilityPacking& out, std::string& error) {
  uint32_t bits = 1;
  while (bits < 32 && (uint64_t(1) << bits) < maxTriangles) ++bits;  // triangle indices 0 .. maxTriangles - 1
  const uint64_t maxDraws = bits >= 32 ? 0 : (uint64_t(1) << (32 - bits)) - 1;
  if (draws > maxDraws) {
    error = "--gbuffer visibility: the scene does not fit the 32-bit visibility id: " + std::to_string(draws) +
            " draws and up to " + std::to_string(maxTriangles) + " triangles in one mesh need " +
            std::to_string(bits) + " triangle bits, which leave room for " + std::to_string(maxDraws) +
            " draws (docs/architecture.md, the visibility buffer); use --gbuffer raster";
    return false;
  }
  out.triangleBits = bits;
  out.maxDraws = uint32_t(maxDraws);
  return true;
}

std::string visibilityOptionsRefusal(const RenderOptions& o) {
  if (o.gbuffer != GBufferKind::Visibility) return "";
  if (o.method == Method::Forward) return "--gbuffer visibility needs a G-buffer: method forward has none";
  if (singlePassFrame(o))
    return "--gbuffer visibility needs the two-pass path: gbuffer_resolve is a compute pass between the raster "
           "pass and lighting, which the single-pass path's subpasses cannot hold";
  return "";
}

}  // namespace gb
