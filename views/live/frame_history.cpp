// FrameHistory (frame_history.h): the last K decoded frames of a stream, their bytes counted.
#include "views/live/frame_history.h"

namespace gb {

size_t frameBytes(const FrameSnapshot& frame) {
  size_t bytes = 0;
  for (const TargetImage& t : frame.images) {
    bytes += t.image.data.size();  // the sample shown: a plane of its own beside every sample's
    for (const CpuImage& s : t.samples) bytes += s.data.size();
  }
  return bytes;
}

void FrameHistory::setLimit(size_t limit) {
  limit_ = limit;
  trim();
}

void FrameHistory::push(const FrameSnapshot& frame, uint64_t appFrame, uint64_t stream, uint64_t endNs) {
  if (limit_ == 0) return;
  HistoryFrame h;
  h.frame = std::make_shared<const FrameSnapshot>(frame);
  h.appFrame = appFrame;
  h.stream = stream;
  h.endNs = endNs;
  h.bytes = frameBytes(frame);
  bytes_ += h.bytes;
  frames_.push_back(std::move(h));
  trim();
}

const HistoryFrame* FrameHistory::find(uint64_t appFrame) const {
  for (const HistoryFrame& h : frames_)
    if (h.appFrame == appFrame) return &h;
  return nullptr;
}

void FrameHistory::clear() {
  frames_.clear();
  bytes_ = 0;
}

void FrameHistory::trim() {
  while (frames_.size() > limit_) {
    bytes_ -= frames_.front().bytes;
    frames_.pop_front();
  }
}

}  // namespace gb
