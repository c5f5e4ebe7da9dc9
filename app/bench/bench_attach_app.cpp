// make bench's attach section for an application that is not gblens (bench_attach.h
// attachApplicationStudy): any program with a frame count on its command line, timed from outside,
// since it prints no frame times of its own: each variant run at two frame counts, the frame time the
// difference of the wall times over the difference of the counts (start-up, pipeline compiles and a
// receiver's connect cancel).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "app/bench/bench_attach.h"
#include "app/bench/bench_report.h"

namespace gb {

namespace {

using Clock = std::chrono::steady_clock;

std::vector<std::string> commandFor(const std::string& command, int frames) {
  std::vector<std::string> argv;
  std::istringstream in(command);
  for (std::string word; in >> word;) {
    if (const size_t at = word.find("{frames}"); at != std::string::npos) word.replace(at, 8, std::to_string(frames));
    argv.push_back(word);
  }
  return argv;
}

// Seconds the application took to its exit without a receiver (the layer not loaded, or loaded
// and idle); negative when it failed.
double runAlone(const std::vector<std::string>& argv, bool layerLoaded) {
  const auto start = Clock::now();
  return runWithoutReceiver(argv, layerLoaded, "/dev/null") == 0 ? std::chrono::duration<double>(Clock::now() - start).count()
                                                                   : -1.0;
}

// Seconds to the application's exit under a receiver decoding every frame it gets (every Nth);
// negative when it failed.
double runStreamed(const std::string& layout, int every, const std::vector<std::string>& argv, LiveCounts* counts) {
  const auto start = Clock::now();
  const Attached a = runAttached(layout, every, argv, "/dev/null");  // its output, as runAlone's
  const double seconds = std::chrono::duration<double>(Clock::now() - start).count();
  if (counts) *counts = a.counts;
  return a.exitStatus == 0 ? seconds : -1.0;
}

}  // namespace

nlohmann::json attachApplicationStudy(const AttachBenchSettings& s) {
  if (s.application.empty()) return nullptr;
  const auto start = Clock::now();
  const std::vector<std::string> names = {"without", "idle", "every frame", "every " + std::to_string(s.every) + "th frame"};
  const int few = s.applicationFrames, many = s.applicationFrames * 4;
  std::vector<std::vector<double>> ms(names.size());
  LiveCounts streamed;
  for (int r = 0; r < s.rounds; ++r)
    for (size_t k = 0; k < names.size(); ++k) {
      const size_t v = (k + size_t(r)) % names.size();  // rotated: no variant always runs first
      double t[2];
      for (int i = 0; i < 2; ++i) {
        const std::vector<std::string> argv = commandFor(s.application, i ? many : few);
        t[i] = v < 2 ? runAlone(argv, v == 1)
                     : runStreamed(s.applicationLayout, v == 2 ? 1 : s.every, argv, v == 2 && i ? &streamed : nullptr);
      }
      // A run that failed: NaN (null in bench.json). On a loaded machine with short runs the
      // difference can even be negative; it is written as it came.
      ms[v].push_back(t[0] > 0.0 && t[1] > 0.0 ? (t[1] - t[0]) * 1e3 / double(many - few) : std::nan(""));
    }
  nlohmann::json variants = nlohmann::json::array();
  for (size_t v = 0; v < names.size(); ++v) {
    variants.push_back(attachVariantRow(names[v], ms[v], ms[0], v > 0));
  }
  return {{"application", s.application},
          {"layout", s.applicationLayout},
          {"frames", {few, many}},
          {"rounds", s.rounds},
          {"variants", variants},
          {"streaming", {{"received", streamed.received}, {"dropped", streamed.dropped}, {"decode_ms", streamed.meanDecodeMs},
                         {"layer", streamed.layer}}},
          {"seconds", std::chrono::duration<double>(Clock::now() - start).count()}};
}

std::string attachApplicationMarkdown(const nlohmann::json& a) {
  if (!a.is_object()) return "";
  std::ostringstream md;
  char line[512];
  md << "\n## gblens attach: the layer's cost for another application\n\n`" << a.value("application", "") << "` with `"
     << a.value("layout", "") << "`; frame ms = (wall time at " << a["frames"][1] << " frames - at " << a["frames"][0]
     << ") / the difference (the application prints no frame times; start-up and a receiver's connect cancel), "
     << a.value("rounds", 0) << " interleaved rounds, ratio = the variant's over the same round's without the layer.\n\n"
     << "| variant | frame ms (per round) | ratio median | interval | target |\n| --- | --- | --- | --- | --- |\n";
  for (const nlohmann::json& v : a["variants"]) {
    const std::string ms = attachRoundsText(v["frame_ms"]), name = v.value("name", "");
    const char* target = attachVariantTarget(name);
    if (v.contains("ratio"))
      std::snprintf(line, sizeof(line), "| %s | %s | %.3f | %.3f..%.3f (%.0f%%) | %s |\n", name.c_str(), ms.c_str(),
                    v["ratio"].value("median", 0.0), v["ratio"].value("ci_low", 0.0), v["ratio"].value("ci_high", 0.0),
                    100.0 * v["ratio"].value("confidence", 0.0), target);
    else
      std::snprintf(line, sizeof(line), "| %s | %s | 1 | | |\n", name.c_str(), ms.c_str());
    md << line;
  }
  const nlohmann::json& st = a["streaming"];
  std::snprintf(line, sizeof(line), "\nStreaming every frame (the last round's longer run): %llu received, %llu dropped, decoding %.1f ms a frame, ring shared: %s.\n",
                (unsigned long long)st.value("received", 0ull), (unsigned long long)st.value("dropped", 0ull), st.value("decode_ms", 0.0),
                st.value("layer", nlohmann::json::object()).value("ring_shared", false) ? "yes" : "no");
  md << line;
  return md.str();
}

}  // namespace gb
