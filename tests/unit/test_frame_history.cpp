// FrameHistory (views/live/frame_history.h, `gblens attach --history K`): the last K frames of a
// stream with their numbers, and never more than K frames' bytes.
#include <gtest/gtest.h>

#include "views/live/frame_history.h"

namespace gb {
namespace {

// A frame of one target, `bytes` of texels (and `samples` more planes of the same size).
FrameSnapshot frameOf(size_t bytes, uint8_t fill, size_t samples = 0) {
  FrameSnapshot f;
  f.images.resize(1);
  f.images[0].image.width = uint32_t(bytes);
  f.images[0].image.height = 1;
  f.images[0].image.data.assign(bytes, fill);
  for (size_t k = 0; k < samples; ++k) f.images[0].samples.push_back(f.images[0].image);
  return f;
}

TEST(AttachHistory, KeepsTheLastKFramesAndAtMostKFramesBytes) {
  FrameHistory h(3);
  for (uint64_t n = 10; n < 15; ++n) h.push(frameOf(1000, uint8_t(n)), n, n - 9, n * 100);
  ASSERT_EQ(h.frames().size(), 3u);
  EXPECT_EQ(h.frames().front().appFrame, 12u);  // oldest first
  EXPECT_EQ(h.frames().back().appFrame, 14u);
  EXPECT_EQ(h.frames().back().stream, 5u);
  EXPECT_EQ(h.frames().back().endNs, 1400u);
  EXPECT_EQ(h.bytes(), 3000u);
  ASSERT_NE(h.find(13), nullptr);
  EXPECT_EQ(h.find(13)->frame->images[0].image.data[0], 13);  // a copy of that frame
  EXPECT_EQ(h.find(11), nullptr);                              // gone
  h.setLimit(1);
  ASSERT_EQ(h.frames().size(), 1u);
  EXPECT_EQ(h.frames().front().appFrame, 14u);
  EXPECT_EQ(h.bytes(), 1000u);
  h.clear();
  EXPECT_EQ(h.bytes(), 0u);
}

TEST(AttachHistory, NoneKeptWithoutALimitAndSamplesCount) {
  FrameHistory none;
  none.push(frameOf(64, 1), 0, 1, 0);
  EXPECT_TRUE(none.frames().empty());
  EXPECT_EQ(none.bytes(), 0u);
  // A multisampled target: the sample shown and each sample's plane.
  EXPECT_EQ(frameBytes(frameOf(64, 1, 4)), 64u * 5u);
  FrameHistory two(2);
  two.push(frameOf(64, 1, 4), 0, 1, 0);
  two.push(frameOf(32, 2), 1, 2, 0);
  two.push(frameOf(16, 3), 2, 3, 0);
  EXPECT_EQ(two.bytes(), 48u);
}

}  // namespace
}  // namespace gb
