// gblens attach's command line (cmd_attach.cpp runs it): the flags, and every check of them that
// needs no application, apart from the command so that tests/fuzz/fuzz_attach.cpp can parse and
// check command lines without starting anything or opening a window.
#pragma once
#include <CLI/CLI.hpp>

#include <cstdint>
#include <string>
#include <vector>

#include "views/live/live.h"

namespace gb {

struct AttachOptions {
  std::string layout, output;
  std::vector<std::string> params, app;
  uint32_t every = 1;
  int64_t captureFrame = -1;  // the application's frame --capture-frame writes (0: its first); -1: none
  std::string captureFrames;  // --capture-frames A..B: those frames as a sequence ("" : none)
  uint64_t frames = 0;
  size_t history = 0;         // --history K: the stream keeps its last K decoded frames
  bool sequence() const { return !captureFrames.empty(); }
  bool capturing() const { return captureFrame >= 0 || sequence(); }  // writes frames to -o
  bool suggest = false, stats = false, keepRunning = false;
  double timeout = 300.0;
  std::string window = "1280x800", eventLog, probeLog;  // the viewer's
  bool paused = false;
  std::string pace;  // --pace on|off ("" : on for the viewer without --history, off otherwise)
};

// The flags of `gblens attach` on `cmd`, parsed into `o`.
void addAttachOptions(CLI::App* cmd, AttachOptions& o);

// The flags' combinations (one line naming the flag when they do not go together) and what the
// session is asked: `lo` (layout, --param values, the application, --every, the frame or the frames
// --capture-frames names, --history, --suggest).
bool checkAttachOptions(const AttachOptions& o, LiveOptions& lo, std::string& error);

}  // namespace gb
