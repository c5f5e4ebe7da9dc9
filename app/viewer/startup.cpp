// The viewer's start and end (viewer.cpp runs the loop in between): the arguments and logs
// checked, the window's Vulkan context and callbacks, the frame source (the live renderer, or
// --capture / --compare), the model's first state; at the end the exit summary and the teardown.
#define GLFW_INCLUDE_VULKAN
#include <GLFW/glfw3.h>

#include <algorithm>
#include <cstdio>
#include <tuple>

#include "app/viewer/viewer.h"
#include "renderer/core/statistics.h"
#include "renderer/vk/check.h"
#include "renderer/vk/renderdoc_capture.h"

namespace gb {

// --window WxH and --compare without --capture; a message and false on a mistake.
static bool checkArgs(const ViewerArgs& args, unsigned& width, unsigned& height) {
  char sep = 0;
  if (std::sscanf(args.window.c_str(), "%u%c%u", &width, &sep, &height) != 3 || width < 64 || height < 64) {
    std::fprintf(stderr, "gblens view: --window %s: expected WxH, at least 64x64\n", args.window.c_str());
    return false;
  }
  if (!args.compare.empty() && args.capture.empty()) {
    std::fprintf(stderr, "gblens view: --compare B needs --capture A\n");
    return false;
  }
  return true;
}

// --probe-log and --event-log, opened for appending; a message and false when one cannot be.
static bool openLogs(Viewer& v) {
  for (auto [flag, path, file] : {std::tuple{"--probe-log", &v.args.probeLog, &v.probeLog},
                                  std::tuple{"--event-log", &v.args.eventLog, &v.eventLog}}) {
    if (path->empty()) continue;
    file->open(*path, std::ios::app);
    if (!*file) {
      std::fprintf(stderr, "gblens view: %s %s: cannot open for writing\n", flag, path->c_str());
      return false;
    }
  }
  return true;
}

// The viewer's own Vulkan context (with the window's instance extensions and a swapchain), the
// window's surface and swapchain, the input callbacks and Dear ImGui.
static void openContext(Viewer& v) {
  ContextOptions co;
  co.validation = v.args.validate;
  co.device = v.args.device;
  co.swapchain = true;
  uint32_t n = 0;
  const char** exts = glfwGetRequiredInstanceExtensions(&n);
  for (uint32_t i = 0; i < n; ++i) co.instanceExtensions.push_back(exts[i]);
  v.ctx = createContext(co);
  VK_CHECK(glfwCreateWindowSurface(v.ctx.instance, v.window, nullptr, &v.swapchain.surface));
  installInputCallbacks(v);
  while (!recreateSwapchain(v)) glfwWaitEvents();  // a window may open minimised
  initImGui(v);
}

// The live renderer on the scene (from a copy of the chosen scene camera), or the captures; and
// the GPU view mapping. False (a message was printed, everything torn down) when a capture fails.
static bool openFrameSource(Viewer& v, bool live) {
  if (live) {
    // The scene camera the viewer starts from, copied to a camera of its own (the last one).
    resetRig(v.rig, v.scene.cameras[size_t(v.args.render.camera)], v.scene.bounds);
    v.scene.cameras.push_back(v.rig.desc);
    initRenderer(v.renderer, v.ctx, v.scene);
  } else if (v.args.attach) {
    openAttached(v);  // gblens attach: the stream's frames, shown as captures are
  } else if (!openCaptures(v)) {
    shutdownImGui(v);
    destroyRenderer(v.renderer);
    closeWindow(v);
    destroyContext(v.ctx);
    return false;
  }
  initViewMapper(v.mapper, v.renderer);
  return true;
}

// The model's first state: view settings, the options and view as given, names for the panels.
static void initModel(Viewer& v, bool live) {
  ViewerModel& m = v.model;
  const ViewerArgs& args = v.args;
  m.wanted = args.render;
  // A fixed render size (--size, else the options' default), letterboxed in each view: pixel coordinates in
  // the viewer are those of `gblens render` / `capture` at that size. Following the view area is a choice.
  m.fixedSize = true;
  m.lightCount = int(v.scene.generatedLights ? args.render.lights : int(v.scene.lights.size()));
  m.playing = !args.paused;
  m.probeReference = args.probeReference;
  m.reduceWhileMoving = args.reduceWhileMoving;
  m.deviceName = v.ctx.deviceName;
  m.sceneName = live || args.attach ? args.scene : args.capture + (args.compare.empty() ? "" : " vs " + args.compare);
  if (m.timeline.on) m.sceneName = "sequence " + m.timeline.dir;  // the frame shown ends the status line
  if (live) {
    m.rendered = m.wanted;  // until the first frame: the views of the layout it will have
    updateLiveViews(v);
    for (size_t i = 0; i + 1 < v.scene.cameras.size(); ++i)
      m.cameraNames.push_back(v.scene.cameras[i].name.empty() ? "camera " + std::to_string(i) : v.scene.cameras[i].name);
    installLiveTexelValues(v);
    m.captureAvailable = true;
    m.renderDocAvailable = underRenderDoc();
    m.captureHint = "Writes this frame, every target at full precision, to ./gblens-capture-<date>-<time>/\n"
                    "(EXR per target + manifest.json; open it with gblens view --capture DIR)";
  }
}

bool startViewer(Viewer& v) {
  unsigned width = 0, height = 0;
  if (!checkArgs(v.args, width, height) || !openLogs(v) || !openWindow(v, width, height)) return false;
  openContext(v);
  const bool live = v.args.capture.empty() && !v.args.attach;
  if (!openFrameSource(v, live)) return false;
  initModel(v, live);
  // The first view: --view (a view of this frame's layout), else the layout's first colour view.
  ViewerModel& m = v.model;
  if (!v.args.initialView.empty()) {
    const int k = findView(m.views, v.args.initialView);
    if (k < 0) {
      std::fprintf(stderr, "gblens view: --view %s: not a view of this frame (its views: %s)\n", v.args.initialView.c_str(),
                   viewNameList(m.views).c_str());
      finishViewer(v);
      return false;
    }
    m.primary = m.edited = k;
    m.layout = LayoutMode::Single;
  }
  return true;
}

int finishViewer(Viewer& v) {
  const ViewerModel& m = v.model;
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
  destroyViewImages(v.imagesA, v.ctx);
  destroyViewImages(v.imagesB, v.ctx);
  destroyViewDecoder(v.decoder, v.ctx);
  stopCompareFlip(v);
  stopReferenceError(v);
  stopTemporalViews(v);
  destroyRenderer(v.renderer);
  closeWindow(v);
  int messages = reportValidation(v.ctx);
  destroyContext(v.ctx);
  return messages ? 1 : 0;
}

}  // namespace gb
