// Captures in the viewer: the capture button (the live frame, whole, through the capture
// writer), and --capture A [--compare B]: each view of the capture's layout decoded and uploaded,
// the probe run on the captures' own snapshots, and A vs B with `gblens compare`'s report.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "app/viewer/viewer.h"
#include "renderer/core/decode.h"
#include "renderer/core/layout_json.h"
#include "renderer/render_targets.h"
#include "renderer/session.h"
#include "renderer/vk/renderdoc_capture.h"
#include "views/analysis/compare.h"
#include "views/analysis/probe.h"
#include "views/analysis/view_text.h"
#include "views/analysis/visualize.h"
#include "views/capture/capture.h"

namespace gb {

bool captureLiveFrame(Viewer& v, std::string& written, std::string& error, std::string* rdc) {
  Renderer& r = v.renderer;
  std::vector<Target> targets = readableTargets(r, r.options);
  FrameRequest request;
  request.readback = targets;
  request.sampleAfter = targets;
  request.cullingStats = r.options.coverage;
  char stamp[32];
  std::time_t now = std::time(nullptr);
  std::strftime(stamp, sizeof stamp, "%Y%m%d-%H%M%S", std::localtime(&now));
  written = std::string("gblens-capture-") + stamp;
  // "Capture in RenderDoc": the same frame in RenderDoc too, its .rdc beside the capture folder
  // (RenderDoc appends "_frameN.rdc" to the template).
  if (rdc) setRenderDocCaptureTemplate(written);
  RenderDocCapture renderDoc(v.ctx, rdc != nullptr);
  const FrameStats& stats = renderFrame(r, r.options, request);  // the same frame again (deterministic), whole
  if (rdc) {
    *rdc = renderDoc.end(&error);
    if (rdc->empty()) return false;
  }
  FrameSnapshot snapshot = snapshotFromRenderer(r, targets);
  CaptureMeta meta;
  meta.device = v.ctx.deviceName;
  meta.driver = v.ctx.driverName;
  meta.scene = v.args.scene;
  meta.sceneSha256 = sceneContentSha256(v.scene);
  meta.stats = stats;
  meta.commandLine = v.args.commandLine + " (capture button)";
  return writeCapture(written, snapshot, meta, error);
}

static bool nativeFrame(const FrameSnapshot& f) { return f.layout.name == nativeLayout(f.options).name; }

static std::string describe(const Capture& c) {
  const nlohmann::json& m = c.manifest;
  std::ostringstream o;
  const RenderOptions& opt = c.frame.options;
  if (!nativeFrame(c.frame)) {
    // An imported G-buffer: its own layout; the views are its quantities.
    o << c.dir << "\n  layout " << c.frame.layout.name << ", " << opt.width << "x" << opt.height << " (imported)\n  targets:";
    for (size_t i = 0; i < c.frame.images.size(); ++i)
      if (c.frame.images[i].present()) o << " " << c.frame.layout.targets[i].name;
    return o.str();
  }
  o << c.dir << "\n  " << m.value("scene", nlohmann::json("?")).dump() << ", " << opt.width << "x" << opt.height << ", time "
    << opt.time << "\n  " << name(opt.path) << ", eye depth " << (opt.eyeDepth ? "on" : "off") << ", stencil culling "
    << (opt.stencilCulling ? "on" : "off") << "\n  device " << m.value("device", nlohmann::json("?")).dump() << "\n  targets:";
  for (size_t i = 0; i < c.frame.images.size(); ++i)
    if (c.frame.images[i].present()) o << " " << c.frame.layout.targets[i].name;
  return o.str();
}

Scene emptyScene(const Camera& camera) {
  Scene s;
  s.source = "capture";
  s.materials.push_back(MaterialDesc{});
  CameraDesc cam;
  cam.worldFromEye = camera.worldFromEye;
  s.cameras.push_back(cam);
  return s;
}

// Each view of `views` decoded from `f` (an empty image where f does not hold its target).
static std::vector<CpuImage> decodeViews(const FrameSnapshot& f, const std::vector<ViewDef>& views) {
  std::vector<CpuImage> out;
  for (const ViewDef& d : views) out.push_back(d.quantity >= 0 ? viewImage(f, d) : CpuImage{});
  return out;
}

// The largest |A - B| over a view's components, where both hold a value.
static double largestDifference(const CpuImage& a, const CpuImage& b, uint32_t components) {
  double worst = 0.0;
  if (a.empty() || b.empty() || a.width != b.width || a.height != b.height) return worst;
  for (uint32_t y = 0; y < a.height; ++y)
    for (uint32_t x = 0; x < a.width; ++x)
      for (uint32_t c = 0; c < components && c < a.channelCount(); ++c) {
        double e = std::abs(a.value(x, y, c) - b.value(x, y, c));
        if (std::isfinite(e)) worst = std::max(worst, e);
      }
  return worst;
}

// What the views can show: A's layout's views, B's of the same names beside them.
static void setCaptureViews(Viewer& v) {
  ViewerModel& m = v.model;
  const FrameSnapshot& a = v.captureA.frame;
  m.frameLayout = a.layout;
  setViews(m, layoutViews(a.layout));
  v.decodedA = decodeViews(a, m.views);
  v.viewsB.clear();
  if (v.hasB) {
    const std::vector<ViewDef> all = layoutViews(v.captureB.frame.layout);
    for (const ViewDef& d : m.views) {
      int i = findView(all, d.name);
      v.viewsB.push_back(i >= 0 && all[size_t(i)].visual == d.visual ? all[size_t(i)] : ViewDef{});
    }
    v.decodedB = decodeViews(v.captureB.frame, v.viewsB);
  }
  for (size_t k = 0; k < m.views.size(); ++k) {
    const ViewDef& d = m.views[k];
    m.unavailable[k].clear();
    Absent why = a.absences[d.target];
    if (v.decodedA[k].empty()) m.unavailable[k] = a.layout.targets[d.target].name + ": " + absentText(why == Absent::No ? Absent::NotCaptured : why);
    else if (v.hasB && v.decodedB[k].empty()) m.unavailable[k] = d.name + " is not in B";
    if (v.hasB) m.differenceMax[k] = largestDifference(v.decodedA[k], v.decodedB[k], d.components);
  }
  uploadViewImages(v.imagesA, v.ctx, v.decodedA);
  if (v.hasB) uploadViewImages(v.imagesB, v.ctx, v.decodedB);
  v.rangeKeys.assign(m.views.size(), "");
  const TargetImage* sm = nullptr;
  for (const ViewDef& d : m.views)
    if (d.sun) sm = layoutImage(a, d.target);
  m.shadowMapSize = sm && sm->present() ? glm::uvec2(sm->image.width, sm->image.height) : glm::uvec2(1, 1);
}

void updateCaptureRanges(Viewer& v) {
  ViewerModel& m = v.model;
  for (int k : visibleViews(m)) {
    const ViewDef& d = m.views[size_t(k)];
    const ViewSettings& s = m.settings[size_t(k)];
    const ViewMapping mapping = viewMapping(d, s);
    const std::string key = std::to_string(mapping.mask) + (s.autoRange ? "a" : "m");
    if (v.rangeKeys[size_t(k)] == key || v.decodedA[size_t(k)].empty()) continue;
    v.rangeKeys[size_t(k)] = key;
    m.ranges[size_t(k)] = {imageRange(v.decodedA[size_t(k)], d, mapping.mask)};
    m.uiChanged = true;
  }
}

bool openCaptures(Viewer& v) {
  ViewerModel& m = v.model;
  std::string error;
  if (!loadCapture(v.args.capture, v.captureA, error)) {
    std::fprintf(stderr, "gblens view: --capture %s\n", error.c_str());
    return false;
  }
  m.source = FrameSource::Capture;
  m.captureA = v.args.capture;
  m.captureInfo = describe(v.captureA);
  if (!v.args.compare.empty()) {
    if (!loadCapture(v.args.compare, v.captureB, error)) {
      std::fprintf(stderr, "gblens view: --compare %s\n", error.c_str());
      return false;
    }
    const RenderOptions &a = v.captureA.frame.options, &b = v.captureB.frame.options;
    if (a.width != b.width || a.height != b.height) {
      std::fprintf(stderr, "gblens view: --compare: %s is %ux%u, %s is %ux%u (captures of one size only)\n",
                   v.args.capture.c_str(), a.width, a.height, v.args.compare.c_str(), b.width, b.height);
      return false;
    }
    v.hasB = true;
    m.source = FrameSource::Compare;
    m.captureB = v.args.compare;
    m.captureInfo = "A: " + describe(v.captureA) + "\nB: " + describe(v.captureB);
    CompareReport report;
    if (compareCaptures(v.captureA, v.captureB, ThresholdSettings{}, report, error))
      m.compareSummary = report.text();
    else
      m.compareSummary = error;
  }
  // A renderer that holds no frame: the view pipelines' context (sampler, scene set).
  v.scene = emptyScene(v.captureA.frame.camera);
  initRenderer(v.renderer, v.ctx, v.scene);
  v.renderer.camera = v.captureA.frame.camera;
  m.rendered = v.captureA.frame.options;
  setCaptureViews(v);
  m.captureAvailable = false;
  m.captureHint = "This is a capture already";
  v.frameValid = true;
  return true;
}

void probeCapturePixel(Viewer& v, glm::ivec2 p) {
  auto start = v.clickPending ? v.clickTime : std::chrono::steady_clock::now();
  v.clickPending = false;
  v.probeStart = start;
  ViewerModel& m = v.model;
  const FrameSnapshot& a = v.captureA.frame;
  p = glm::clamp(p, glm::ivec2(0), glm::ivec2(int(a.options.width) - 1, int(a.options.height) - 1));
  PixelDossier d = probePixel(a, uint32_t(p.x), uint32_t(p.y));
  m.probePixel = p;
  m.probeError = d.error;
  m.dossier = d;
  m.dossierJson = dossierJson(d);
  m.reference.reset();
  m.referenceNote = "captures: gblens probe CAPTURE X Y --reference (the viewer's reference follows live frames)";
  m.dossierB.reset();
  if (v.hasB) {
    PixelDossier b = probePixel(v.captureB.frame, uint32_t(p.x), uint32_t(p.y));
    m.dossierB = b;
    m.dossierJson = {{"a", m.dossierJson}, {"b", dossierJson(b)}};
  }
  m.shadowTexelOfProbe.reset();
  if (d.shadowMap.valid)
    m.shadowTexelOfProbe = glm::ivec2(int(std::floor(d.shadowMap.texel.x + 0.5)), int(std::floor(d.shadowMap.texel.y + 0.5)));
  double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  m.probeLatencyMs = ms;
  logLine(v.probeLog, m.dossierJson);
  logLine(v.eventLog, {{"event", "probe"}, {"pixel", {p.x, p.y}}, {"latency_ms", ms}});
}

std::string captureHoverText(const Viewer& v, int view, glm::ivec2 texel) {
  const ViewerModel& m = v.model;
  if (view < 0 || size_t(view) >= m.views.size()) return "";
  std::string a = viewValueText(v.captureA.frame, m.views[size_t(view)], uint32_t(texel.x), uint32_t(texel.y));
  if (!v.hasB) return a;
  const ViewDef& b = v.viewsB[size_t(view)];
  return "A: " + a + (b.quantity >= 0 ? "\nB: " + viewValueText(v.captureB.frame, b, uint32_t(texel.x), uint32_t(texel.y)) : "");
}

}  // namespace gb
