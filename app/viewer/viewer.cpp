// The viewer's loop, read top to bottom: await work, update (input, camera, render, probe, ranges),
// present, log. Renders on demand (frame_render.cpp): a frame is rendered only when something it
// depends on changed (camera, options, lights, time), the interface is redrawn only for a few frames
// after an event, and with nothing to do the loop sleeps in glfwWaitEventsTimeout.
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
  trackSequenceProbe(v);  // a sequence: the point followed through its frames
  trackLiveProbe(v);      // a frozen stream with kept frames: through those
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
  s.animating |= m.timeline.on && m.timeline.playing;         // a sequence plays
  s.keysHeld = false;
  for (int key : {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_Q, GLFW_KEY_E})
    s.keysHeld |= glfwGetKey(v.window, key) == GLFW_PRESS && glfwGetKey(v.window, GLFW_KEY_LEFT_CONTROL) != GLFW_PRESS;
  // A reduced frame on screen is refined kRefineAfterMs after the last input.
  const double refineIn = v.model.reducedBy > 1 ? kRefineAfterMs - millisecondsSince(v.lastInput) : 1e9;
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
  const bool refineDue = v.model.reducedBy > 1 && millisecondsSince(v.lastInput) >= kRefineAfterMs;
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
  updateSequence(v, dt);  // a sequence: the frame played or asked for
  updateRanges(v);
  v.referenceBusy = updateReferenceError(v);
  v.referenceBusy |= updateCompareFlip(v);
  v.referenceBusy |= updateTemporalViews(v);  // a sequence: the motion check, flicker
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
    const double ms = millisecondsSince(now);
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
                 m.cameraDolly != 0.0 || m.stepForward || m.stepBack || m.timeline.requested >= 0 || m.captureRequested || m.renderDocRequested ||
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
