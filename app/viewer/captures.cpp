// Captures in the viewer: the capture button (the live frame, whole, through the capture
// writer), and --capture A [--compare B]: captured targets uploaded so every view works on
// them, the probe run on the captures' own snapshots, and A vs B with `gblens compare`'s report.
#include <chrono>
#include <cmath>
#include <cstdio>
#include <ctime>
#include <sstream>

#include "app/viewer/viewer.h"
#include "renderer/render_targets.h"
#include "renderer/session.h"
#include "renderer/upload_targets.h"
#include "renderer/vk/renderdoc_capture.h"
#include "views/analysis/compare.h"
#include "views/analysis/probe.h"
#include "views/analysis/viewable.h"
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

static std::string describe(const Capture& c) {
  const nlohmann::json& m = c.manifest;
  std::ostringstream o;
  const RenderOptions& opt = c.frame.options;
  if (!nativeFrame(c.frame)) {
    // An imported G-buffer: its own layout; the views show its quantities decoded.
    o << c.dir << "\n  layout " << c.frame.layout.name << ", " << opt.width << "x" << opt.height
      << " (imported: the views show its quantities decoded)\n  targets:";
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

static void upload(Renderer& r, GpuContext& ctx, Scene& scene, const FrameSnapshot& shown) {
  scene = emptyScene(shown.camera);
  initRenderer(r, ctx, scene);
  std::array<const CpuImage*, kTargetCount> images{};
  for (const TargetInfo& t : targetTable())
    if (shown.target(t.target).present()) images[size_t(t.target)] = &shown.target(t.target).image;
  uploadTargets(r, shown.options, images);
  r.camera = shown.camera;
}

bool openCaptures(Viewer& v) {
  ViewerModel& m = v.model;
  std::string error;
  if (!loadCapture(v.args.capture, v.captureA, error)) {
    std::fprintf(stderr, "gblens view: --capture %s\n", error.c_str());
    return false;
  }
  v.shownA = viewableFrame(v.captureA.frame);
  upload(v.renderer, v.ctx, v.scene, v.shownA);
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
    v.shownB = viewableFrame(v.captureB.frame);
    upload(v.rendererB, v.ctx, v.sceneB, v.shownB);
    v.hasB = true;
    m.source = FrameSource::Compare;
    m.captureB = v.args.compare;
    m.captureInfo = "A: " + describe(v.captureA) + "\nB: " + describe(v.captureB);
    CompareReport report;
    if (compareCaptures(v.captureA, v.captureB, ThresholdSettings{}, report, error))
      m.compareSummary = report.text();
    else
      m.compareSummary = error;
    // The white point of each |A - B| view: the largest difference over its channels.
    for (int k = 0; k < kViewKindCount; ++k) {
      const ViewDef& d = viewDef(ViewKind(k));
      const TargetImage &ta = v.shownA.target(d.source.target), &tb = v.shownB.target(d.source.target);
      double worst = 0.0;
      if (ta.present() && tb.present() && ta.image.width == tb.image.width && ta.image.height == tb.image.height) {
        uint32_t mask = d.source.stencil ? 0x2u : d.channels;
        for (uint32_t y = 0; y < ta.image.height; ++y)
          for (uint32_t x = 0; x < ta.image.width; ++x)
            for (uint32_t c = 0; c < ta.image.channelCount(); ++c)
              if (mask & (1u << c)) {
                double e = std::abs(ta.image.value(x, y, c) - tb.image.value(x, y, c));
                if (std::isfinite(e)) worst = std::max(worst, e);
              }
      }
      m.differenceMax[k] = worst;
    }
  }
  // What the views can show.
  const FrameSnapshot& f = v.shownA;
  m.rendered = f.options;
  const TargetImage& sm = f.target(Target::ShadowMap);
  m.shadowMapSize = sm.present() ? glm::uvec2(sm.image.width, sm.image.height) : glm::uvec2(1, 1);
  for (int k = 0; k < kViewKindCount; ++k) {
    Target t = viewDef(ViewKind(k)).source.target;
    m.unavailable[k].clear();
    if (!f.target(t).present()) m.unavailable[k] = std::string(targetName(t)) + ": " + absentText(f.absence(t));
    else if (v.hasB && !v.shownB.target(t).present())
      m.unavailable[k] = std::string(targetName(t)) + " is not in B: " + absentText(v.shownB.absence(t));
  }
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

std::string captureHoverText(const Viewer& v, ViewKind view, glm::ivec2 texel) {
  const ViewDef& d = viewDef(view);
  std::string out;
  for (const FrameSnapshot* c : {&v.shownA, v.hasB ? &v.shownB : nullptr}) {
    if (!c) continue;
    const TargetImage& ti = c->target(d.source.target);
    if (!ti.contains(uint32_t(texel.x), uint32_t(texel.y))) continue;
    char buf[96];
    std::snprintf(buf, sizeof buf, "%s%s (%d, %d):", out.empty() ? "" : " | ", v.hasB ? (c == &v.shownA ? "A" : "B") : targetName(d.source.target),
                  texel.x, texel.y);
    out += buf;
    for (uint32_t ch = 0; ch < ti.image.channelCount(); ++ch) {
      std::snprintf(buf, sizeof buf, " %s %.7g", ti.image.channels[ch].c_str(), ti.value(uint32_t(texel.x), uint32_t(texel.y), ch));
      out += buf;
    }
  }
  return out;
}

}  // namespace gb
