// Helpers of the `gblens attach` tests: the environment that puts an application under the layer
// without a receiver, the test-only present-dump layer (tests/subjects/present_dump), captures
// compared texel for texel, and vkcube's cube seen as cube.c draws it (computed here, apart from
// gblens's decoder).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <glm/glm.hpp>
#include <nlohmann/json.hpp>

#include "views/capture/capture.h"
#include "views/live/live.h"

namespace gb::attach {

// The variables that load the gblens layer into an application (what LiveSession sets, minus the
// socket when `socket` is empty) and, with a dumpFile, the present-dump layer writing every present
// to dumpFile.N.
std::string layerEnvironment(const std::string& socket, const std::string& dumpFile = "");
// Synchronization validation for an application that enables the validation layer itself.
constexpr const char* kSyncValidation =
    "VK_LAYER_ENABLES=VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT:"
    "VALIDATION_CHECK_ENABLE_SYNCHRONIZATION_VALIDATION_QUEUE_SUBMIT";

// The layer's report of one frame's render passes (--suggest, no layout) for `argv` run under it
// with `environment` (and GBLENS_VALIDATE=1), its output in dir/app.log; the application is let run
// to its end (status: its exit status, -1 if it ran on past 60 s).
struct Report {
  nlohmann::json passes, hello;
  int status = -1;
  std::string log, error;
};
Report passesReport(const std::vector<std::string>& argv, const std::vector<std::string>& environment, const std::string& dir);

// A paced stream (LiveOptions::paced) of the application `o` runs: its first frame comes; then for
// a second of not asking, none, though the application renders on (its frame count in the next
// frame's layer figures); each of `cycles` frames after a ready() ended after that call (CLOCK_MONOTONIC,
// both processes' clock). With `oneTime` (recordings submitted once, so copies are recorded only for
// frames asked for) the frames copied across the hold are at most the two the application had in
// flight when it began. The session is detached and the application let run to its end (status 0:
// validation clean), or with `stop` ended (one that would run on for minutes).
void expectPacedStream(LiveOptions o, int cycles, bool oneTime, bool stop = false);

// A present the dump layer wrote: width, height, VkFormat and the raw texels.
struct Dump {
  uint32_t width = 0, height = 0;
  int format = 0;
  std::vector<uint8_t> texels;
};
bool readDump(const std::string& file, Dump& out);

// The targets two captures both hold whose stored texels differ (name: how many texels), and the
// targets only one holds.
std::vector<std::string> texelDifferences(const Capture& a, const Capture& b);

// vkcube (Vulkan-Tools 1.3.239 cube.c): the cube [-1, 1]^3 turned about Y by 4 degrees per frame
// (frame 0 already turned once), seen from (0, 3, 5) looking at the origin with a 45 degree
// perspective (aspect 1, near 0.1, far 100, Y flipped for Vulkan) in a square viewport. The hardware
// depth at a pixel's centre, 1 where the ray misses; `nearEdge` when a ray a tenth of a pixel away
// hits another face or misses (a texel rasterisation may give either).
double vkcubeDepth(uint32_t frame, uint32_t width, uint32_t height, uint32_t x, uint32_t y, bool& nearEdge);

}  // namespace gb::attach
