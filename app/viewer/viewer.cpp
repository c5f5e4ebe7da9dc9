// The viewer's loop. Renders on demand: a frame is rendered only when something it depends on
// changed (camera, options, lights, time), the interface is redrawn only for a few frames after
// an event, and with nothing to do the loop sleeps in glfwWaitEventsTimeout.
#include "app/viewer/viewer.h"

#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <imgui/backends/imgui_impl_glfw.h>
#include <imgui/backends/imgui_impl_vulkan.h>

#include <algorithm>
#include <atomic>
#include <csignal>

#include "renderer/render_targets.h"

namespace gb {

ViewDrawCallback viewDrawCallback();  // window.cpp

static std::atomic<bool> g_quit{false};

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
  for (ViewKind k : visibleViews(m))
    o.coverage |= k == ViewKind::CoverageMasked || k == ViewKind::CoverageFull;
  o.keepGBuffer = true;  // views and the probe read the G-buffer in the single-pass path too
  return o;
}

static void renderIfNeeded(Viewer& v, const RenderOptions& o) {
  ViewerModel& m = v.model;
  if (v.frameValid && !frameOutdated(v.renderer.options, o) && v.renderedCamera == v.cameraVersion &&
      v.renderedLights == v.lightsVersion)
    return;
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
  m.stats = stats;
  m.framesRendered++;
  v.renderMs.push_back(stats.frameMs);
  const ImageDesc& sm = v.renderer.targets[size_t(Target::ShadowMap)].image.desc;
  m.shadowMapSize = {sm.width, sm.height};
  for (int k = 0; k < kViewKindCount; ++k) {
    const ViewDef& d = viewDef(ViewKind(k));
    std::string& why = m.unavailable[k];
    why.clear();
    if (d.source.target == Target::ShadowMap && !v.scene.sun.enabled) why = "no sun: no shadow map";
  }
  // A pinned probe follows the frame (not logged: only clicks and arrow keys are).
  if (m.probePixel && !m.probeRequest) probeViewerPixel(v, *m.probePixel, false);
  v.hoverRead.reset();  // re-read the value under the mouse
  v.hoverReadView.reset();
}

static void updateRanges(Viewer& v) {
  ViewerModel& m = v.model;
  std::vector<RangeRequest> all;
  std::vector<std::pair<ViewKind, size_t>> owners;  // view, count of its requests
  std::string key;
  for (ViewKind k : visibleViews(m)) {
    std::vector<RangeRequest> q = rangeRequests(viewDef(k), m.settings[int(k)]);
    key += std::to_string(int(k)) + ":" + std::to_string(m.settings[int(k)].channels) + (q.empty() ? "m;" : "a;");
    if (std::any_of(owners.begin(), owners.end(), [&](auto& o) { return o.first == k; })) continue;
    owners.push_back({k, q.size()});
    all.insert(all.end(), q.begin(), q.end());
  }
  if (!v.rangesStale && key == v.rangesKey) return;
  v.rangesStale = false;
  v.rangesKey = key;
  std::vector<RangeStats> stats = computeRanges(v.mapper, v.renderer, all, readableTargets(v.renderer, v.renderer.options));
  size_t at = 0;
  for (auto& [k, n] : owners) {
    m.ranges[int(k)].assign(stats.begin() + long(at), stats.begin() + long(at + n));
    at += n;
  }
  m.uiChanged = true;
}

static void logLayout(Viewer& v, int windowW, int windowH) {
  ViewerModel& m = v.model;
  Rect area = viewArea(m, windowW, windowH);
  nlohmann::json j = {{"event", "layout"}, {"window", {windowW, windowH}}, {"size", {m.rendered.width, m.rendered.height}}};
  nlohmann::json list = nlohmann::json::array();
  static const char* const kSides[] = {"a", "b", "difference"};
  for (const ViewSlot& slot : viewSlots(m, area)) {
    glm::uvec2 size = viewImageSize(m, slot.kind);
    Placement p = placeImage(slot.rect, size.x, size.y, m.transform);
    list.push_back({{"view", viewName(slot.kind)},
                    {"side", slot.split ? "split" : kSides[int(slot.side)]},
                    {"rect", {slot.rect.x, slot.rect.y, slot.rect.w, slot.rect.h}},
                    {"origin", {p.originX, p.originY}},
                    {"scale", p.scale},
                    {"image", {size.x, size.y}}});
  }
  j["views"] = list;
  std::string key = j.dump();
  if (key == v.layoutKey) return;
  v.layoutKey = key;
  logLine(v.eventLog, j);
}

static void answerProbe(Viewer& v) {
  ViewerModel& m = v.model;
  if (m.source == FrameSource::Live)
    probeViewerPixel(v, *m.probeRequest, true);
  else
    probeCapturePixel(v, *m.probeRequest);
  m.probeRequest.reset();
}

static void buildInterface(Viewer& v) {
  ImGui_ImplVulkan_NewFrame();
  ImGui_ImplGlfw_NewFrame();
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
  if (!s.minimised && (s.animating || s.keysHeld || v.uiFramesLeft > 0))
    glfwPollEvents();
  else
    glfwWaitEventsTimeout(0.5);  // idle: sleep until an event (wake twice a second to notice SIGTERM)
  glfwGetFramebufferSize(v.window, &fbw, &fbh);
  s.minimised = fbw == 0 || fbh == 0 || glfwGetWindowAttrib(v.window, GLFW_ICONIFIED);
  if (s.minimised) {
    v.pressedKeys.clear();
    v.lastTick = std::chrono::steady_clock::now();
    return false;
  }
  if (!s.animating && !s.keysHeld && v.uiFramesLeft <= 0) return false;
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
    renderIfNeeded(v, wantedOptions(v, fbw, fbh));
  }
  m.stepForward = m.stepBack = false;
  updateRanges(v);
  if (m.probeRequest) answerProbe(v);
  if (s.live) {
    readHover(v);
  } else {
    std::optional<glm::ivec2> texel = m.hoverView && viewDef(*m.hoverView).source.target == Target::ShadowMap
                                          ? m.hoverShadowTexel
                                          : m.hover;
    m.hoverText = texel && m.hoverView ? captureHoverText(v, *m.hoverView, *texel) : "";
  }
  if (m.captureRequested) {
    m.captureRequested = false;
    std::string dir, error;
    m.captureStatus = captureLiveFrame(v, dir, error) ? "wrote " + dir : "capture failed: " + error;
    logLine(v.eventLog, {{"event", "capture"}, {"status", m.captureStatus}});
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
    buildInterface(v);
  }
  if (m.copyJson) {
    glfwSetClipboardString(v.window, m.dossierJson.dump(2).c_str());
    m.copyJson = false;
  }
  ImGui::Render();
  if (!presentFrame(v)) recreateSwapchain(v);
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
  if (m.framesRendered != renderedBefore)
    v.renderedLoopMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - now).count());
  int winW = 0, winH = 0;
  glfwGetWindowSize(v.window, &winW, &winH);
  logLayout(v, winW, winH);
  if (!s.ready) {
    s.ready = true;
    logLine(v.eventLog, {{"event", "ready"}, {"size", {m.rendered.width, m.rendered.height}}});
  }
  // Changes made in this interface frame need another one (and maybe a render).
  bool pending = m.uiChanged || m.probeRequest || m.resetCamera || m.gltfCamera >= 0 || m.cameraDrag != glm::dvec2(0.0) ||
                 m.cameraDolly != 0.0 || m.stepForward || m.stepBack || m.captureRequested ||
                 (s.live && frameOutdated(v.renderer.options, wantedOptions(v, fbw, fbh)));
  v.uiFramesLeft = pending ? std::max(v.uiFramesLeft, 2) : v.uiFramesLeft - 1;
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
  s.live = args.capture.empty();
  while (!glfwWindowShouldClose(v.window) && !g_quit) {
    int fbw = 0, fbh = 0;
    if (awaitWork(v, s, fbw, fbh)) iterate(v, s, fbw, fbh);
  }
  return finishViewer(v);
}

}  // namespace gb
