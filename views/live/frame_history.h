// The last frames of a live stream (`gblens attach --history K`, docs/attach.md): a bounded queue of
// decoded frames with the application's frame numbers, kept so that a timeline can go back over
// them. Its memory is bounded by K frames' texels: pushing frame K+1 lets the oldest go.
#pragma once
#include <cstddef>
#include <cstdint>
#include <deque>
#include <memory>

#include "renderer/core/snapshot.h"

namespace gb {

struct HistoryFrame {
  std::shared_ptr<const FrameSnapshot> frame;
  uint64_t appFrame = 0;  // the application's frame number (0: its first)
  uint64_t stream = 0;    // its number among the streamed frames (1, 2, ...)
  uint64_t endNs = 0;     // when the application ended it (CLOCK_MONOTONIC, live_wire.h monotonicNs)
  size_t bytes = 0;       // its texels' bytes (frameBytes)
};

// The bytes of a frame's texels: every target's image and its samples' planes.
size_t frameBytes(const FrameSnapshot& frame);

class FrameHistory {
 public:
  explicit FrameHistory(size_t limit = 0) : limit_(limit) {}
  size_t limit() const { return limit_; }  // frames kept at most (0: none)
  void setLimit(size_t limit);             // the oldest go when it shrinks
  // Keeps a copy of `frame` (nothing with a limit of 0); the oldest frame goes beyond the limit.
  void push(const FrameSnapshot& frame, uint64_t appFrame, uint64_t stream, uint64_t endNs);
  const std::deque<HistoryFrame>& frames() const { return frames_; }  // oldest first
  size_t bytes() const { return bytes_; }  // the texels kept: at most limit() frames' frameBytes
  const HistoryFrame* find(uint64_t appFrame) const;  // the kept frame of that number, or null
  void clear();

 private:
  void trim();
  size_t limit_ = 0, bytes_ = 0;
  std::deque<HistoryFrame> frames_;
};

}  // namespace gb
