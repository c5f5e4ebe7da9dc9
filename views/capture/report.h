// Frame statistics as JSON (the --stats output, bench rows, capture manifests): pass names,
// per-pass ms (median over frames), skips with reasons, culling statistics.
#pragma once
#include <nlohmann/json.hpp>

#include <string>
#include <vector>

#include "renderer/core/frame_stats.h"
#include "renderer/core/options.h"

namespace gb {

nlohmann::json optionsJson(const RenderOptions& o);
// The inverse of optionsJson (capture manifests). Members left out keep their defaults; a
// malformed member gives false and a message naming it.
bool optionsFromJson(const nlohmann::json& j, RenderOptions& o, std::string& error);
// One frame's figures (capture manifests, and what statsJson starts from): frame_ms, gpu_ms,
// cpu_ms, record_ms, render_pass_groups, passes (name, ms, skipped, reason), lights, sky_pixels,
// culling (valid, the counts; valid false with the reason when the frame did not count them).
nlohmann::json frameStatsJson(const FrameStats& frame);
// Where the frames were rendered: the device, its driver and SCENE as given.
struct StatsSource {
  std::string device, driver, scene;
};
// Times, passes and lights of `frames` (frameStatsJson of the last, with times and pass times as
// medians over all); the culling counts of `counted` when given (a frame rendered with coverage
// on after the timed ones), else of the last frame. With `burst` (`frames` began with a burst of
// frames in flight), frame_ms is its throughput; else the median of the frames' (each waited for);
// frame_ms_measured says which.
nlohmann::json statsJson(const std::vector<FrameStats>& frames, const StatsSource& source, const RenderOptions& o,
                         const FrameStats* counted = nullptr, const FrameBurst* burst = nullptr);

}  // namespace gb
