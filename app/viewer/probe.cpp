// The pixel probe in the viewer: reads back only a 1x1 window of each target (plus the
// shadow-map texels the pixel's lookup reads) and hands them to the shared dossier.
#include <chrono>
#include <cstdio>

#include "app/viewer/viewer.h"
#include "renderer/region_readback.h"

namespace gb {

void logLine(std::ofstream& f, const nlohmann::json& j) {
  if (!f.is_open()) return;
  f << j.dump() << '\n';
  f.flush();
}

std::vector<Target> readableTargets(const Renderer& r) {
  std::vector<Target> out;
  for (size_t i = 0; i < kTargetCount; ++i) {
    Target t = Target(i);
    const GraphTarget& g = r.targets[i];
    if (!g.image.image || g.image.desc.transient) continue;
    if ((t == Target::CoverageMasked || t == Target::CoverageFull) && !r.options.coverage) continue;
    out.push_back(t);
  }
  return out;
}

static std::string valuesText(const CpuImage& img) {
  std::string s;
  char buf[64];
  for (uint32_t c = 0; c < img.channelCount(); ++c) {
    std::snprintf(buf, sizeof buf, "%s%s %.7g", c ? ", " : "", img.channels[c].c_str(), img.value(0, 0, c));
    s += buf;
  }
  return s;
}

// Provisional dossier (until the capture branch's views/probe.h lands): stored values only.
static nlohmann::json provisionalDossier(const Viewer& v, glm::ivec2 p, const std::vector<RegionImage>& regions) {
  nlohmann::json j;
  j["pixel"] = {p.x, p.y};
  nlohmann::json targets = nlohmann::json::object();
  for (const RegionImage& ri : regions) {
    if (ri.image.empty()) continue;
    nlohmann::json t = nlohmann::json::object();
    for (uint32_t c = 0; c < ri.image.channelCount(); ++c)
      t[ri.image.channels[c]] = {{"value", ri.image.value(0, 0, c)}, {"bits", ri.image.raw(0, 0, c)}};
    targets[targetName(ri.target)] = t;
  }
  j["targets"] = targets;
  j["time"] = v.renderer.options.time;
  return j;
}

void probePixel(Viewer& v, glm::ivec2 p) {
  auto start = v.clickPending ? v.clickTime : std::chrono::steady_clock::now();
  v.clickPending = false;
  Renderer& r = v.renderer;
  ViewerModel& m = v.model;
  p = glm::clamp(p, glm::ivec2(0), glm::ivec2(int(r.options.width) - 1, int(r.options.height) - 1));
  std::vector<Target> readable = readableTargets(r);
  std::vector<RegionRequest> requests;
  for (Target t : readable)
    if (t != Target::ShadowMap) requests.push_back({t, p.x, p.y, 1, 1});
  std::vector<RegionImage> regions = readbackRegions(r, requests, readable);
  m.probePixel = p;
  m.probeError.clear();
  m.dossier = provisionalDossier(v, p, regions);
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  m.probeLatencyMs = ms;
  logLine(v.probeLog, m.dossier);
  logLine(v.eventLog, {{"event", "probe"}, {"pixel", {p.x, p.y}}, {"latency_ms", ms}});
  std::fprintf(stderr, "gblens view: probe (%d, %d) answered in %.2f ms\n", p.x, p.y, ms);
}

void readHover(Viewer& v) {
  ViewerModel& m = v.model;
  std::optional<glm::ivec2> texel = m.hover;
  std::optional<ViewKind> view = m.hoverView;
  if (view && viewDef(*view).source.target == Target::ShadowMap) texel = m.hoverShadowTexel;
  if (texel == v.hoverRead && view == v.hoverReadView) return;
  v.hoverRead = texel;
  v.hoverReadView = view;
  m.hoverText.clear();
  if (!texel || !view || !v.frameValid || !m.unavailable[int(*view)].empty()) return;
  const ViewDef& d = viewDef(*view);
  std::vector<RegionImage> regions =
      readbackRegions(v.renderer, {{d.source.target, texel->x, texel->y, 1, 1}}, readableTargets(v.renderer));
  if (regions[0].image.empty()) return;
  char head[96];
  std::snprintf(head, sizeof head, "%s (%d, %d): ", targetName(d.source.target), texel->x, texel->y);
  m.hoverText = head + valuesText(regions[0].image);
}

}  // namespace gb
