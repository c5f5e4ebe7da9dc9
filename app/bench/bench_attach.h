// The cost of `gblens attach` (issue 27) in make bench: gblens's own renderer (`gblens render
// builtin:temple`) as the application, its frame time without the layer, with the layer idle (no
// receiver), streaming four targets every frame and every Nth frame, in interleaved rounds (the
// ratios are per round, so the machine's load hits every variant alike); the ring's memory, a soak of
// many small frames (no growth), and the latency from the application's frame end to the receiver.
#pragma once
#include <nlohmann/json.hpp>

#include <string>

namespace gb {

struct AttachBenchSettings {
  std::string size = "1280x720";
  int frames = 8;            // frames per run of the application (the first waited for, the rest in flight)
  int rounds = 5;            // interleaved rounds of the four variants
  int every = 4;             // the "every Nth frame" variant
  int soakFrames = 10000;    // the soak: frames streamed at soakSize
  std::string soakSize = "160x90";
  std::string gbuffer = "raster";  // the application's --gbuffer (visibility: three targets written by compute)
};

// Runs the study with the gblens executable this process is (it starts itself as the application).
nlohmann::json attachStudy(const AttachBenchSettings& s);
// The bench.md section.
std::string attachMarkdown(const nlohmann::json& study);

}  // namespace gb
