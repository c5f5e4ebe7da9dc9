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
#include "renderer/frame/session.h"
#include "renderer/gpu/render_targets.h"
#include "renderer/vk/renderdoc_capture.h"
#include "views/analysis/compare.h"
#include "views/analysis/probe.h"
#include "views/analysis/sample_views.h"
#include "views/analysis/view_text.h"
#include "views/analysis/visualize.h"
#include "views/capture/capture.h"

namespace gb {

bool captureLiveFrame(Viewer& v, std::string& written, std::string& error, std::string* rdc) {
  if (v.args.attach) return captureAttachedFrame(v, written, error);  // the streamed frame shown
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

std::string describeCapture(const Capture& c) {
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
  const nlohmann::json scene = m.value("scene", nlohmann::json("?"));
  o << c.dir << "\n  " << (scene.is_object() ? scene.value("source", scene.dump()) : scene.dump()) << ", " << opt.width << "x" << opt.height << ", time "
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

// ---- FLIP of the colour views (A the reference, B the test) ------------------------------------

// A decoded colour view as FLIP's input: linear RGB, empty texels and non-finite values 0.
static FlipImage flipInput(const CpuImage& decoded) {
  FlipImage out;
  out.width = decoded.width, out.height = decoded.height;
  out.rgb.resize(size_t(out.width) * out.height * 3);
  for (uint32_t y = 0; y < out.height; ++y)
    for (uint32_t x = 0; x < out.width; ++x)
      for (uint32_t c = 0; c < 3; ++c) {
        const bool empty = decoded.raw(x, y, 0) == gpu::kEmptyTexel;
        const double v = empty ? 0.0 : decoded.value(x, y, c);
        out.rgb[(size_t(y) * out.width + x) * 3 + c] = std::isfinite(v) ? float(v) : 0.0f;
      }
  return out;
}

// A FLIP map in magma (flip.h magmaColor, as the FLIP tool draws it) as a decoded colour image.
static CpuImage flipImage(const std::vector<float>& errors, uint32_t width, uint32_t height) {
  CpuImage img = decodedViewImage("flip", width, height);
  float* out = reinterpret_cast<float*>(img.data.data());
  for (size_t i = 0; i < errors.size(); ++i) {
    uint8_t c[3];
    magmaColor(std::clamp(double(errors[i]), 0.0, 1.0), c);
    for (int k = 0; k < 3; ++k) out[i * 4 + k] = float(srgbToLinear(c[k] / 255.0));
    out[i * 4 + 3] = 1.0f;
  }
  return img;
}

// Starts the worker: LDR-FLIP of each colour view (HDR-FLIP of radiance) that A and B both hold,
// as `gblens compare` computes FLIP of final and hdr, at FLIP's default observer.
static void startFlip(Viewer& v) {
  ViewerModel& m = v.model;
  struct Input {
    size_t view;
    bool hdr;
    FlipImage a, b;
  };
  std::vector<Input> inputs;
  for (size_t k = 0; k < m.views.size(); ++k)
    if (m.views[k].visual == Visual::Color && m.unavailable[k].empty())
      inputs.push_back({k, m.views[k].hdr, flipInput(v.decodedA[k]), flipInput(v.decodedB[k])});
  auto progress = std::make_shared<WorkProgress>();
  progress->total = inputs.size();
  v.flipProgress = progress;
  m.flipStatus = "computing FLIP: 0 of " + std::to_string(inputs.size()) + " colour views";
  v.flipJob = std::async(std::launch::async, [inputs = std::move(inputs), n = m.views.size(), progress]() {
    Viewer::FlipMaps out;
    out.errors.resize(n);
    out.images.resize(n);
    out.pools.resize(n);
    for (const Input& in : inputs) {
      if (progress->cancelled()) break;
      const double ppd = flipDefaultPpd();
      std::vector<float> e = in.hdr ? hdrFlip(in.a, in.b, ppd, hdrFlipExposures(in.a)) : ldrFlip(in.a, in.b, ppd);
      out.images[in.view] = flipImage(e, in.a.width, in.a.height);
      out.pools[in.view] = poolFlip(e);
      out.errors[in.view] = std::move(e);
      progress->done++;
    }
    return out;
  });
}

bool updateCompareFlip(Viewer& v) {
  if (!v.flipJob.valid()) return false;
  ViewerModel& m = v.model;
  const WorkProgress& p = *v.flipProgress;
  if (v.flipJob.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    const std::string status = "computing FLIP: " + std::to_string(p.done.load()) + " of " + std::to_string(p.total.load()) +
                               " colour views";
    if (status != m.flipStatus) m.flipStatus = status, m.uiChanged = true;
    return true;
  }
  Viewer::FlipMaps maps = v.flipJob.get();
  v.flipErrors = std::move(maps.errors);
  uploadViewImages(v.imagesFlip, v.ctx, maps.images);
  m.flipPools = maps.pools;
  m.flipStatus.clear();
  m.uiChanged = true;
  nlohmann::json means = nlohmann::json::object();
  for (size_t k = 0; k < m.views.size(); ++k)
    if (m.flipPools[k]) means[m.views[k].name] = m.flipPools[k]->mean;
  logLine(v.eventLog, {{"event", "flip"}, {"mean", means}});
  return false;
}

void stopCompareFlip(Viewer& v) {
  if (v.flipProgress) v.flipProgress->cancel = true;
  if (v.flipJob.valid()) v.flipJob.wait();
  destroyViewImages(v.imagesFlip, v.ctx);
}

// What the views can show: A's layout's views, B's of the same names beside them.
std::vector<ViewDef> frameViews(const FrameSnapshot& f) {
  std::vector<ViewDef> views = layoutViews(f.layout);
  for (ViewDef& d : spreadViews(f)) views.push_back(std::move(d));
  return views;
}

// What the capture panel says of a multisampled frame: the sample shown and how to change it.
std::string samplesNote(const FrameSnapshot& f) {
  const size_t n = frameSamples(f);
  if (n < 2) return "";
  return "multisampled: showing sample " + std::to_string(f.sampleShown) + " of " + std::to_string(n) +
         " (X: the next); the spread views show where samples differ";
}

void showNextSample(Viewer& v) {
  FrameSnapshot& f = v.captureA.frame;
  const size_t n = frameSamples(f);
  if (n < 2) return;
  v.model.sampleShown = (f.sampleShown + 1) % uint32_t(n);
  showSample(f, v.model.sampleShown);
  setCaptureViews(v);
  if (v.model.probePixel && v.model.dossier) {
    v.model.dossier = probePixel(f, uint32_t(v.model.probePixel->x), uint32_t(v.model.probePixel->y));
    v.model.dossierJson = dossierJson(*v.model.dossier);
  }
  v.model.regionDirty = v.model.region.has_value();
}

void setCaptureViews(Viewer& v, bool decode) {
  ViewerModel& m = v.model;
  const FrameSnapshot& a = v.captureA.frame;
  m.frameLayout = a.layout;
  m.samplesNote = samplesNote(a);
  std::vector<ViewDef> views = frameViews(a);
  appendTemporalViews(v, views);  // a sequence: the motion check's and flicker's maps (temporal_views.cpp)
  setViews(m, std::move(views));
  v.decodedA = decode ? decodeViews(a, m.views) : std::vector<CpuImage>(m.views.size());
  v.gpuRanges.assign(m.views.size(), {});
  v.gpuDecoded.assign(m.views.size(), false);
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
    if (d.quantity < 0) continue;  // a temporal view: fillTemporalViews
    Absent why = a.absences[d.target];
    if (decode ? v.decodedA[k].empty() : !a.images[d.target].present()) m.unavailable[k] = a.layout.targets[d.target].name + ": " + absentText(why == Absent::No ? Absent::NotCaptured : why);
    else if (v.hasB && v.decodedB[k].empty()) m.unavailable[k] = d.name + " is not in B";
    if (v.hasB) m.differenceMax[k] = largestDifference(v.decodedA[k], v.decodedB[k], d.components);
  }
  v.rangeKeys.assign(m.views.size(), "");
  fillTemporalViews(v);
  uploadViewImages(v.imagesA, v.ctx, v.decodedA);
  if (v.hasB) uploadViewImages(v.imagesB, v.ctx, v.decodedB);
  if (v.hasB) startFlip(v);
  const TargetImage* sm = nullptr;
  for (const ViewDef& d : m.views)
    if (d.sun) sm = layoutImage(a, d.target);
  m.shadowMapSize = sm && sm->present() ? glm::uvec2(sm->image.width, sm->image.height) : glm::uvec2(1, 1);
  // Values in texels at high zoom: both captures are on the CPU, decoded as hover decodes them.
  m.texelValue = [&v](int view, FrameSide side, glm::ivec2 t) -> std::optional<TexelValue> {
    const bool b = side == FrameSide::B;
    if ((b && !v.hasB) || view < 0 || size_t(view) >= v.model.views.size()) return std::nullopt;
    const ViewDef& d = b ? v.viewsB[size_t(view)] : v.model.views[size_t(view)];
    const FrameSnapshot& f = b ? v.captureB.frame : v.captureA.frame;
    if (d.quantity < 0) return b ? std::nullopt : temporalTexelValue(v, view, t);  // a derived map
    TexelValue out;
    const std::optional<std::array<double, 4>> value = viewValue(f, d, uint32_t(t.x), uint32_t(t.y));
    out.lines = texelValueLines(f, d, value, v.model.settings[size_t(view)].channels);
    if (value) {
      for (int c = 0; c < 4; ++c) out.value[size_t(c)] = float((*value)[size_t(c)]);
      out.empty = false;
    }
    return out;
  };
}

void updateCaptureRanges(Viewer& v) {
  ViewerModel& m = v.model;
  for (int k : visibleViews(m)) {
    const ViewDef& d = m.views[size_t(k)];
    const ViewSettings& s = m.settings[size_t(k)];
    const ViewMapping mapping = viewMapping(d, s);
    const std::string key = std::to_string(mapping.mask) + (s.autoRange ? "a" : "m");
    // A stream's view decoded on the GPU has its statistics when its range was automatic then; one
    // made automatic since is decoded again (decodeShown, on the next poll).
    const bool onGpu = size_t(k) < v.gpuDecoded.size() && v.gpuDecoded[size_t(k)];
    if (onGpu && s.autoRange && v.gpuRanges[size_t(k)].empty()) {
      v.attachShown.clear();
      continue;
    }
    if (v.rangeKeys[size_t(k)] == key || (v.decodedA[size_t(k)].empty() && !onGpu)) continue;
    v.rangeKeys[size_t(k)] = key;
    m.ranges[size_t(k)] = onGpu ? selectRanges(v.gpuRanges[size_t(k)], d, mapping.mask)
                                : std::vector<RangeStats>{imageRange(v.decodedA[size_t(k)], d, mapping.mask)};
    m.uiChanged = true;
  }
}

bool openCaptures(Viewer& v) {
  ViewerModel& m = v.model;
  std::string error;
  // A sequence (SEQ, SEQ@N; not beside --compare): its frame shown, the timeline over the rest (sequence.cpp).
  const bool sequence = v.args.compare.empty() && sequenceArgument(v.args.capture);
  if (sequence ? !openSequence(v, error) : !loadCapture(v.args.capture, v.captureA, error)) {
    std::fprintf(stderr, "gblens view: %s%s\n", sequence ? "" : "--capture ", error.c_str());
    return false;
  }
  m.source = FrameSource::Capture;
  m.captureA = v.args.capture;
  m.captureInfo = describeCapture(v.captureA);
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
    m.captureInfo = "A: " + describeCapture(v.captureA) + "\nB: " + describeCapture(v.captureB);
    auto report = std::make_shared<CompareReport>();
    if (compareCaptures(v.captureA, v.captureB, ThresholdSettings{}, *report, error)) {
      m.compareSummary = report->text();
      for (GroupResult& g : report->groups) std::vector<float>().swap(g.errors);  // the tables show figures only
      m.compareReport = report;
    } else {
      m.compareSummary = error;
    }
  }
  // A renderer that holds no frame: the view pipelines' context (sampler, scene set).
  v.scene = emptyScene(v.captureA.frame.camera);
  initRenderer(v.renderer, v.ctx, v.scene);
  v.renderer.camera = v.renderer.unjitteredCamera = v.captureA.frame.camera;
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
  if (m.views[size_t(view)].quantity < 0) return temporalHoverText(v, view, texel);  // a derived map
  std::string a = viewValueText(v.captureA.frame, m.views[size_t(view)], uint32_t(texel.x), uint32_t(texel.y));
  if (!v.hasB) return a;
  const ViewDef& b = v.viewsB[size_t(view)];
  std::string text =
      "A: " + a + (b.quantity >= 0 ? "\nB: " + viewValueText(v.captureB.frame, b, uint32_t(texel.x), uint32_t(texel.y)) : "");
  // |A - B| of the decoded components, as the |A-B| view maps it (each side decoded by its layout).
  const std::optional<std::array<double, 4>> va = viewValue(v.captureA.frame, m.views[size_t(view)], uint32_t(texel.x), uint32_t(texel.y));
  const std::optional<std::array<double, 4>> vb =
      b.quantity >= 0 ? viewValue(v.captureB.frame, b, uint32_t(texel.x), uint32_t(texel.y)) : std::nullopt;
  if (va && vb) {
    const ViewDef& d = m.views[size_t(view)];
    text += "\n|A-B|";
    char part[64];
    for (uint32_t c = 0; c < std::min(d.components, 4u); ++c) {
      std::snprintf(part, sizeof part, " %s%.7g", d.components > 1 && c < d.componentNames.size() ? (d.componentNames[c] + " ").c_str() : "",
                    std::abs((*va)[c] - (*vb)[c]));
      text += part;
    }
  } else if (va.has_value() != vb.has_value()) {
    text += std::string("\n|A-B| a value in ") + (va ? "A" : "B") + " only";
  }
  if (size_t(view) < v.flipErrors.size() && !v.flipErrors[size_t(view)].empty()) {
    const std::vector<float>& e = v.flipErrors[size_t(view)];
    const size_t i = size_t(texel.y) * v.decodedA[size_t(view)].width + size_t(texel.x);
    char flip[48];
    std::snprintf(flip, sizeof flip, "\nFLIP %.4f", i < e.size() ? double(e[i]) : 0.0);
    text += flip;
  }
  return text;
}

}  // namespace gb
