// Texels as bytes and back, for every TexelFormat: the packing a GPU copy produces
// (vkCmdCopyImageToBuffer; RenderDoc's texture data): colour formats tightly packed; depth/stencil
// formats the depth plane (4 bytes a texel for D32F and D24 in 32 bits, 2 for D16) followed by one
// stencil byte a texel. CpuImage holds RGB10A2 as four U16 channels and depth/stencil as two F32
// channels (depth, stencil); D24 depth is widened to float.
#pragma once
#include <cstdint>
#include <vector>

#include "renderer/core/image.h"
#include "renderer/core/targets.h"

namespace gb {

// Bytes one texel takes in the packed form (depth/stencil: the depth plane only).
uint32_t packedTexelBytes(TexelFormat f);
// All bytes of a packed w x h image (depth/stencil: both planes).
size_t packedImageBytes(TexelFormat f, uint32_t width, uint32_t height);

// Packed bytes -> a CpuImage of that format (type and encoding from texelFormatInfo; name and
// channel names left to the caller). `src` holds packedImageBytes(f, w, h) bytes.
CpuImage unpackTexels(TexelFormat f, const uint8_t* src, uint32_t width, uint32_t height);
// The same into `img`, keeping its buffer where it is large enough (a stream's frames are of one
// size: a buffer already written once is filled without page faults or zero-filling), large
// images split over the machine's cores.
void unpackTexelsInto(TexelFormat f, const uint8_t* src, uint32_t width, uint32_t height, CpuImage& img);
// Four-byte texels stored B, G, R, A (a B8G8R8A8 attachment copied as the GPU holds it) reordered
// R, G, B, A in place, split over the machine's cores for large images.
void swapRedBlue(CpuImage& img);
// The inverse: the CpuImage's texels packed for an upload into an image of format f.
std::vector<uint8_t> packTexels(const CpuImage& image, TexelFormat f);

}  // namespace gb
