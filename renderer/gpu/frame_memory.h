// What a frame's targets cost in memory, known before anything is allocated, and whether the
// device can hold them: an output too large fails with a message instead of an allocation abort.
#pragma once
#include <cstdint>
#include <string>

#include "renderer/core/options.h"
#include "renderer/scene/scene.h"
#include "renderer/vk/context.h"

namespace gb {

struct FrameMemory {
  uint64_t targets = 0;   // every render target of the frame (image bytes, before alignment)
  uint64_t readback = 0;  // host buffers when every target is read back
};
FrameMemory frameMemory(const GpuContext& ctx, const Scene& scene, const RenderOptions& options);

// "" when the frame fits the device (its dimension limit, and its targets plus `readback` bytes
// in 90% of the largest memory heap, or of system memory on a CPU device); else one line naming --size, what it needs and what there is.
std::string frameTooLarge(const GpuContext& ctx, const Scene& scene, const RenderOptions& options,
                          uint64_t readback = 0);

}  // namespace gb
