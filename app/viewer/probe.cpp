// The pixel probe in the viewer: reads back only a 1x1 window of each target (plus the
// shadow-map texels the pixel's lookup reads) and hands them to the shared dossier.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "app/viewer/viewer.h"
#include "renderer/frame/region_readback.h"
#include "renderer/frame/session.h"
#include "renderer/gpu/render_targets.h"
#include "views/analysis/probe.h"
#include "views/analysis/view_text.h"

namespace gb {

void logLine(std::ofstream& f, const nlohmann::json& j) {
  if (!f.is_open()) return;
  f << j.dump() << '\n';
  f.flush();
}

// The frame as the probe sees it: matrices, lights and options of the live renderer, and the
// read-back windows as region TargetImages (texel (x0, y0) of the target is image texel (0, 0)).
void addRegions(FrameSnapshot& s, const std::vector<RegionImage>& regions) {
  for (const RegionImage& ri : regions) {
    if (ri.image.empty()) continue;
    TargetImage& ti = s.target(ri.target);
    ti.image = ri.image;
    ti.x0 = ri.x0;
    ti.y0 = ri.y0;
    ti.targetWidth = ri.targetWidth;
    ti.targetHeight = ri.targetHeight;
    s.setAbsence(ri.target, Absent::No);
  }
}

// The reference column of a live frame's probe, when the panel asks for it; the Embree scene is
// built once (the viewer's geometry never changes; lights are read at each frame's time).
static void probeReference(Viewer& v, const FrameSnapshot& snapshot, const PixelDossier& d) {
  ViewerModel& m = v.model;
  m.reference.reset();
  m.referenceNote.clear();
  if (!m.probeReference || !d.error.empty()) return;
  const auto start = std::chrono::steady_clock::now();
  if (!v.referenceRays) v.referenceRays = std::make_unique<reference::RayScene>(v.scene);
  m.reference = referencePixel(*v.referenceRays, snapshot, d);
  m.referenceMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  m.dossierJson["reference"] = referenceJson(*m.reference);
}

FrameSnapshot screenRegionSnapshot(Renderer& r, int x, int y, int width, int height) {
  const std::vector<Target> readable = readableTargets(r, r.options);
  std::vector<RegionRequest> requests;
  for (Target t : readable)
    if (screenSpaceTarget(t)) requests.push_back({t, x, y, uint32_t(width), uint32_t(height)});
  FrameSnapshot snapshot = snapshotFromRenderer(r, {});
  addRegions(snapshot, readbackRegions(r, requests, readable));
  return snapshot;
}

void probeViewerPixel(Viewer& v, glm::ivec2 p, bool logged) {
  auto start = v.clickPending && logged ? v.clickTime : std::chrono::steady_clock::now();
  if (logged) {
    v.clickPending = false;
    v.probeStart = start;
  }
  Renderer& r = v.renderer;
  ViewerModel& m = v.model;
  m.probeNote.clear();
  if (p.x < 0 || p.y < 0 || p.x >= int(r.options.width) || p.y >= int(r.options.height)) {
    // The pixel keeps its coordinates (never moved to another one); the frame does not hold it now.
    m.probePixel = p;
    m.dossier.reset();
    m.probeError = "pixel " + std::to_string(p.x) + "," + std::to_string(p.y) + " is outside the " +
                   std::to_string(r.options.width) + "x" + std::to_string(r.options.height) + " frame";
    return;
  }
  const uint32_t x = uint32_t(p.x), y = uint32_t(p.y);
  const std::vector<Target> readable = readableTargets(r, r.options);
  // 1. The pixel in every screen-space target (1x1 windows).
  FrameSnapshot snapshot = screenRegionSnapshot(r, p.x, p.y, 1, 1);
  // 2. The 2x2 shadow-map block its lookup reads, placed from the depth just read.
  int32_t sx = 0, sy = 0;
  bool hasShadowTexels = std::find(readable.begin(), readable.end(), Target::ShadowMap) != readable.end() &&
                         shadowMapFootprint(snapshot, x, y, sx, sy);
  if (hasShadowTexels) addRegions(snapshot, readbackRegions(r, {{Target::ShadowMap, sx, sy, 2, 2}}, readable));
  PixelDossier d = gb::probePixel(snapshot, x, y);
  m.probePixel = p;
  m.probeError = d.error;
  m.dossier = d;
  m.dossierJson = dossierJson(d);
  probeReference(v, snapshot, d);
  m.shadowTexelOfProbe.reset();
  if (d.shadowMap.valid)
    m.shadowTexelOfProbe = glm::ivec2(int(std::floor(d.shadowMap.texel.x + 0.5)), int(std::floor(d.shadowMap.texel.y + 0.5)));
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  m.probeLatencyMs = ms;
  if (!logged) return;
  logLine(v.probeLog, m.dossierJson);
  logLine(v.eventLog, {{"event", "probe"}, {"pixel", {p.x, p.y}}, {"latency_ms", ms}});
  std::fprintf(stderr, "gblens view: probe (%d, %d): dossier ready %.2f ms after the click\n", p.x, p.y, ms);
}

void refreshProbe(Viewer& v) {
  ViewerModel& m = v.model;
  const std::optional<PixelDossier> before = m.dossier;
  probeViewerPixel(v, *m.probePixel, false);
  if (!before || !m.dossier) return;
  // Stored bits of every target at the pixel: what "the content changed" means.
  bool changed = before->targets.size() != m.dossier->targets.size();
  for (size_t t = 0; !changed && t < before->targets.size(); ++t) {
    const ProbeTarget &a = before->targets[t], &b = m.dossier->targets[t];
    changed = a.present != b.present || a.channels.size() != b.channels.size();
    for (size_t c = 0; !changed && c < a.channels.size(); ++c) changed = a.channels[c].bits != b.channels[c].bits;
  }
  if (changed) m.probeNote = "the frame changed since the click: same pixel, new content";
  logLine(v.eventLog, {{"event", "probe_refreshed"}, {"pixel", {m.probePixel->x, m.probePixel->y}}, {"changed", changed}});
}

void countMarkedPixels(Viewer& v) {
  ViewerModel& m = v.model;
  if (!m.shadowMark) {
    m.shadowMarks.reset(), m.shadowMarkNote.clear();
    v.markCountKey.clear();
    return;
  }
  const bool live = m.source == FrameSource::Live;
  if (live && m.reducedBy > 1) {  // a reduced frame's lookups are not the full frame's
    m.shadowMarks.reset();
    m.shadowMarkNote = "counted when the full frame is drawn";
    return;
  }
  const std::string key = std::to_string(m.shadowMark->x) + "," + std::to_string(m.shadowMark->y) + "@" +
                          (live ? "live " + std::to_string(m.framesRendered) : "shown " + std::to_string(v.framesShown));
  if (key == v.markCountKey) return;
  v.markCountKey = key;
  // Where each pixel's lookup falls, from its depth (the rule of the shader's mark and of the probe).
  if (live) {
    Renderer& r = v.renderer;
    const std::vector<Target> readable = readableTargets(r, r.options);
    std::vector<RegionRequest> requests;
    for (Target t : {Target::Depth, Target::DepthStencil, Target::Position})
      if (std::find(readable.begin(), readable.end(), t) != readable.end())
        requests.push_back({t, 0, 0, r.options.width, r.options.height});
    FrameSnapshot snapshot = snapshotFromRenderer(r, {});
    addRegions(snapshot, readbackRegions(r, requests, readable));
    m.shadowMarks = shadowMarks(snapshot, *m.shadowMark);
  } else {
    m.shadowMarks = shadowMarks(v.captureA.frame, *m.shadowMark);
  }
  m.shadowMarkNote = m.shadowMarks->note;
  nlohmann::json line = {{"event", "shadow_mark"}, {"texel", {m.shadowMark->x, m.shadowMark->y}}, {"pixels", m.shadowMarks->pixels}};
  if (m.shadowMarks->box) {
    const RegionRect& b = *m.shadowMarks->box;
    line["box"] = {b.x, b.y, b.width, b.height};
  }
  if (!m.shadowMarkNote.empty()) line["note"] = m.shadowMarkNote;
  logLine(v.eventLog, line);
}

void readHover(Viewer& v) {
  ViewerModel& m = v.model;
  std::optional<int> view = m.hoverView;
  std::optional<glm::ivec2> texel = view && m.views[size_t(*view)].sun ? m.hoverShadowTexel : m.hover;
  if (texel == v.hoverRead && view == v.hoverReadView) return;
  v.hoverRead = texel;
  v.hoverReadView = view;
  m.hoverText.clear();
  if (!texel || !view || !v.frameValid || !m.unavailable[size_t(*view)].empty()) return;
  const ViewDef& d = m.views[size_t(*view)];
  std::optional<ViewSource> source = nativeSource(m.frameLayout, d);
  if (!source) return;
  // A reduced frame: the texel of it that covers the full-resolution texel (the probe refines first).
  glm::ivec2 at = *texel;
  const bool reduced = m.reducedBy > 1 && !d.sun;
  if (reduced)
    at = glm::min(glm::ivec2(glm::dvec2(at) * glm::dvec2(m.rendered.width, m.rendered.height) / glm::dvec2(m.fullSize)),
                  glm::ivec2(int(m.rendered.width) - 1, int(m.rendered.height) - 1));
  // The view's target and the depth that says whether a surface is there, read back at the texel,
  // decoded through the frame's layout as a capture's would be.
  Renderer& r = v.renderer;
  std::vector<RegionRequest> requests = {{source->target, at.x, at.y, 1, 1}};
  if (!d.sun && source->target != Target::Depth) requests.push_back({Target::Depth, at.x, at.y, 1, 1});
  FrameSnapshot snapshot = snapshotFromRenderer(r, {});
  addRegions(snapshot, readbackRegions(r, requests, readableTargets(r, r.options)));
  const std::vector<ViewDef> views = layoutViews(snapshot.layout);
  const int k = findView(views, d.name);
  if (k < 0) return;
  m.hoverText = viewValueText(snapshot, views[size_t(k)], uint32_t(at.x), uint32_t(at.y));
  if (reduced && !m.hoverText.empty()) m.hoverText += "  (of the reduced frame)";
}

}  // namespace gb
