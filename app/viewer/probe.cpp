// The pixel probe in the viewer: reads back only a 1x1 window of each target (plus the
// shadow-map texels the pixel's lookup reads) and hands them to the shared dossier.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>

#include "app/viewer/viewer.h"
#include "renderer/region_readback.h"
#include "renderer/render_targets.h"
#include "renderer/session.h"
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

void probeViewerPixel(Viewer& v, glm::ivec2 p, bool logged) {
  auto start = v.clickPending && logged ? v.clickTime : std::chrono::steady_clock::now();
  if (logged) {
    v.clickPending = false;
    v.probeStart = start;
  }
  Renderer& r = v.renderer;
  ViewerModel& m = v.model;
  p = glm::clamp(p, glm::ivec2(0), glm::ivec2(int(r.options.width) - 1, int(r.options.height) - 1));
  const uint32_t x = uint32_t(p.x), y = uint32_t(p.y);
  std::vector<Target> readable = readableTargets(r, r.options);
  // 1. The pixel in every screen-space target (1x1 windows).
  std::vector<RegionRequest> requests;
  for (Target t : readable)
    if (screenSpaceTarget(t)) requests.push_back({t, p.x, p.y, 1, 1});
  FrameSnapshot snapshot = snapshotFromRenderer(r, {});
  addRegions(snapshot, readbackRegions(r, requests, readable));
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
