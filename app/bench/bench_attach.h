// The cost of `gblens attach` (issue 27) in make bench: gblens's own renderer (`gblens render
// builtin:temple`) as the application, its frame time without the layer, with the layer idle (no
// receiver), streaming four targets every frame and every Nth frame, in interleaved rounds (the
// ratios are per round, so the machine's load hits every variant alike); the ring's memory, a soak of
// many small frames (no growth), and the latency from the application's frame end to the receiver.
#pragma once
#include <nlohmann/json.hpp>

#include "views/live/live.h"

#include <string>
#include <vector>

namespace gb {

struct AttachBenchSettings {
  std::string size = "1280x720";
  int frames = 8;            // frames per run of the application (the first waited for, the rest in flight)
  int rounds = 5;            // interleaved rounds of the four variants
  int every = 4;             // the "every Nth frame" variant
  int soakFrames = 10000;    // the soak: frames streamed at soakSize
  std::string soakSize = "160x90";
  std::string gbuffer = "raster";  // the application's --gbuffer (visibility: three targets written by compute)
  // Another application (bench_attach_app.cpp): its command line, "{frames}" standing for its frame
  // count, and the layout it streams under; frames: the shorter of its two runs (the longer: 4x).
  std::string application, applicationLayout;
  int applicationFrames = 40;
};

// A session streaming `layout` from `argv` (its output to `log`) as the viewer streams (the ring made
// off the application's thread), every Nth frame, paced or not; false (said on stderr) if it did not start.
bool startAttached(LiveSession& s, const std::string& layout, const std::vector<std::string>& argv, const std::string& log,
                   int every, bool paced);
// The application under the layer, the receiver decoding every frame it gets (every Nth) until
// the application's end, giving each back as the viewer does; its output to `log` (its --stats read
// from there, gblens render's); soakFrames: its memory early and late too.
struct Attached {
  nlohmann::json app;   // the application's --stats (gblens render's; null for another)
  LiveCounts counts;    // the receiver's, with the layer's figures
  nlohmann::json soak;  // memory early and late (soak runs)
  long peakKb = 0;      // the application's peak resident memory
  int exitStatus = -1;  // the application's (-1: the session did not start)
};
Attached runAttached(const std::string& layout, int every, const std::vector<std::string>& argv, const std::string& log,
                     int soakFrames = 0);
// The same with the viewer's receiver (LiveReceiver) and a viewer that takes the newest frame `hz`
// times a second (bench_attach_viewer.cpp), paced or not (LiveOptions::paced); `taken`: the frames it
// took, `counts.layer` the layer's figures (copied_frames: what the application copied).
Attached runViewed(const std::string& layout, const std::vector<std::string>& argv, const std::string& log, double hz,
                   bool paced, uint64_t& taken);
// The JSON `gblens render --stats` printed among its other lines in `log` (null: none).
nlohmann::json renderStats(const std::string& log);
// The application run to its exit without a receiver: the layer not loaded, or loaded and idle; its
// output to `log`. Its exit status (-1: it did not start or was killed); `peakKb`: its peak memory.
int runWithoutReceiver(const std::vector<std::string>& argv, bool layerLoaded, const std::string& log, long* peakKb = nullptr);
// A variant's bench.json row: its frame ms per round and, with `ratio`, its ratios to `without`'s.
nlohmann::json attachVariantRow(const std::string& name, const std::vector<double>& ms, const std::vector<double>& without,
                                bool ratio);
// bench.md: a variant's frame ms per round ("37.7, 37.5, 38.0"), and its target ("" none).
std::string attachRoundsText(const nlohmann::json& frameMs);
const char* attachVariantTarget(const std::string& variant);
// Per-round ratios as bench.json gives them: median, range, the interval of the median, each round's.
nlohmann::json attachRatioJson(const std::vector<double>& ratios);
// Runs the study with the gblens executable this process is (it starts itself as the application).
nlohmann::json attachStudy(const AttachBenchSettings& s);
// The bench.md section.
std::string attachMarkdown(const nlohmann::json& study);
// The same four variants for another application (null without one), timed from outside: each run
// at two frame counts, the frame time the difference of their wall times over the difference.
nlohmann::json attachApplicationStudy(const AttachBenchSettings& s);
std::string attachApplicationMarkdown(const nlohmann::json& study);

}  // namespace gb
