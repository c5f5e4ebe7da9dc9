// The frame-fit check that keeps an output the device cannot hold from reaching an allocation.
#include <gtest/gtest.h>

#include "renderer/gpu/frame_memory.h"
#include "tests/gpu/gpu_test.h"

namespace gb {

class FrameFit : public GpuTest {};

TEST_F(FrameFit, RefusesWhatTheDeviceCannotHoldAndNamesSize) {
  Scene s = floorScene();
  RenderOptions o;
  o.width = 640;
  o.height = 480;
  EXPECT_EQ(frameTooLarge(ctx(), s, o), "");
  // The estimate: at least colour + depth targets of the size (a lower bound computed by hand:
  // albedo 4 + normal 4 + eye depth 4 + depth/stencil 5 + hdr 16 + final 4 bytes per pixel).
  EXPECT_GE(frameMemory(ctx(), s, o).targets, uint64_t(640) * 480 * 37);
  GpuContext small = ctx();  // a copy with a small heap and a small dimension limit
  small.isCpu = false;       // (a CPU device is bounded by system memory instead)
  small.memory.memoryHeapCount = 1;
  small.memory.memoryHeaps[0].size = 4ull << 20;  // the frame needs ~11 MiB
  std::string why = frameTooLarge(small, s, o);
  EXPECT_NE(why.find("--size 640x480"), std::string::npos) << why;
  EXPECT_NE(why.find("GiB"), std::string::npos) << why;
  small.properties.limits.maxImageDimension2D = 512;
  why = frameTooLarge(small, s, o);
  EXPECT_NE(why.find("at most 512"), std::string::npos) << why;
}

}  // namespace gb
