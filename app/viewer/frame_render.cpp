// Rendering the live frame for the viewer's loop (viewer.cpp): on demand, reduced while input
// changes it and refined when it stops, the views' GPU sources and their automatic ranges.
#include "app/viewer/viewer.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cmath>

#include "renderer/core/layout_json.h"
#include "renderer/gpu/render_targets.h"

namespace gb {

// Responsive rendering (issue 16, as Blender's viewport does it): while input changes the frame
// it is rendered at 1/n of the full size, n chosen so that one iteration (render, views, present)
// takes at most kInputBudgetMs, so input -> updated view (at most the iteration under way and the
// next) stays within 100 ms; kRefineAfterMs after the last input the full frame replaces it.
constexpr double kInputBudgetMs = 50.0;
constexpr int kMaxReduction = 8;

double millisecondsSince(std::chrono::steady_clock::time_point t) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t).count();
}

// The reduction for a frame changed by input: fixed, off, or (auto) none while a full iteration
// fits the budget, else the adapted one.
static int reductionForInput(const Viewer& v) {
  const int mode = v.model.reduceWhileMoving;
  if (mode != ViewerModel::kReduceAuto) return std::max(mode, 1);
  return v.fullIterationMs <= kInputBudgetMs ? 1 : v.autoReduceBy;
}

// After a rendering iteration of `ms`: auto's next reduction, from the first full iteration's time
// (pixels scale as 1/n^2) and then from each reduced one (one step at a time).
void adaptReduction(Viewer& v, int reducedBy, double ms) {
  int& n = v.autoReduceBy;
  if (reducedBy == 1) {
    v.fullIterationMs = ms;
    if (v.reducedIterationMs == 0.0) n = std::clamp(int(std::ceil(std::sqrt(ms / kInputBudgetMs))), 2, kMaxReduction);
    return;
  }
  v.reducedIterationMs = ms;
  if (reducedBy != n) return;  // a fixed reduction or a refinement under way says nothing about n
  if (ms > kInputBudgetMs && n < kMaxReduction)
    ++n;
  else if (n > 2 && ms * double(n * n) / double((n - 1) * (n - 1)) < 0.7 * kInputBudgetMs)
    --n;
}

// The options the next frame needs: what the user chose, at the view area's size (or --size),
// with coverage only when a coverage view is shown or culling is measured.
RenderOptions wantedOptions(Viewer& v, int fbWidth, int fbHeight) {
  ViewerModel& m = v.model;
  RenderOptions o = m.wanted;
  if (!m.fixedSize) {
    int w = 0, h = 0;
    glfwGetWindowSize(v.window, &w, &h);
    Rect area = viewArea(m, w, h);
    double sx = w ? double(fbWidth) / w : 1.0, sy = h ? double(fbHeight) / h : 1.0;
    o.width = uint32_t(std::max(16.0, area.w * sx / m.renderScale));
    o.height = uint32_t(std::max(16.0, area.h * sy / m.renderScale));
  }
  o.camera = int(v.scene.cameras.size()) - 1;  // the viewer's camera (a copy of a scene camera)
  o.lights = m.lightCount;
  o.coverage = m.cullingStats;
  // A coverage view on screen needs the coverage targets rendered.
  for (int k : visibleViews(m))
    if (std::optional<ViewSource> src = nativeSource(m.frameLayout, m.views[size_t(k)]))
      o.coverage |= src->target == Target::CoverageMasked || src->target == Target::CoverageFull;
  o.keepGBuffer = true;  // views and the probe read the G-buffer in the single-pass path too
  return o;
}

// Whether input arrived that will change the frame (a refinement started now would only delay it):
// events are polled first, so a drag step that came in during the last frame counts.
static bool inputPending(Viewer& v) {
  glfwPollEvents();
  const ViewerModel& m = v.model;
  // A drag paused for a moment still counts: its next step is likely within a refinement's time.
  const bool dragging = glfwGetMouseButton(v.window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS && millisecondsSince(v.lastInput) < 300.0;
  return !v.pressedKeys.empty() || m.cameraDrag != glm::dvec2(0.0) || m.cameraDolly != 0.0 || dragging;
}

// Renders when the frame is outdated (at 1/n of `full` when input changed it and n > 1), or at
// full size when a reduced frame is on screen and input stopped kRefineAfterMs ago (or `refine`:
// the probe and captures read full-resolution frames).
void renderIfNeeded(Viewer& v, const RenderOptions& full, bool animating, bool refine) {
  ViewerModel& m = v.model;
  const bool sceneChanged = v.renderedCamera != v.cameraVersion || v.renderedLights != v.lightsVersion;
  const bool outdated = !v.frameValid || frameOutdated(v.fullOptions, full) || sceneChanged;
  RenderOptions before = v.fullOptions;
  if (animating) before.time = full.time;  // the animation's own time step is not input
  const bool input = v.frameValid && (sceneChanged || frameOutdated(before, full));
  int n = 1;
  if (input) {
    v.lastInput = std::chrono::steady_clock::now();
    n = reductionForInput(v);
  } else if (!outdated && (m.reducedBy == 1 || (!refine && millisecondsSince(v.lastInput) < kRefineAfterMs))) {
    return;
  }
  if (!input && n == 1 && m.reducedBy > 1 && !refine && inputPending(v)) return;  // refine when the input stops
  RenderOptions o = full;
  o.width = std::max(16u, (full.width + uint32_t(n) - 1) / uint32_t(n));
  o.height = std::max(16u, (full.height + uint32_t(n) - 1) / uint32_t(n));
  if (n == 1 || o.width >= full.width) o.width = full.width, o.height = full.height, n = 1;
  FrameRequest request;
  request.cullingStats = m.cullingStats;
  // Every target that can be read stays readable for the views and the probe.
  for (size_t i = 0; i < kTargetCount; ++i) {
    Target t = Target(i);
    if ((t == Target::CoverageMasked || t == Target::CoverageFull) && !o.coverage) continue;
    request.sampleAfter.push_back(t);
  }
  const FrameStats& stats = renderFrame(v.renderer, o, request);
  v.frameValid = true;
  v.renderedCamera = v.cameraVersion;
  v.renderedLights = v.lightsVersion;
  v.rangesStale = true;
  m.rendered = v.renderer.options;  // o as it ran: --gbuffer auto resolved (frameOptions)
  v.fullOptions = full;
  m.fullSize = {full.width, full.height};
  m.reducedBy = n;
  m.stats = stats;
  m.framesRendered++;
  v.renderMs.push_back(stats.frameMs);
  const ImageDesc& sm = v.renderer.targets[size_t(Target::ShadowMap)].image.desc;
  m.shadowMapSize = {sm.width, sm.height};
  updateLiveViews(v);
  // The probe stays on its full-resolution pixel (not logged: only clicks and arrow keys are): a
  // reduced frame leaves the dossier of the last full one, marked; the next full frame probes the same
  // pixel again and says whether what it holds changed.
  if (m.probePixel && !m.probeRequest) {
    if (n > 1)
      m.probeNote = "the frame is moving: this is the dossier of the last full frame";
    else
      refreshProbe(v);
  }
  m.regionDirty = m.regionDirty || m.region.has_value();  // the region's numbers follow the frame too
  v.hoverRead.reset();  // re-read the value under the mouse
  v.hoverReadView.reset();
}

void updateLiveViews(Viewer& v) {
  ViewerModel& m = v.model;
  Layout layout = nativeLayout(m.rendered);
  std::vector<ViewDef> views = layoutViews(layout);
  appendReferenceViews(v, views);  // the reference error's maps, once computed
  bool same = views.size() == m.views.size();
  for (size_t k = 0; same && k < views.size(); ++k) same = views[k].name == m.views[k].name && views[k].visual == m.views[k].visual;
  if (same)
    m.views = views;  // the same views; their encodings may differ
  else
    setViews(m, views);
  m.frameLayout = std::move(layout);
  for (size_t k = 0; k < m.views.size(); ++k) {
    std::string& why = m.unavailable[k];
    why.clear();
    if (m.views[k].quantity < 0) {  // a reference map
      why = referenceViewStatus(v, int(k));
      continue;
    }
    std::optional<ViewSource> src = nativeSource(m.frameLayout, m.views[k], &m.gpuSources[k]);
    if (!src) {
      why = "not one of gblens's targets";
      continue;
    }
    Absent absent = targetAbsence(src->target, m.rendered, v.scene.sun.enabled);
    if (absent != Absent::No)
      why = m.frameLayout.targets[m.views[k].target].name + ": " + absentText(absent);
    else if (!v.frameValid || !v.renderer.targets[size_t(src->target)].image.image)
      why = "not rendered yet";
  }
}

// The live range requests of a view: one per selected component, on the channel holding it.
static std::vector<RangeRequest> rangeRequests(const ViewerModel& m, int k) {
  std::vector<RangeRequest> out;
  const ViewDef& d = m.views[size_t(k)];
  const ViewSettings& s = m.settings[size_t(k)];
  std::optional<ViewSource> src = nativeSource(m.frameLayout, d);
  if (!s.autoRange || !src) return out;
  const ViewGpuSource& g = m.gpuSources[size_t(k)];
  const uint32_t mask = viewMapping(d, s).mask;
  for (uint32_t c = 0; c < 4; ++c)
    if ((mask & (1u << c)) && c < g.channelOf.size())
      out.push_back({*src, src->stencil ? 0u : g.channelOf[c], d.predicate, float(d.background.value_or(0.0))});
  return out;
}

void updateRanges(Viewer& v) {
  ViewerModel& m = v.model;
  if (m.source != FrameSource::Live) return updateCaptureRanges(v);
  std::vector<RangeRequest> all;
  std::vector<std::pair<int, size_t>> owners;  // view, count of its requests
  std::string key;
  for (int k : visibleViews(m)) {
    if (!m.unavailable[size_t(k)].empty()) continue;  // no target to measure
    std::vector<RangeRequest> q = rangeRequests(m, k);
    key += std::to_string(k) + ":" + std::to_string(m.settings[size_t(k)].channels) + (q.empty() ? "m;" : "a;");
    if (std::any_of(owners.begin(), owners.end(), [&](auto& o) { return o.first == k; })) continue;
    owners.push_back({k, q.size()});
    all.insert(all.end(), q.begin(), q.end());
  }
  if (!v.rangesStale && key == v.rangesKey) return;
  v.rangesStale = false;
  v.rangesKey = key;
  // The targets that exist on the GPU (a capture uploads only those it holds).
  std::vector<Target> targets;
  for (Target t : readableTargets(v.renderer, v.renderer.options))
    if (v.renderer.targets[size_t(t)].image.image != VK_NULL_HANDLE) targets.push_back(t);
  std::vector<RangeStats> stats = computeRanges(v.mapper, v.renderer, all, targets);
  size_t at = 0;
  for (auto& [k, n] : owners) {
    m.ranges[size_t(k)].assign(stats.begin() + long(at), stats.begin() + long(at + n));
    at += n;
  }
  m.uiChanged = true;
}

}  // namespace gb
