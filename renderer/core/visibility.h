// The visibility buffer's id (--gbuffer visibility; Burns and Hunt, "The Visibility Buffer: A
// Cache-Friendly Approach to Deferred Shading", JCGT 2013): one R32_UINT per pixel naming the
// draw and the triangle the raster pass kept there, from which gbuffer_resolve rebuilds the
// surface. No Vulkan here: the shaders pack and unpack the same way (shaders/visibility.glsl).
//
// Packing: id = ((draw + 1) << triangleBits) | triangle, where draw is the instance's index (the
// draw's gl_InstanceIndex, DrawData's index), triangle is gl_PrimitiveID within the draw, and 0
// means no geometry. triangleBits is per scene: the fewest bits that hold the triangle index of
// the largest mesh drawn (at least 1); the draw gets the remaining 32 - triangleBits bits. A scene
// fits when draws <= 2^(32 - triangleBits) - 1, i.e. draws * 2^triangleBits < 2^32 roughly: e.g.
// 1M-triangle meshes (20 bits) leave 4095 draws, 65536-triangle meshes (16 bits) 65535 draws.
// Beyond that, --gbuffer visibility is refused (visibilityPacking's error).
#pragma once
#include <cstdint>
#include <string>

#include "renderer/core/options.h"

namespace gb {

struct VisibilityPacking {
  uint32_t triangleBits = 1;  // low bits: the triangle within its draw
  uint32_t maxDraws = 0;      // draws the remaining bits can name (draw + 1 <= maxDraws)
};

// The packing for `draws` instances whose largest mesh has `maxTriangles` triangles; false with
// a message naming the limit when the scene does not fit.
bool visibilityPacking(uint64_t draws, uint64_t maxTriangles, VisibilityPacking& out, std::string& error);

inline uint32_t packVisibility(const VisibilityPacking& p, uint32_t draw, uint32_t triangle) {
  return ((draw + 1u) << p.triangleBits) | triangle;
}
// False for 0 (no geometry).
inline bool unpackVisibility(const VisibilityPacking& p, uint32_t id, uint32_t& draw, uint32_t& triangle) {
  if (id == 0) return false;
  draw = (id >> p.triangleBits) - 1u;
  triangle = id & ((1u << p.triangleBits) - 1u);
  return true;
}

// The frame fills its G-buffer through the visibility id: --gbuffer visibility on a frame that has
// a G-buffer stored between passes (not method forward, not the single-pass path).
inline bool visibilityFrame(const RenderOptions& o) {
  return o.gbuffer == GBufferKind::Visibility && o.method != Method::Forward && !singlePassFrame(o);
}
// Why --gbuffer visibility cannot run with these options ("" when it can, or when it is not asked):
// method forward has no G-buffer, the single-pass path keeps it in tile memory between subpasses.
std::string visibilityOptionsRefusal(const RenderOptions& o);

}  // namespace gb
