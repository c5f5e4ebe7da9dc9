// Region statistics in the viewer: the rectangle selected with ctrl + drag, summarised from capture A
// (the numbers `gblens stats` gives for that capture and rect) or from a read-back of the rect of
// every screen target of the live frame (recomputed when a new full-resolution frame is shown).
#include <chrono>

#include "app/viewer/viewer.h"
#include "renderer/region_readback.h"
#include "renderer/render_targets.h"
#include "renderer/session.h"
#include "views/analysis/region_stats.h"

namespace gb {

void updateRegion(Viewer& v) {
  ViewerModel& m = v.model;
  if (!m.region || !m.regionDirty || !v.frameValid) return;
  const RegionRect r = *m.region;
  const auto start = std::chrono::steady_clock::now();
  if (m.source == FrameSource::Live) {
    if (m.reducedBy > 1) {  // stays dirty: the full frame follows when the input stops
      m.regionNote = "waiting for the full-resolution frame";
      return;
    }
    Renderer& rd = v.renderer;
    if (r.x + r.width > rd.options.width || r.y + r.height > rd.options.height) {
      m.region.reset();
      m.regionStats.reset();
      return;
    }
    const std::vector<Target> readable = readableTargets(rd, rd.options);
    std::vector<RegionRequest> requests;
    for (Target t : readable)
      if (screenSpaceTarget(t)) requests.push_back({t, int32_t(r.x), int32_t(r.y), r.width, r.height});
    FrameSnapshot snapshot = snapshotFromRenderer(rd, {});
    addRegions(snapshot, readbackRegions(rd, requests, readable));
    m.regionStats = regionStats(snapshot, r);
  } else {
    m.regionStats = regionStats(v.captureA.frame, r);
  }
  m.regionDirty = false;
  m.regionNote.clear();
  const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  nlohmann::json line = {{"event", "region"}, {"ms", ms}, {"stats", regionStatsJson(*m.regionStats)}};
  logLine(v.eventLog, line);
}

}  // namespace gb
