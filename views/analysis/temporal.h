// Analyses across the frames of a sequence (docs/temporal.md): motion vectors pair by pair
// (motion.h) with one verdict for the sequence, and flicker: per-pixel temporal statistics of any
// decoded quantity, each frame's values carried to the reference frame's pixels by reprojection.
#pragma once
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/image.h"
#include "views/analysis/motion.h"
#include "views/capture/sequence.h"

namespace gb {

// A sequence's frame loaded for analysis: the capture and what the sequence says of it.
struct LoadedFrame {
  std::shared_ptr<Capture> capture;
  TemporalFrame frame;  // frame.frame points into capture
};
bool loadTemporalFrame(const Sequence& seq, size_t i, LoadedFrame& out, std::string& error);

// Walks a sequence's frames in order with three in memory: visit(i, nullptr, nullptr, frame 0), then
// visit(i, N-2 or null, N-1, N) for every later frame; stops at a load failure or a visit's false.
// A sequence of fewer than two frames is refused first, naming `what` needs pairs ("motion").
using FramePairVisit = std::function<bool(size_t i, const TemporalFrame* before, const TemporalFrame* previous,
                                          const TemporalFrame& current, std::string& error)>;
bool walkFramePairs(const Sequence& seq, const char* what, const FramePairVisit& visit, std::string& error);
// A sequence check's verdict: "differs" with findings, else "agrees" when some pair decided, else "undecided".
const char* sequenceVerdict(const std::vector<std::string>& findings, bool anyDecided);
// Appends `s` to `list` unless it is there (a sequence's findings, each once).
void addFindingOnce(std::vector<std::string>& list, const std::string& s);

struct MotionSequenceOptions {
  std::string motion;         // the motion quantity's name ("": the layout's first)
  double inlierPixels = 0.0;  // 0: derived (motion.h)
  double wrongFraction = 0.02;  // of the surface, beyond which a pair's moving pixels are a finding
  std::function<void(const std::string&)> progress;
};

struct MotionReport {
  std::string motion;               // the quantity checked
  std::vector<MotionPair> pairs;
  std::vector<std::string> findings;  // every pair's differences and warp findings, each once
  // "agrees": every decided pair follows the layout; "differs": a finding; "undecided": no pair decided.
  std::string verdict;
};

// Loads the frames one window at a time (three in memory). False with one line when a frame cannot
// be read or the layout has no motion quantity.
bool checkMotionSequence(const Sequence& seq, const MotionSequenceOptions& options, MotionReport& out, std::string& error);
nlohmann::json motionReportJson(const MotionReport& r, const std::string& sequenceDir);
std::string motionReportText(const MotionReport& r);

struct FlickerOptions {
  std::string quantity;       // a decoded quantity's name (layout); its view's first channels
  int64_t reference = -1;     // frame number every frame is carried to (-1: the first)
  bool reproject = true;      // carry by depth and cameras; off: the same pixel in every frame
  std::function<void(const std::string&)> progress;
};

struct FlickerReport {
  std::string quantity;
  uint32_t components = 0;
  int64_t reference = 0;
  size_t frames = 0;
  // f32, one channel per component: the temporal standard deviation and the largest change between
  // consecutive frames, at the reference frame's pixels (NaN where fewer than two frames saw the point).
  CpuImage stddev, maxStep;
  CpuImage seen;  // f32: how many frames saw the point
  double meanStddev = 0.0, p99Stddev = 0.0, maxStepAll = 0.0;
};

bool flickerSequence(const Sequence& seq, const FlickerOptions& options, FlickerReport& out, std::string& error);
nlohmann::json flickerReportJson(const FlickerReport& r);

}  // namespace gb
