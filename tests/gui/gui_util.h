// Helpers for GUI tests: child processes, an Xvfb server of the test's own (display chosen by
// Xvfb -displayfd, so parallel runs never collide), xdotool input, screenshots read as RGB.
#pragma once
#include "tests/support/test_paths.h"
#include <sys/types.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <functional>
#include <string>
#include <vector>

namespace gb::gui {

bool haveTool(const std::string& name);  // on PATH

// Starts `argv` with extra environment entries ("NAME=value"); stdout+stderr go to `logFile`.
pid_t spawn(const std::vector<std::string>& argv, const std::vector<std::string>& env, const std::string& logFile);
// Waits up to `seconds`; true with the exit status when it exited (-1: killed by a signal).
bool waitExit(pid_t pid, double seconds, int& status);
void terminate(pid_t pid);  // SIGTERM, then SIGKILL after 3 s

// Runs a shell command, returns stdout; status in `status`.
std::string run(const std::string& command, int* status = nullptr);

struct Xvfb {
  pid_t pid = -1;
  std::string display;  // ":N"
  bool start(int width, int height, std::string& error);
  void stop();
};

// Lines of a JSON-lines file from line `cursor` on; waits until `pred` holds for one (returns it
// and moves `cursor` past it) or times out (null).
nlohmann::json waitForLine(const std::string& file, double seconds, const std::function<bool(const nlohmann::json&)>& pred,
                           size_t& cursor);

// What a GUI test fixture holds: its folder (events.jsonl, viewer.log, screenshots), its Xvfb, the
// viewer it started and how far its event log was read. Fixtures inherit it (beside GpuTest where
// they need a device), so every one drives the viewer the same way.
struct Session {
  std::filesystem::path dir_;
  Xvfb xvfb_;
  pid_t viewer_ = -1;
  size_t eventCursor_ = 0;  // events before this line were consumed

  // A fresh `dir` and an Xvfb screen of width x height.
  bool openDisplay(const std::filesystem::path& dir, int width, int height, std::string& error);
  // The same in GBLENS_BUILD_DIR/<prefix><the running test's name>: a folder per test (ctest runs a
  // fixture's tests in parallel, and each starts by emptying its own).
  bool openTestDisplay(const std::string& prefix, int width, int height, std::string& error);
  void closeDisplay();  // the viewer terminated (if running), Xvfb stopped
  std::string xdotool(const std::string& args) const;
  // The next event of dir_/events.jsonl after those already waited for that `pred` accepts.
  nlohmann::json waitEvent(const std::function<bool(const nlohmann::json&)>& pred, double seconds = 30.0);
};

// The first of the tools the GUI tests drive the viewer with (xdotool, xwd, convert) that is not
// installed ("" : all are; debian-packages.txt lists them, make deps installs them).
std::string missingTool();

struct Screenshot {
  int width = 0, height = 0;
  std::vector<float> rgb;  // row-major, 3 floats per pixel in [0, 1]
  const float* at(int x, int y) const { return &rgb[(size_t(y) * width + x) * 3]; }
};
// Captures the root window of `display` (xwd), writes it as PNG to `png`, and reads it back.
bool screenshot(const std::string& display, const std::string& png, Screenshot& out, std::string& error);

// A thumbnail (n x n blocks, mean RGB each) of a rectangle of a screenshot: enough to tell views apart.
std::vector<float> thumbnail(const Screenshot& s, int x0, int y0, int x1, int y1, int n);
double meanAbsDifference(const std::vector<float>& a, const std::vector<float>& b);
double standardDeviation(const std::vector<float>& v);

}  // namespace gb::gui
