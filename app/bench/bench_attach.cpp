// The attach section of make bench (see bench_attach.h). The application is this gblens binary's
// own `render --stats` (its frame_ms: the throughput of frames in flight); the receiver decodes
// every frame it gets, as the viewer will.
#include "app/bench/bench_attach.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include "app/bench/bench_report.h"
#include "renderer/core/layout_json.h"
#include "views/live/live.h"

extern char** environ;

namespace gb {

namespace {

namespace fs = std::filesystem;

constexpr const char* kTargets[] = {"albedo_specular", "normal_shadow", "depth_stencil", "final"};
constexpr const char* kViewerPaced = "viewer 60 Hz";
constexpr const char* kViewerUnpaced = "viewer 60 Hz, unpaced";

std::string self() {
  std::error_code ec;
  return fs::read_symlink("/proc/self/exe", ec).string();
}

}  // namespace

nlohmann::json renderStats(const std::string& log) {
  std::ifstream in(log);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  const size_t open = text.find("{\n"), close = text.rfind('}');
  if (open == std::string::npos || close == std::string::npos) return nullptr;
  return nlohmann::json::parse(text.substr(open, close - open + 1), nullptr, false);
}

namespace {

long rssKb(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/status");
  for (std::string line; std::getline(in, line);)
    if (line.rfind("VmRSS:", 0) == 0) return std::stol(line.substr(6));
  return -1;
}

// The application without a receiver: with or without the layer loaded (idle). `peakKb`: its peak
// resident memory.
nlohmann::json runPlain(const std::vector<std::string>& argv, bool layerLoaded, const std::string& log,
                        long* peakKb = nullptr) {
  // Its statistics count even when it could not write its PNG (a GPU machine without OpenImageIO's
  // plugins, docs/perf-gpu/h27_carry.sh): the frames were rendered and timed.
  return runWithoutReceiver(argv, layerLoaded, log, peakKb) >= 0 ? renderStats(log) : nullptr;
}

}  // namespace

bool startAttached(LiveSession& s, const std::string& layout, const std::vector<std::string>& argv, const std::string& log,
                   int every, bool paced) {
  LiveOptions o;
  o.layout = layout;
  o.argv = argv;
  o.every = uint32_t(every);
  o.ringOffThread = true;  // as the viewer streams
  o.paced = paced;
  o.log = log;
  std::string error;
  if (s.start(o, error)) return true;
  std::fprintf(stderr, "gblens bench: attach: %s\n", error.c_str());
  return false;
}

Attached runAttached(const std::string& layout, int every, const std::vector<std::string>& argv, const std::string& log,
                     int soakFrames) {
  Attached a;
  LiveSession s;
  if (!startAttached(s, layout, argv, log, every, false)) return a;
  bool early = false;
  FrameSnapshot f;
  while (s.running() || s.attached()) {
    if (s.wait(f, 0.5)) s.recycle(std::move(f));  // as the viewer gives its frames back
    const uint64_t frames = s.counts().appFrames;
    const auto memory = [&] {
      return nlohmann::json{{"application_frames", frames}, {"rss_kb", rssKb(s.pid())},
                            {"ring_bytes", s.counts().layer.value("ring_bytes", 0)},
                            {"shm_bytes", s.counts().layer.value("shm_bytes", 0)}};
    };
    if (soakFrames && !early && frames >= uint64_t(soakFrames) / 10) a.soak["early"] = memory(), early = true;
    if (soakFrames && frames >= uint64_t(soakFrames) * 95 / 100 && s.running()) a.soak["late"] = memory();
  }
  a.counts = s.counts();
  a.app = renderStats(log);
  a.peakKb = s.applicationPeakKb();
  a.exitStatus = s.exitStatus();
  return a;
}

namespace {

// The four G-buffer targets of builtin:gblens under the default options, as a layout file.
std::string writeLayout(const std::string& dir) {
  Layout all = nativeLayout(RenderOptions{});
  Layout four = all;
  four.targets.clear();
  four.quantities.clear();
  for (const char* name : kTargets) {
    const int t = all.findTarget(name);
    for (const Quantity* q : all.quantitiesOf(uint32_t(t))) {
      Quantity k = *q;
      k.target = uint32_t(four.targets.size());
      four.quantities.push_back(k);
    }
    four.targets.push_back(all.targets[size_t(t)]);
  }
  const std::string path = dir + "/four_targets.json";
  std::ofstream(path) << layoutJson(four).dump(2);
  return path;
}

// A run's frames apart: the connect (the first kConnectFrames counted frames, where a receiver's
// ring is made) and the steady state after it (the median interval); the hitch is the longest
// connect frame over the steady median.
constexpr size_t kConnectFrames = 8;
struct Phases {
  double steadyMs = 0.0, hitchMs = 0.0;
};
Phases phases(const nlohmann::json& stats) {
  Phases p;
  if (!stats.is_object() || !stats.contains("frame_intervals_ms")) return p;
  std::vector<double> all = stats["frame_intervals_ms"].get<std::vector<double>>();
  if (all.size() <= kConnectFrames + 2) return p;
  std::vector<double> steady(all.begin() + long(kConnectFrames), all.end());
  std::sort(steady.begin(), steady.end());
  p.steadyMs = steady[steady.size() / 2];
  p.hitchMs = *std::max_element(all.begin(), all.begin() + long(kConnectFrames)) - p.steadyMs;
  return p;
}

}  // namespace

int runWithoutReceiver(const std::vector<std::string>& argv, bool layerLoaded, const std::string& log, long* peakKb) {
  std::vector<std::string> env;
  for (char** e = environ; *e; ++e)
    if (std::string(*e).rfind("GBLENS_LIVE_SOCKET=", 0) != 0) env.push_back(*e);
  if (layerLoaded)
    env.insert(env.end(), {"ENABLE_GBLENS_LIVE=1", "XDG_DATA_DIRS=" + layerFolder() + ":/usr/local/share:/usr/share"});
  else
    env.push_back("DISABLE_GBLENS_LIVE=1");
  std::vector<char*> args, envp;
  for (const std::string& a : argv) args.push_back(const_cast<char*>(a.c_str()));
  for (const std::string& e : env) envp.push_back(const_cast<char*>(e.c_str()));
  args.push_back(nullptr);
  envp.push_back(nullptr);
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, 1, 2);
  pid_t pid = -1;
  const bool started = posix_spawn(&pid, args[0], &files, nullptr, args.data(), envp.data()) == 0;
  posix_spawn_file_actions_destroy(&files);
  int status = 0;
  rusage usage{};
  if (!started || wait4(pid, &status, 0, &usage) != pid || !WIFEXITED(status)) return -1;
  if (peakKb) *peakKb = usage.ru_maxrss;
  return WEXITSTATUS(status);
}

std::string attachRoundsText(const nlohmann::json& frameMs) {
  std::string text;
  char number[32];
  for (const nlohmann::json& m : frameMs) {
    if (m.is_number()) std::snprintf(number, sizeof(number), "%s%.1f", text.empty() ? "" : ", ", m.get<double>());
    else std::snprintf(number, sizeof(number), "%sfailed", text.empty() ? "" : ", ");  // null: the run failed
    text += number;
  }
  return text;
}

const char* attachVariantTarget(const std::string& variant) {
  return variant == "idle" ? "< 1.01" : variant == "every frame" ? "<= 1.10" : "";
}

nlohmann::json attachVariantRow(const std::string& name, const std::vector<double>& ms, const std::vector<double>& without,
                                bool ratio) {
  nlohmann::json row = {{"name", name}, {"frame_ms", ms}};
  std::vector<double> ratios;
  for (size_t r = 0; r < ms.size() && r < without.size(); ++r)
    if (without[r] > 0.0 && ms[r] > 0.0) ratios.push_back(ms[r] / without[r]);
  if (ratio && !ratios.empty()) row["ratio"] = attachRatioJson(ratios);
  return row;
}

nlohmann::json attachRatioJson(const std::vector<double>& ratios) {
  const AbResult ab = abStatistics(ratios);
  return {{"median", ab.median}, {"min", ab.ratios.front()}, {"max", ab.ratios.back()}, {"ci_low", ab.ciLow},
          {"ci_high", ab.ciHigh}, {"confidence", ab.confidence}, {"per_round", ratios}};
}

nlohmann::json attachStudy(const AttachBenchSettings& s) {
  const auto start = std::chrono::steady_clock::now();
  const fs::path dir = fs::temp_directory_path() / ("gblens-bench-attach-" + std::to_string(getpid()));
  fs::create_directories(dir);
  const std::string layout = writeLayout(dir.string()), log = (dir / "app.log").string();
  // The raster G-buffer by default: its four targets are render-pass attachments. Where --gbuffer auto
  // picks the visibility path (the H200), albedo and normals are storage images a compute pass writes,
  // copied after its dispatches (docs/attach.md "Targets written by compute"): --attach-gbuffer.
  const std::vector<std::string> app = {self(), "render", "builtin:temple", "--size", s.size, "--frames",
                                        std::to_string(s.frames), "--gbuffer", s.gbuffer, "--stats", "-o", (dir / "frame.png").string()};
  // The last two: the viewer's receiver with a viewer taking frames at 60 Hz, paced (its default) and
  // not (what pacing saves the application when it is quicker than the viewer).
  const std::vector<std::string> names = {"without", "idle", "every frame", "every " + std::to_string(s.every) + "th frame",
                                          kViewerPaced, kViewerUnpaced};
  std::vector<nlohmann::json> viewer(names.size(), nlohmann::json::object());
  std::vector<std::vector<double>> ms(names.size());
  std::vector<std::vector<Phases>> phase(names.size());
  std::vector<double> latencyMs, latencyFrames, readyFrames;
  nlohmann::json streaming;
  for (int r = 0; r < s.rounds; ++r)
    for (size_t k = 0; k < names.size(); ++k) {
      const size_t v = (k + size_t(r)) % names.size();  // rotated: no variant always runs first
      nlohmann::json stats;
      if (v < 2) {
        stats = runPlain(app, v == 1, log);
      } else if (v >= 4) {
        uint64_t taken = 0;
        Attached a = runViewed(layout, app, log, 60.0, v == 4, taken);
        stats = a.app;
        viewer[v]["taken"].push_back(taken);
        viewer[v]["copied_frames"].push_back(a.counts.layer.value("copied_frames", uint64_t(0)));
        viewer[v]["application_frames"].push_back(a.counts.layer.value("frames", uint64_t(0)));
      } else {
        Attached a = runAttached(layout, v == 2 ? 1 : s.every, app, log);
        stats = a.app;
        if (v == 2 && stats.is_object()) {
          latencyMs.push_back(a.counts.meanLatencyMs);
          latencyFrames.push_back(a.counts.meanLatencyMs / stats.value("frame_ms", 1.0));
          readyFrames.push_back(a.counts.meanReadyMs / stats.value("frame_ms", 1.0));
          streaming = {{"received", a.counts.received}, {"dropped", a.counts.dropped}, {"latency_ms_max", a.counts.maxLatencyMs},
                       {"decode_ms", a.counts.meanDecodeMs}, {"ready_ms", a.counts.meanReadyMs}, {"layer", a.counts.layer}};
        }
      }
      ms[v].push_back(stats.is_object() ? stats.value("frame_ms", 0.0) : 0.0);
      phase[v].push_back(phases(stats));
    }
  nlohmann::json variants = nlohmann::json::array();
  for (size_t v = 0; v < names.size(); ++v) {
    nlohmann::json row = attachVariantRow(names[v], ms[v], ms[0], v > 0);
    // The steady state apart from the connect: the median frame after the first kConnectFrames, over
    // the same round's without the layer; the hitch: the longest connect frame over that median.
    std::vector<double> steady, hitch;
    for (int r = 0; r < s.rounds; ++r) {
      const Phases& p = phase[v][size_t(r)];
      const Phases& base = phase[0][size_t(r)];
      if (p.steadyMs > 0.0 && base.steadyMs > 0.0) steady.push_back(p.steadyMs / base.steadyMs);
      if (p.steadyMs > 0.0) hitch.push_back(p.hitchMs);
    }
    if (v > 0 && !steady.empty()) row["steady_ratio"] = attachRatioJson(steady);
    if (!hitch.empty()) row["connect_hitch_ms"] = hitch;
    if (!viewer[v].empty()) row["viewer"] = viewer[v], row["viewer"]["hz"] = 60.0, row["viewer"]["paced"] = v == 4;
    variants.push_back(row);
  }
  const auto median = [](std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v.empty() ? 0.0 : v[v.size() / 2];
  };
  streaming["latency_ms_mean"] = latencyMs;
  streaming["latency_frames_median"] = median(latencyFrames);
  streaming["ready_frames"] = median(readyFrames);
  // The soak: many small frames streamed, memory early and late.
  const std::vector<std::string> soakApp = {self(), "render", "builtin:temple", "--size", s.soakSize, "--frames",
                                            std::to_string(s.soakFrames), "--stats", "-o", (dir / "soak.png").string()};
  Attached soak = runAttached(layout, 1, soakApp, log, s.soakFrames);
  soak.soak["received"] = soak.counts.received;
  soak.soak["dropped"] = soak.counts.dropped;
  soak.soak["frames"] = s.soakFrames;
  soak.soak["size"] = s.soakSize;
  // The application's peak memory with the layer streaming and without it (its own grows with its
  // frames: gblens render keeps every frame's statistics).
  long without = 0;
  runPlain(soakApp, false, log, &without);
  soak.soak["peak_kb"] = soak.peakKb;
  soak.soak["peak_kb_without_layer"] = without;
  std::error_code ec;
  fs::remove_all(dir, ec);
  std::ostringstream application;
  for (size_t i = 1; i < app.size() - 2; ++i) application << (i > 1 ? " " : "") << app[i];
  return {{"application", "gblens " + application.str()},
          {"targets", kTargets},
          {"rounds", s.rounds},
          {"variants", variants},
          {"streaming", streaming},
          {"soak", soak.soak},
          {"seconds", std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count()}};
}

std::string attachMarkdown(const nlohmann::json& a) {
  if (!a.is_object()) return "";
  std::ostringstream md;
  char line[512];
  md << "\n## gblens attach: the layer's cost\n\n";
  md << "The application: `" << a.value("application", "") << "` (frame_ms: its frames in flight), streaming "
     << a["targets"].size() << " targets of builtin:gblens (albedo_specular, normal_shadow, depth_stencil, final) and the "
     << "camera; the receiver decodes every frame it gets. " << a.value("rounds", 0)
     << " interleaved rounds, variants rotated; ratio = the variant's frame time / the same round's without the layer "
     << "(median, and the interval of the median at the stated confidence).\n\n";
  md << "Steady: the median frame after the first " << kConnectFrames << " counted ones, over the same round's without the "
        "layer; hitch: the longest of those first frames (where a receiver's ring is made) over that median, the largest of "
        "the rounds.\n\n";
  md << "| variant | frame ms (per round) | ratio median | interval | steady ratio | hitch ms | target |\n"
        "| --- | --- | --- | --- | --- | --- | --- |\n";
  for (const nlohmann::json& v : a["variants"]) {
    const std::string ms = attachRoundsText(v["frame_ms"]), name = v.value("name", "");
    const char* target = attachVariantTarget(name);
    double hitch = 0.0;
    for (const nlohmann::json& h : v.value("connect_hitch_ms", nlohmann::json::array())) hitch = std::max(hitch, h.get<double>());
    const std::string steady = v.contains("steady_ratio") ? std::to_string(v["steady_ratio"].value("median", 0.0)).substr(0, 5) : "";
    if (v.contains("ratio"))
      std::snprintf(line, sizeof(line), "| %s | %s | %.3f | %.3f..%.3f (%.0f%%) | %s | %.1f | %s |\n", name.c_str(), ms.c_str(),
                    v["ratio"].value("median", 0.0), v["ratio"].value("ci_low", 0.0), v["ratio"].value("ci_high", 0.0),
                    100.0 * v["ratio"].value("confidence", 0.0), steady.c_str(), hitch, target);
    else
      std::snprintf(line, sizeof(line), "| %s | %s | 1 | | | %.1f | |\n", name.c_str(), ms.c_str(), hitch);
    md << line;
  }
  for (const nlohmann::json& v : a["variants"])
    if (v.contains("viewer")) {  // frames copied per frame the viewer took, over the rounds
      uint64_t taken = 0, copied = 0, frames = 0;
      for (size_t r = 0; r < v["viewer"]["taken"].size(); ++r)
        taken += v["viewer"]["taken"][r].get<uint64_t>(), copied += v["viewer"]["copied_frames"][r].get<uint64_t>(),
            frames += v["viewer"]["application_frames"][r].get<uint64_t>();
      std::snprintf(line, sizeof(line), "%s: the viewer took %llu frames of %llu, the application copied %llu (%.2f a frame taken).\n",
                    v.value("name", "").c_str(), (unsigned long long)taken, (unsigned long long)frames, (unsigned long long)copied,
                    taken ? double(copied) / double(taken) : 0.0);
      md << (v.value("name", "") == kViewerPaced ? "\n" : "") << line;
    }
  const nlohmann::json& st = a["streaming"];
  const nlohmann::json layer = st.value("layer", nlohmann::json::object());
  std::snprintf(line, sizeof(line),
                "\nStreaming every frame: %llu frames received, %llu dropped (the receiver was busy) in the last round; "
                "from the application's frame end to its copies done %.2f frames (median of the rounds' means; target "
                "<= 2), to the receiver having it decoded %.2f frames, max %.1f ms; the layer's own time in the application's threads %.2f ms a frame, its "
                "thread's copy into shared memory %.2f ms, the receiver's decoding %.1f ms. Ring %.1f MB (three slots), "
                "shared memory %.1f MB.\n",
                (unsigned long long)st.value("received", 0ull), (unsigned long long)st.value("dropped", 0ull),
                st.value("ready_frames", 0.0), st.value("latency_frames_median", 0.0), st.value("latency_ms_max", 0.0), layer.value("layer_ms_per_frame", 0.0),
                layer.value("thread_copy_ms", 0.0), st.value("decode_ms", 0.0), double(layer.value("ring_bytes", 0ull)) / 1e6, double(layer.value("shm_bytes", 0ull)) / 1e6);
  md << line;
  const nlohmann::json& soak = a["soak"];
  if (soak.contains("early") && soak.contains("late")) {
    std::snprintf(line, sizeof(line),
                  "\nSoak: %d frames at %s streamed (%llu received, %llu dropped). At application frame %llu: process "
                  "%ld kB, ring %.2f MB, shared memory %.2f MB; at frame %llu: %ld kB, ring %.2f MB, shared memory %.2f MB.\n",
                  soak.value("frames", 0), soak.value("size", "").c_str(), (unsigned long long)soak.value("received", 0ull),
                  (unsigned long long)soak.value("dropped", 0ull), (unsigned long long)soak["early"].value("application_frames", 0ull),
                  soak["early"].value("rss_kb", 0L), double(soak["early"].value("ring_bytes", 0ull)) / 1e6,
                  double(soak["early"].value("shm_bytes", 0ull)) / 1e6, (unsigned long long)soak["late"].value("application_frames", 0ull),
                  soak["late"].value("rss_kb", 0L), double(soak["late"].value("ring_bytes", 0ull)) / 1e6,
                  double(soak["late"].value("shm_bytes", 0ull)) / 1e6);
    md << line;
  }
  if (soak.contains("peak_kb")) {
    std::snprintf(line, sizeof(line), "The application's peak memory: %ld kB streaming, %ld kB without the layer.\n",
                  soak.value("peak_kb", 0L), soak.value("peak_kb_without_layer", 0L));
    md << line;
  }
  return md.str();
}

}  // namespace gb
