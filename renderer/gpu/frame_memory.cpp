// Frame memory estimate and the device-fit check (see frame_memory.h).
#include "renderer/gpu/frame_memory.h"

#include <unistd.h>

#include <algorithm>
#include <cstdio>

#include "renderer/core/targets.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/vk/resources.h"

namespace gb {

FrameMemory frameMemory(const GpuContext& ctx, const Scene& scene, const RenderOptions& o) {
  FrameMemory m;
  for (size_t i = 0; i < kTargetCount; ++i) {
    Target t = Target(i);
    VkExtent2D e = targetExtent(ctx, t, scene, o);
    uint64_t w = e.width, h = e.height;
    VkFormat f = targetFormat(t, o);
    uint64_t bytes = w * h * bytesPerPixel(f);
    if (t == Target::DepthStencil) bytes += w * h;  // the stencil aspect
    if (!targetTransient(t, o)) m.targets += bytes;
    if (targetAbsence(t, o) == Absent::No) m.readback += bytes;
  }
  return m;
}

static std::string gib(uint64_t bytes) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f GiB", double(bytes) / double(1ull << 30));
  return buf;
}

std::string frameTooLarge(const GpuContext& ctx, const Scene& scene, const RenderOptions& o, uint64_t readback) {
  const uint32_t maxDim = ctx.properties.limits.maxImageDimension2D;
  const std::string size = "--size " + std::to_string(o.width) + "x" + std::to_string(o.height);
  if (o.width > maxDim || o.height > maxDim)
    return size + ": " + ctx.deviceName + " allows at most " + std::to_string(maxDim) + " pixels per side";
  const VkPhysicalDeviceMemoryProperties& mp = ctx.memory;
  uint64_t heap = 0;
  for (uint32_t i = 0; i < mp.memoryHeapCount; ++i) heap = std::max<uint64_t>(heap, mp.memoryHeaps[i].size);
  // A CPU device allocates from system memory: lavapipe reports a 2 GiB heap yet renders
  // 8192x8192 (2.6 GiB of targets). What bounds it is the machine's physical memory.
  const long pages = sysconf(_SC_PHYS_PAGES), pageSize = sysconf(_SC_PAGESIZE);
  if (ctx.isCpu && pages > 0 && pageSize > 0) heap = std::max<uint64_t>(heap, uint64_t(pages) * uint64_t(pageSize));
  uint64_t need = frameMemory(ctx, scene, o).targets + readback;
  if (heap && need > heap / 10 * 9)
    return size + ": the frame needs " + gib(need) + " of targets" + (readback ? " and read-back buffers" : "") +
           "; " + ctx.deviceName + "'s largest memory heap (system memory for a CPU device) is " + gib(heap) + " (use a smaller --size)";
  return "";
}

}  // namespace gb
