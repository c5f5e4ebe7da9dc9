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
#include <cstdio>

#include "renderer/core/statistics.h"
#include "renderer/render_targets.h"
#include "renderer/vk/check.h"

namespace gb {

ViewDrawCallback viewDrawCallback();  // window.cpp

static std::atomic<bool> g_quit{false};

static Viewer& viewerOf(GLFWwindow* w) { return *static_cast<Viewer*>(glfwGetWindowUserPointer(w)); }
static void wake(GLFWwindow* w) { viewerOf(w).uiFramesLeft = std::max(viewerOf(w).uiFramesLeft, 3); }

static void installCallbacks(Viewer& v) {
  glfwSetWindowUserPointer(v.window, &v);
  glfwSetKeyCallback(v.window, [](GLFWwindow* w, int key, int, int action, int mods) {
    if (action != GLFW_RELEASE) viewerOf(w).pressedKeys.push_back(key | (mods & GLFW_MOD_CONTROL ? 0x10000 : 0));
    wake(w);
  });
  glfwSetMouseButtonCallback(v.window, [](GLFWwindow* w, int button, int action, int) {
    if (button == GLFW_MOUSE_BUTTON_LEFT && action == GLFW_PRESS) {
      viewerOf(w).clickTime = std::chrono::steady_clock::now();  // click-to-dossier latency starts here
      viewerOf(w).clickPending = true;
    }
    wake(w);
  });
  glfwSetCursorPosCallback(v.window, [](GLFWwindow* w, double, double) { wake(w); });
  glfwSetScrollCallback(v.window, [](GLFWwindow* w, double, double) { wake(w); });
  glfwSetCharCallback(v.window, [](GLFWwindow* w, unsigned) { wake(w); });
  glfwSetWindowRefreshCallback(v.window, [](GLFWwindow* w) { wake(w); });
  glfwSetFramebufferSizeCallback(v.window, [](GLFWwindow* w, int, int) { wake(w); });
  glfwSetWindowFocusCallback(v.window, [](GLFWwindow* w, int) { wake(w); });
  glfwSetCursorEnterCallback(v.window, [](GLFWwindow* w, int) { wake(w); });
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

int runViewer(const ViewerArgs& args, Scene scene) {
  Viewer v;
  v.args = args;
  v.scene = std::move(scene);
  ViewerModel& m = v.model;
  unsigned ww = 0, wh = 0;
  char sep = 0;
  if (std::sscanf(args.window.c_str(), "%u%c%u", &ww, &sep, &wh) != 3 || ww < 64 || wh < 64) {
    std::fprintf(stderr, "gblens view: --window %s: expected WxH, at least 64x64\n", args.window.c_str());
    return 2;
  }
  const bool live = args.capture.empty();
  if (!args.compare.empty() && live) {
    std::fprintf(stderr, "gblens view: --compare B needs --capture A\n");
    return 2;
  }
  if (!args.probeLog.empty()) {
    v.probeLog.open(args.probeLog, std::ios::app);
    if (!v.probeLog) {
      std::fprintf(stderr, "gblens view: --probe-log %s: cannot open for writing\n", args.probeLog.c_str());
      return 2;
    }
  }
  if (!args.eventLog.empty()) {
    v.eventLog.open(args.eventLog, std::ios::app);
    if (!v.eventLog) {
      std::fprintf(stderr, "gblens view: --event-log %s: cannot open for writing\n", args.eventLog.c_str());
      return 2;
    }
  }
  if (!openWindow(v, ww, wh)) return 2;

  ContextOptions co;
  co.validation = args.validate;
  co.device = args.device;
  co.swapchain = true;
  uint32_t n = 0;
  const char** exts = glfwGetRequiredInstanceExtensions(&n);
  for (uint32_t i = 0; i < n; ++i) co.instanceExtensions.push_back(exts[i]);
  v.ctx = createContext(co);
  VK_CHECK(glfwCreateWindowSurface(v.ctx.instance, v.window, nullptr, &v.swapchain.surface));
  installCallbacks(v);
  while (!recreateSwapchain(v)) glfwWaitEvents();  // a window may open minimised
  initImGui(v);

  if (live) {
    // The scene camera the viewer starts from, copied to a camera of its own (the last one).
    resetRig(v.rig, v.scene.cameras[size_t(args.render.camera)], v.scene.bounds);
    v.scene.cameras.push_back(v.rig.desc);
    initRenderer(v.renderer, v.ctx, v.scene);
  } else if (!openCaptures(v)) {
    shutdownImGui(v);
    destroyRenderer(v.renderer);
    destroyRenderer(v.rendererB);
    closeWindow(v);
    destroyContext(v.ctx);
    return 2;
  }
  initViewMapper(v.mapper, v.renderer);

  for (int k = 0; k < kViewKindCount; ++k) m.settings[k] = defaultSettings(ViewKind(k));
  m.wanted = args.render;
  m.fixedSize = args.sizeGiven;
  m.lightCount = int(v.scene.generatedLights ? args.render.lights : int(v.scene.lights.size()));
  m.playing = !args.paused;
  parseView(args.initialView, m.primary);
  m.edited = m.primary;
  m.deviceName = v.ctx.deviceName;
  m.sceneName = live ? args.scene : args.capture + (args.compare.empty() ? "" : " vs " + args.compare);
  if (live) {
    for (size_t i = 0; i + 1 < v.scene.cameras.size(); ++i)
      m.cameraNames.push_back(v.scene.cameras[i].name.empty() ? "camera " + std::to_string(i) : v.scene.cameras[i].name);
    m.captureAvailable = true;
    m.captureHint = "Writes this frame, every target at full precision, to ./gblens-capture-<date>-<time>/\n"
                    "(EXR per target + manifest.json; open it with gblens view --capture DIR)";
  }

  std::signal(SIGINT, [](int) { g_quit = true; });
  std::signal(SIGTERM, [](int) { g_quit = true; });
  v.lastTick = std::chrono::steady_clock::now();
  bool ready = false, minimised = false;
  while (!glfwWindowShouldClose(v.window) && !g_quit) {
    bool animating = live && m.playing && m.timeSpeed != 0.0f;  // a capture does not move
    bool keysHeld = false;
    for (int key : {GLFW_KEY_W, GLFW_KEY_A, GLFW_KEY_S, GLFW_KEY_D, GLFW_KEY_Q, GLFW_KEY_E})
      keysHeld |= glfwGetKey(v.window, key) == GLFW_PRESS && glfwGetKey(v.window, GLFW_KEY_LEFT_CONTROL) != GLFW_PRESS;
    if (!minimised && (animating || keysHeld || v.uiFramesLeft > 0))
      glfwPollEvents();
    else
      glfwWaitEventsTimeout(0.5);  // idle: sleep until an event (wake twice a second to notice SIGTERM)
    int fbw = 0, fbh = 0;
    glfwGetFramebufferSize(v.window, &fbw, &fbh);
    minimised = fbw == 0 || fbh == 0 || glfwGetWindowAttrib(v.window, GLFW_ICONIFIED);
    if (minimised) {
      v.pressedKeys.clear();
      v.lastTick = std::chrono::steady_clock::now();
      continue;
    }
    if (!animating && !keysHeld && v.uiFramesLeft <= 0) continue;
    if (!v.swapchainValid || v.swapchain.extent.width != uint32_t(fbw) || v.swapchain.extent.height != uint32_t(fbh))
      if (!recreateSwapchain(v)) continue;

    auto now = std::chrono::steady_clock::now();
    const uint64_t renderedBefore = m.framesRendered;
    double dt = std::min(0.1, std::chrono::duration<double>(now - v.lastTick).count());
    v.lastTick = now;
    handleKeys(v);
    if (live) {
      if (animating) m.wanted.time += dt * m.timeSpeed;
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
    if (live) {
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
    if (m.framesRendered != renderedBefore)
      v.renderedLoopMs.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - now).count());
    int winW = 0, winH = 0;
    glfwGetWindowSize(v.window, &winW, &winH);
    logLayout(v, winW, winH);
    if (!ready) {
      ready = true;
      logLine(v.eventLog, {{"event", "ready"}, {"size", {m.rendered.width, m.rendered.height}}});
    }
    // Changes made in this interface frame need another one (and maybe a render).
    bool pending = m.uiChanged || m.probeRequest || m.resetCamera || m.gltfCamera >= 0 || m.cameraDrag != glm::dvec2(0.0) ||
                   m.cameraDolly != 0.0 || m.stepForward || m.stepBack || m.captureRequested ||
                   (live && frameOutdated(v.renderer.options, wantedOptions(v, fbw, fbh)));
    v.uiFramesLeft = pending ? std::max(v.uiFramesLeft, 2) : v.uiFramesLeft - 1;
  }

  nlohmann::json summary = {{"event", "exit"},
                            {"frames_rendered", m.framesRendered},
                            {"frames_presented", m.framesPresented},
                            {"render_ms_median", median(v.renderMs)},
                            {"present_ms_median", median(v.presentMs)},
                            {"rendered_iteration_ms_median", median(v.renderedLoopMs)},
                            {"size", {m.rendered.width, m.rendered.height}}};
  logLine(v.eventLog, summary);
  std::fprintf(stderr,
               "gblens view: %llu frames rendered (median %.2f ms), %llu presented (median %.2f ms); "
               "render + present %.2f ms\n",
               (unsigned long long)m.framesRendered, median(v.renderMs), (unsigned long long)m.framesPresented,
               median(v.presentMs), median(v.renderedLoopMs));
  vkDeviceWaitIdle(v.ctx.device);
  shutdownImGui(v);
  destroyViewMapper(v.mapper, v.renderer);
  destroyRenderer(v.renderer);
  destroyRenderer(v.rendererB);
  closeWindow(v);
  int messages = reportValidation(v.ctx);
  destroyContext(v.ctx);
  return messages ? 1 : 0;
}

}  // namespace gb
