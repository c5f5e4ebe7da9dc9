// The viewer's loop. Renders on demand: a frame is rendered only when something it depends on
// changed (camera, options, lights, time), the interface is redrawn only for a few frames after
// an event, and with nothing to do the loop sleeps in glfwWaitEventsTimeout. Where a full frame
// is slow (a CPU device), frames changed by input are rendered reduced and refined when it stops.
#include "app/viewer/viewer.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui/backends/imgui_impl_glfw.h>
#include <imgui/backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <csignal>

#include "renderer/core/layout_json.h"
#include "renderer/gpu/render_targets.h"

namespace gb {

ViewDrawCallback viewDrawCallback();  // window.cpp

static std::atomic<bool> g_quit{false};

// Responsive rendering (issue 16, as Blender's viewport does it): while input changes the frame
// it is rendered at 1/n of the full size, n chosen so that one iteration (render, views, present)
// takes at most kInputBudgetMs, so input -> updated view (at most the iteration under way and the
// next) stays within 100 ms; kRefineAfterMs after the last input the full frame replaces it.
constexpr double kInputBudgetMs = 50.0;
constexpr double kRefineAfterMs = 100.0;
constexpr int kMaxReduction = 8;

static double msSince(std::chrono::steady_clock::time_point t) {
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
static void adaptReduction(Viewer& v, int reducedBy, double ms) {
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
static RenderOptions wantedOptions(Viewer& v, int fbWidth, int fbHeight) {
  ViewerModel& m = v.model;
  RenderOptions o = m.wanted;
  if (!m.fixedSize) {
    ImGuiIO& io = ImGui::GetIO();
    int w = 0, h = 0;
    glfwGetWindowSize(v.window, &w, &h);
    Rect area = viewArea(m, w, h);
    double sx = w ? double(fbWidth) / w : 1.0, sy = h ? double(fbHeight) / h : 1.0;
    (void)io;
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
  const bool dragging = glfwGetMouseButton(v.window, GLFW_MOUSE_BUTTON_RIGHT) == GLFW_PRESS && msSince(v.lastInput) < 300.0;
  return !v.pressedKeys.empty() || m.cameraDrag != glm::dvec2(0.0) || m.cameraDolly != 0.0 || dragging;
}

// Renders when the frame is outdated (at 1/n of `full` when input changed it and n > 1), or at
// full size when a reduced frame is on screen and input stopped kRefineAfterMs ago (or `refine`:
// the probe and captures read full-resolution frames).
static void renderIfNeeded(Viewer& v, const RenderOptions& full, bool animating, bool refine = false) {
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
  } else if (!outdated && (m.reducedBy == 1 || (!refine && msSince(v.lastInput) < kRefineAfterMs))) {
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
  m.rendered = o;
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

static void updateRanges(Viewer& v) {
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

static void logLayout(Viewer& v, int windowW, int windowH) {
  ViewerModel& m = v.model;
  Rect area = viewArea(m, windowW, windowH);
  nlohmann::json j = {{"event", "layout"}, {"window", {windowW, windowH}}, {"size", {m.rendered.width, m.rendered.height}}};
  nlohmann::json list = nlohmann::json::array();
  static const char* const kSides[] = {"a", "b", "difference", "flip"};
  for (const ViewSlot& slot : viewSlots(m, area)) {
    glm::uvec2 size = viewImageSize(m, slot.view);
    const Rect image = imageRectOf(m, slot);
    Placement p = placeImage(image, size.x, size.y, m.transform);
    list.push_back({{"view", m.views[size_t(slot.view)].name},
                    {"side", slot.split ? "split" : kSides[int(slot.side)]},
                    {"rect", {slot.rect.x, slot.rect.y, slot.rect.w, slot.rect.h}},
                    {"image_rect", {image.x, image.y, image.w, image.h}},  // the slot less its legend strip
                    {"origin", {p.originX, p.originY}},
                    {"scale", p.scale},
                    {"image", {size.x, size.y}}});
    if (slot.split) list.back()["split_at"] = m.splitAt;  // the swipe: A left of rect x + w * split_at
    // A view the frame cannot show (e.g. an imported layout without a shadow map) says why.
    if (!m.unavailable[size_t(slot.view)].empty()) list.back()["unavailable"] = m.unavailable[size_t(slot.view)];
  }
  j["views"] = list;
  std::string key = j.dump();
  if (key != v.layoutKey) {
    v.layoutKey = key;
    logLine(v.eventLog, j);
  }
  // The values printed in texels (at high zoom), when they change: what a person reads there.
  if (m.texelValuesDrawn == v.loggedTexelValues) return;
  v.loggedTexelValues = m.texelValuesDrawn;
  for (const TexelValuesDrawn& d : m.texelValuesDrawn) {
    nlohmann::json texels = nlohmann::json::array();
    for (const auto& [t, lines] : d.texels) texels.push_back({{"texel", {t.x, t.y}}, {"lines", lines}});
    logLine(v.eventLog, {{"event", "texel_values"}, {"view", m.views[size_t(d.view)].name}, {"side", kSides[int(d.side)]},
                         {"scale", d.scale}, {"texels", texels}});
  }
}

static void answerProbe(Viewer& v) {
  ViewerModel& m = v.model;
  if (m.source == FrameSource::Live && m.reducedBy > 1) renderIfNeeded(v, v.fullOptions, false, true);
  if (m.source == FrameSource::Live)
    probeViewerPixel(v, *m.probeRequest, true);
  else
    probeCapturePixel(v, *m.probeRequest);
  m.probeRequest.reset();
}

// `fresh`: the iteration's first interface frame takes the next queued input; a rebuild of the same
// frame (a click answered at once) sees the same input again.
static void buildInterface(Viewer& v, bool fresh = true) {
  if (fresh) feedInput(v);
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
  applyInputState(v);
  ImGui::NewFrame();
  v.draws.clear();
  drawViewerUi(v.model, viewDrawCallback(), v.draws);
}

// What the loop carries from one iteration to the next.
namespace {
struct LoopState {
  bool live = true;        // a live renderer (else --capture / --compare: nothing moves)
  bool animating = false;  // time runs this iteration
  bool keysHeld = false;   // WASD/QE move the camera this iteration
  bool minimised = false;
  bool ready = false;      // the first frame was shown (logged once)
};
}  // namespace

// Sleeps until there is something to do: polls while time runs, keys move the camera or the
// interface is settling after an event, else waits (waking twice a second to notice SIGTERM).
// False when this iteration draws nothing (minimised, idle, no swapchain yet).
static bool awaitWork(Viewer& v, LoopState& s, int& fbw, int& fbh) {
  const ViewerModel& m = v.model;
  s.animating = s.live && m.playing && m.timeSpeed != 0.0f;  // a capture does not move
  s.keysHeld = false;
  for (int key : {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_Q, GLFW_KEY_E})
    s.keysHeld |= glfwGetKey(v.window, key) == GLFW_PRESS && glfwGetKey(v.window, GLFW_KEY_LEFT_CONTROL) != GLFW_PRESS;
  // A reduced frame on screen is refined kRefineAfterMs after the last input.
  const double refineIn = v.model.reducedBy > 1 ? kRefineAfterMs - msSince(v.lastInput) : 1e9;
  if (!s.minimised && (s.animating || s.keysHeld || v.uiFramesLeft > 0))
    glfwPollEvents();
  else
    // idle: until an event (or SIGTERM, or the refinement; an attached stream is polled every 10 ms)
    glfwWaitEventsTimeout(std::clamp(refineIn / 1000.0, 0.001, v.args.attach ? 0.01 : 0.5));
  glfwGetFramebufferSize(v.window, &fbw, &fbh);
  s.minimised = fbw == 0 || fbh == 0 || glfwGetWindowAttrib(v.window, GLFW_ICONIFIED);
  if (s.minimised) {
    v.pressedKeys.clear();
    v.lastTick = std::chrono::steady_clock::now();
    return false;
  }
  const bool refineDue = v.model.reducedBy > 1 && msSince(v.lastInput) >= kRefineAfterMs;
  if (!s.animating && !s.keysHeld && v.uiFramesLeft <= 0 && !refineDue) return false;
  if (!v.swapchainValid || v.swapchain.extent.width != uint32_t(fbw) || v.swapchain.extent.height != uint32_t(fbh))
    if (!recreateSwapchain(v)) return false;
  return true;
}

// Keys, time, camera and lights applied and the frame rendered if outdated (live); automatic
// ranges, a pending probe, the hover read-out and a requested capture brought up to date.
static void updateFrame(Viewer& v, const LoopState& s, int fbw, int fbh, double dt) {
  ViewerModel& m = v.model;
  handleKeys(v);
  if (s.live) {
    if (s.animating) m.wanted.time += dt * m.timeSpeed;
    if (m.stepForward || m.stepBack) {
      m.wanted.time = std::max(0.0, m.wanted.time + (m.stepForward ? 1.0 : -1.0) / 30.0);
      m.playing = false;
    }
    updateCamera(v, dt);
    updateLights(v);
    renderIfNeeded(v, wantedOptions(v, fbw, fbh), s.animating);
  }
  m.stepForward = m.stepBack = false;
  updateRanges(v);
  v.referenceBusy = updateReferenceError(v);
  v.referenceBusy |= updateCompareFlip(v);
  if (m.probeRequest) answerProbe(v);
  updateRegion(v);
  countMarkedPixels(v);
  if (s.live) {
    readHover(v);
    if (m.hoverView && m.hover && m.views[size_t(*m.hoverView)].quantity < 0)  // a reference map: its value
      m.hoverText = referenceHoverText(v, *m.hoverView, *m.hover);
  } else {
    std::optional<glm::ivec2> texel = m.hoverView && m.views[size_t(*m.hoverView)].sun ? m.hoverShadowTexel : m.hover;
    m.hoverText = texel && m.hoverView ? captureHoverText(v, *m.hoverView, *texel) : "";
  }
  if (m.hoverText != v.loggedHover) {  // what the status bar says, for tests and scripts
    v.loggedHover = m.hoverText;
    if (!m.hoverText.empty()) logLine(v.eventLog, {{"event", "hover"}, {"view", m.views[size_t(*m.hoverView)].name}, {"text", m.hoverText}});
  }
  if (m.captureRequested || m.renderDocRequested) {
    if (s.live && m.reducedBy > 1) renderIfNeeded(v, v.fullOptions, false, true);  // captures are full-resolution
    std::string dir, error, rdc;
    const bool ok = captureLiveFrame(v, dir, error, m.renderDocRequested ? &rdc : nullptr);
    m.captureStatus = ok ? "wrote " + dir + (rdc.empty() ? "" : " and " + rdc) : "capture failed: " + error;
    logLine(v.eventLog, {{"event", "capture"}, {"status", m.captureStatus}, {"rdc", rdc}});
    m.captureRequested = m.renderDocRequested = false;
    v.rangesStale = true;
  }
}

// The interface built and presented; a click in it is answered in the same interface frame, and
// the frame that first shows its dossier is logged with the click's latency.
static void presentInterface(Viewer& v) {
  ViewerModel& m = v.model;
  m.uiChanged = false;
  buildInterface(v);
  if (m.probeRequest) {
    // A click in this interface frame: answer it now and show the dossier in the same frame.
    ImGui::EndFrame();
    answerProbe(v);
    v.probeShownPending = true;
    buildInterface(v, false);
  }
  if (m.copyJson) {
    const std::string text = m.dossierJson.dump(2);
    glfwSetClipboardString(v.window, text.c_str());
    m.copyJson = false;
    m.copiedBytes = text.size();
    m.copiedAt = ImGui::GetTime();
    logLine(v.eventLog, {{"event", "copied"}, {"bytes", text.size()}});
  }
  ImGui::Render();
  if (!presentFrame(v)) recreateSwapchain(v);
  if (v.args.attach) attachedFramePresented(v);
  if (v.probeShownPending) {  // the frame that shows a clicked pixel's dossier is on screen
    v.probeShownPending = false;
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - v.probeStart).count();
    logLine(v.eventLog, {{"event", "probe_shown"}, {"pixel", {m.probePixel->x, m.probePixel->y}}, {"latency_ms", ms}});
  }
}

// One iteration that draws: update, present, log, and how many more interface frames to draw.
static void iterate(Viewer& v, LoopState& s, int fbw, int fbh) {
  ViewerModel& m = v.model;
  auto now = std::chrono::steady_clock::now();
  const uint64_t renderedBefore = m.framesRendered;
  double dt = std::min(0.1, std::chrono::duration<double>(now - v.lastTick).count());
  v.lastTick = now;
  updateFrame(v, s, fbw, fbh, dt);
  presentInterface(v);
  if (m.framesRendered != renderedBefore) {
    const double ms = msSince(now);
    v.renderedLoopMs.push_back(ms);
    adaptReduction(v, m.reducedBy, ms);
    // Each rendered frame with its wall-clock time on screen (tests/gui/measure_viewer.sh times input -> view).
    const double epochMs =
        std::chrono::duration<double, std::milli>(std::chrono::system_clock::now().time_since_epoch()).count();
    logLine(v.eventLog, {{"event", "frame"},
                         {"size", {m.rendered.width, m.rendered.height}},
                         {"full", {m.fullSize.x, m.fullSize.y}},
                         {"reduced_by", m.reducedBy},
                         {"render_ms", m.stats.frameMs},
                         {"iteration_ms", ms},
                         {"shown_epoch_ms", epochMs}});
  }
  int winW = 0, winH = 0;
  glfwGetWindowSize(v.window, &winW, &winH);
  logLayout(v, winW, winH);
  if (!s.ready) {
    s.ready = true;
    logLine(v.eventLog, {{"event", "ready"}, {"size", {m.rendered.width, m.rendered.height}}});
  }
  // Changes made in this interface frame need another one (and maybe a render).
  bool pending = m.uiChanged || m.probeRequest || m.resetCamera || m.gltfCamera >= 0 || m.cameraDrag != glm::dvec2(0.0) ||
                 m.cameraDolly != 0.0 || m.stepForward || m.stepBack || m.captureRequested || m.renderDocRequested ||
                 v.referenceBusy || m.referenceError.computeRequested ||
                 (s.live && frameOutdated(v.fullOptions, wantedOptions(v, fbw, fbh)));
  v.uiFramesLeft = pending ? std::max(v.uiFramesLeft, 2) : v.uiFramesLeft - 1;
  // A new dossier's tables size their columns from what they drew in the frames before (ImGui):
  // a few more frames let them settle instead of freezing on clipped first-frame widths.
  if (m.dossier && v.dossierShownFor != m.probePixel) {
    v.dossierShownFor = m.probePixel;
    v.uiFramesLeft = std::max(v.uiFramesLeft, 4);
  }
}

int runViewer(const ViewerArgs& args, Scene scene) {
  Viewer v;
  v.args = args;
  v.scene = std::move(scene);
  if (!startViewer(v)) return 2;
  std::signal(SIGINT, [](int) { g_quit = true; });
  std::signal(SIGTERM, [](int) { g_quit = true; });
  v.lastTick = std::chrono::steady_clock::now();
  LoopState s;
  s.live = args.capture.empty() && !args.attach;
  while (!glfwWindowShouldClose(v.window) && !g_quit) {
    int fbw = 0, fbh = 0;
    if (args.attach && pollAttached(v)) v.uiFramesLeft = std::max(v.uiFramesLeft, 1);  // a new frame or status
    if (awaitWork(v, s, fbw, fbh)) iterate(v, s, fbw, fbh);
  }
  return finishViewer(v);
}

}  // namespace gb
