// Sequences: consecutive frames as one folder, a capture per frame (frame_NNNN/) and sequence.json
// (each frame's number, time and camera jitter where known; docs/temporal.md). Written atomically like
// a capture; `SEQ@N` names frame N of one wherever a capture is taken (loadCapture resolves it).
#pragma once
#include <nlohmann/json.hpp>

#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include <glm/glm.hpp>

#include "views/capture/capture.h"

namespace gb {

constexpr int kSequenceFormatVersion = 1;

struct SequenceFrame {
  int64_t number = 0;                // the frame's number (the N of SEQ@N; an import's #### value)
  std::string dir;                   // its capture folder, relative to the sequence ("frame_0012")
  std::optional<double> time;        // seconds, when the source says
  // The sub-pixel offset the frame was rendered with (pixels, x right, y down: the projection moved
  // by it), when the source says. The capture's camera is the unjittered one.
  std::optional<glm::dvec2> jitter;
};

struct Sequence {
  std::string dir;
  nlohmann::json manifest;
  std::vector<SequenceFrame> frames;  // in number order, numbers strictly increasing
  std::string captureDir(size_t i) const;  // dir / frames[i].dir
  int find(int64_t number) const;          // index of frame `number`, or -1
};

// Whether `dir` holds a sequence.json (no validation).
bool isSequence(const std::string& dir);
// Loads and validates sequence.json (every frame's folder present; not the captures themselves).
bool loadSequence(const std::string& dir, Sequence& out, std::string& error);

// "SEQ@N": true with `captureDir` set to frame N's folder; false with `error` when SEQ is no
// sequence or has no frame N; false with an empty error when `text` is not of that form (a capture).
bool resolveSequenceFrame(const std::string& text, std::string& captureDir, std::string& error);

// What one frame of a sequence being written is: filled by the producer.
struct SequenceEntry {
  FrameSnapshot frame;
  CaptureMeta meta;
  int64_t number = 0;
  std::optional<double> time;
  std::optional<glm::dvec2> jitter;
};
// Writes `count` frames, produce(i, entry, error) filling each in turn, as the sequence `dir`
// (replaced when it is one; any other non-empty folder refused). `extra` is merged into
// sequence.json (the producer's record: "command_line", "source"). Nothing is left at `dir` unless
// every frame was written.
bool writeSequence(const std::string& dir, size_t count,
                   const std::function<bool(size_t i, SequenceEntry& entry, std::string& error)>& produce,
                   const nlohmann::json& extra, std::string& error);

// A frame range "A..B" (inclusive) or "N": false with a message naming `flag` otherwise.
bool parseFrameRange(const std::string& text, const std::string& flag, int64_t& first, int64_t& last,
                     std::string& error);

}  // namespace gb
