// The reference error, live: the frame on screen rendered once more as `gblens error` renders it
// (views/analysis/accuracy.h measuredSnapshot), then the reference, the error and the lighting
// decomposition computed in a worker thread from copies (the scene, the snapshot), so the viewer
// keeps answering. The worker counts rows into a WorkProgress (renderer/core/progress.h): the panel
// shows the percentage, and a cancel stops it between rows. The maps become views of the live frame
// (quantity -1: not the layout's), appended to its views: decoded images drawn, hovered and probed
// like a capture's.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "app/viewer/viewer.h"
#include "renderer/frame/session.h"
#include "views/analysis/accuracy.h"
#include "views/analysis/visualize.h"
#include "views/capture/exr.h"
#include "views/capture/image_io.h"

namespace gb {

namespace fs = std::filesystem;

// Rows the worker counts: the reference's surfaces, its penumbra band and its shading
// (ReferenceCache::get), the G-buffer's lighting shaded again (measureError), then the
// decomposition, whose rows count kDecomposeWeight each: it shades every light in view four times a
// pixel (all, diffuse, specular, white albedo) where the shading passes shade the lights near it
// once. Measured on builtin:temple at 480x480 with 256 lights: the four passes 3.1 s, the
// decomposition 12.4 s, so that the percentage shown follows the time.
constexpr uint64_t kRowPasses = 4, kDecomposeWeight = 16;

static void start(Viewer& v) {
  ViewerModel& m = v.model;
  auto& e = m.referenceError;
  e.error.clear();
  const RenderOptions o = v.fullOptions;
  auto render = [&v](const RenderOptions& ro, const std::vector<Target>& t) { return renderSnapshot(v.renderer, ro, t); };
  FrameSnapshot frame = measuredSnapshot(render, o);
  v.frameValid = false;  // the renderer now holds the measured frame: render the one on screen again
  v.referenceOptions = o;
  v.referenceCamera = v.cameraVersion;
  v.referenceLights = v.lightsVersion;
  v.referenceStart = std::chrono::steady_clock::now();
  auto progress = std::make_shared<WorkProgress>();
  progress->total = (kRowPasses + kDecomposeWeight) * frame.camera.height;
  v.referenceProgress = progress;
  v.referenceLoggedTenth = 0;
  v.referenceJob = std::async(std::launch::async, [scene = v.scene, frame = std::move(frame), o, progress]() {
    ProgressScope scope(progress.get());
    Viewer::ReferenceResult result;
    ReferenceCache cache(scene);
    const ReferenceView ref = cache.get(frame.camera, o.time, kShadowBandTexels, o.shadowMapSize);
    if (!progress->cancelled()) result.error = measureError(frame, ref);
    progress->weight = kDecomposeWeight;
    if (!progress->cancelled()) decomposeLighting(frame, result.decomposition, result.decomposeError, 2);
    result.cancelled = progress->cancelled();
    return result;
  });
  e.computing = true;
  e.progress = 0.0;
}

// Every map into `dir` (error maps as gblens error -o names them, the decomposition as gblens
// decompose does, under decompose/), through a temporary folder renamed at the end.
static bool writeMaps(const Viewer::ReferenceResult& r, const std::string& dir, std::string& error) {
  const fs::path tmp = dir + ".tmp-reference-error";
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp / "decompose", ec);
  if (ec) return error = tmp.string() + ": " + ec.message(), false;
  for (const ErrorMapDef& map : errorMaps())
    if (!writePng((tmp / (std::string(map.name) + ".png")).string(), map.make(r.error), error)) return false;
  if (r.decomposeError.empty())
    for (size_t t = 0; t < kLightingTermCount; ++t)
      if (!writeExr((tmp / "decompose" / (std::string(name(LightingTerm(t))) + ".exr")).string(), r.decomposition.images[t],
                    error))
        return false;
  fs::remove_all(dir, ec);
  fs::rename(tmp, dir, ec);
  if (ec) error = dir + ": " + ec.message();
  return !ec;
}

// ---- the maps as views ------------------------------------------------------------------------

static ViewDef mapView(const std::string& name, Visual visual) {
  ViewDef d;
  d.name = name;
  d.visual = visual;
  d.negativeSuspicious = false;
  if (visual == Visual::Count) {
    d.kind = QuantityKind::Count;
    d.integer = true;
    d.componentNames = {"Count"};
    d.channels = 0x1;
    d.autoRange = true;
    d.unit = "point lights";
  } else {
    d.kind = QuantityKind::Radiance;
    d.components = 3;
    d.componentNames = {"R", "G", "B"};
  }
  return d;
}

// An error map (sRGB colours) as a decoded view image: linear RGBA floats.
static CpuImage decodedErrorMap(const Rgba8Image& map, const std::string& name) {
  CpuImage img = decodedViewImage(name, map.width, map.height);
  float* out = reinterpret_cast<float*>(img.data.data());
  for (size_t i = 0; i < size_t(map.width) * map.height; ++i)
    for (int c = 0; c < 4; ++c) out[i * 4 + c] = c < 3 ? float(srgbToLinear(map.pixels[i * 4 + c] / 255.0)) : 1.0f;
  return img;
}

// The light count (R32F) as an integer view image.
static CpuImage decodedCount(const CpuImage& src, const std::string& name) {
  CpuImage img;
  img.name = name;
  img.width = src.width, img.height = src.height;
  img.type = PixelType::U32;
  img.encoding = Encoding::Uint;
  img.channels = {name};
  img.data.resize(size_t(src.width) * src.height * 4);
  for (uint32_t y = 0; y < src.height; ++y)
    for (uint32_t x = 0; x < src.width; ++x) {
      const uint32_t n = uint32_t(src.value(x, y, 0));
      std::memcpy(img.data.data() + (size_t(y) * src.width + x) * 4, &n, 4);
    }
  return img;
}

// The result's maps as views and decoded images: the error maps (errorMaps order), then the
// decomposition's terms where it could be made.
static void makeViews(Viewer& v) {
  const Viewer::ReferenceResult& r = *v.referenceResult;
  auto& e = v.model.referenceError;
  v.referenceViews.clear();
  v.referenceDecoded.clear();
  e.legends.clear();
  for (const ErrorMapDef& map : errorMaps()) {
    ViewDef d = mapView(std::string("error/") + map.name, Visual::Color);
    d.space = "error map of gblens error (its legend: at the bottom of the view)";
    e.legends[d.name] = map.legend;
    v.referenceDecoded.push_back(decodedErrorMap(map.make(r.error), d.name));
    v.referenceViews.push_back(d);
  }
  if (r.decomposeError.empty())
    for (size_t t = 0; t < kLightingTermCount; ++t) {
      const LightingTerm term = LightingTerm(t);
      const bool count = term == LightingTerm::LightCount;
      ViewDef d = mapView(std::string("decompose/") + name(term), count ? Visual::Count : Visual::Color);
      if (!count) {
        d.hdr = true;
        d.autoRange = true;
        d.space = "linear radiance, shading.h in double (gblens decompose)";
      }
      e.legends[d.name] = count ? "point lights whose sphere reaches the surface point (gblens decompose light_count)"
                                : std::string(name(term)) + " from the G-buffer with shading.h in double (gblens decompose); "
                                                            "auto range: black 0 .. white its largest value";
      const CpuImage& img = r.decomposition.images[t];
      v.referenceDecoded.push_back(count ? decodedCount(img, d.name) : img);
      v.referenceViews.push_back(d);
    }
  uploadViewImages(v.referenceImages, v.ctx, v.referenceDecoded);
  v.referenceRanges.assign(v.referenceViews.size(), {});
}

void appendReferenceViews(const Viewer& v, std::vector<ViewDef>& views) {
  views.insert(views.end(), v.referenceViews.begin(), v.referenceViews.end());
}

// The index into referenceViews of the model's view `view` (-1: not a map).
static int mapIndex(const Viewer& v, int view) {
  const ViewerModel& m = v.model;
  if (view < 0 || size_t(view) >= m.views.size() || m.views[size_t(view)].quantity >= 0) return -1;
  return findView(v.referenceViews, m.views[size_t(view)].name);
}

std::string referenceViewStatus(Viewer& v, int view) {
  ViewerModel& m = v.model;
  m.gpuSources[size_t(view)] = ViewGpuSource{};  // a decoded image, components in channels 0..3
  const int k = mapIndex(v, view);
  if (k < 0) return "not computed";
  const CpuImage& img = v.referenceDecoded[size_t(k)];
  if (img.width != m.fullSize.x || img.height != m.fullSize.y) {
    char why[160];
    std::snprintf(why, sizeof why, "computed for a %ux%u frame; this one is %ux%u (recompute)", img.width, img.height,
                  m.fullSize.x, m.fullSize.y);
    return why;
  }
  return "";
}

ViewImage referenceViewImage(const Viewer& v, int view) {
  const int k = mapIndex(v, view);
  return k < 0 ? ViewImage{} : viewImageOf(v.referenceImages, size_t(k));
}

// A map's value at a pixel: what its colour stands for (the error, the class), or the term's value.
std::string referenceHoverText(const Viewer& v, int view, glm::ivec2 texel) {
  const int k = mapIndex(v, view);
  if (k < 0 || !v.referenceResult) return "";
  const FrameError& e = v.referenceResult->error;
  const std::string& name = v.referenceViews[size_t(k)].name;
  const CpuImage& img = v.referenceDecoded[size_t(k)];
  if (texel.x < 0 || texel.y < 0 || uint32_t(texel.x) >= img.width || uint32_t(texel.y) >= img.height) return "";
  const size_t i = size_t(texel.y) * img.width + size_t(texel.x);
  char text[200];
  static const char* const kPixel[] = {"sky", "surface (the same triangle)", "silhouette (another triangle)",
                                       "only the GPU has a surface", "only the reference has a surface"};
  static const char* const kShadow[] = {"not a surface",      "lit in both",  "shadowed in both",
                                        "penumbra band (not compared)", "GPU shadowed, the sun ray is free (acne)",
                                        "GPU lit, the ray is blocked (leak)", "faces away from the sun (not compared)"};
  const std::string pixel = kPixel[size_t(e.pixelClass[i])];
  auto value = [&](const std::vector<float>& values, const char* what) {
    if (e.pixelClass[i] != PixelClass::Surface) return name + ": " + pixel;
    std::snprintf(text, sizeof text, "%s: %.6g %s", name.c_str(), double(values[i]), what);
    return std::string(text);
  };
  if (name == "error/shadow") return name + ": " + kShadow[size_t(e.shadowClass[i])] + ", " + pixel;
  if (name == "error/silhouettes") return name + ": " + pixel;
  if (name == "error/normal") return value(e.normalErrorDeg, "degrees to the reference's normal");
  if (name == "error/hdr") return value(e.hdrRelative, "relative error of the HDR colour");
  if (name == "error/position") return value(e.eyeDepthPositionRelative, "|P - P_ref| / eye depth");
  if (name == "error/lighting") return value(e.lightingPerContribution, "error per light contribution");
  if (img.type == PixelType::U32) {
    std::snprintf(text, sizeof text, "%s: %u point lights", name.c_str(), img.raw(uint32_t(texel.x), uint32_t(texel.y), 0));
    return text;
  }
  std::snprintf(text, sizeof text, "%s: R %.6g G %.6g B %.6g", name.c_str(), img.value(uint32_t(texel.x), uint32_t(texel.y), 0),
                img.value(uint32_t(texel.x), uint32_t(texel.y), 1), img.value(uint32_t(texel.x), uint32_t(texel.y), 2));
  return text;
}

// The automatic ranges of the maps on screen, from their images (the GPU reduction reads only
// gblens's targets; updateRanges leaves these views' ranges empty).
static void updateMapRanges(Viewer& v) {
  ViewerModel& m = v.model;
  for (int view : visibleViews(m)) {
    const int k = mapIndex(v, view);
    if (k < 0 || !m.settings[size_t(view)].autoRange) continue;
    const uint32_t mask = viewMapping(m.views[size_t(view)], m.settings[size_t(view)]).mask;
    auto& cached = v.referenceRanges[size_t(k)];
    if (!cached || cached->first != mask)
      cached = std::make_pair(mask, imageRange(v.referenceDecoded[size_t(k)], v.referenceViews[size_t(k)], mask));
    if (m.ranges[size_t(view)].empty()) {
      m.ranges[size_t(view)] = {cached->second};
      m.uiChanged = true;
    }
  }
}

// The worker's result picked up: the maps become views (or, cancelled, nothing changes).
static void finish(Viewer& v, double seconds) {
  ViewerModel& m = v.model;
  auto& e = m.referenceError;
  Viewer::ReferenceResult result = v.referenceJob.get();
  e.computing = false;
  m.uiChanged = true;
  const WorkProgress& p = *v.referenceProgress;
  if (result.cancelled) {
    const double afterCancel = std::chrono::duration<double>(std::chrono::steady_clock::now() - v.referenceCancelAt).count();
    e.error = "cancelled at " + std::to_string(int(p.fraction() * 100.0)) + "%";
    logLine(v.eventLog, {{"event", "reference_error_cancelled"}, {"fraction", p.fraction()}, {"seconds", seconds},
                         {"seconds_after_cancel", afterCancel}});
    std::fprintf(stderr, "gblens view: reference error cancelled at %.0f%% (stopped %.2f s after the cancel)\n",
                 p.fraction() * 100.0, afterCancel);
    return;
  }
  v.referenceResult = std::move(result);
  e.ready = true;
  e.seconds = seconds;
  const FrameError& fe = v.referenceResult->error;
  char summary[160];
  std::snprintf(summary, sizeof summary, "%ux%u at time %.3f s, %llu surface pixels, %llu silhouettes", fe.width, fe.height,
                v.referenceOptions.time, (unsigned long long)fe.surface, (unsigned long long)fe.silhouette);
  e.summary = summary;
  e.decomposeNote = v.referenceResult->decomposeError.empty() ? "" : "decomposition: " + v.referenceResult->decomposeError;
  logLine(v.eventLog, {{"event", "reference_error"}, {"seconds", seconds}, {"size", {fe.width, fe.height}},
                       {"rows", p.done.load()}, {"rows_expected", p.total.load()}});
  if (!v.args.referenceErrorDir.empty()) {
    std::string error;
    if (!writeMaps(*v.referenceResult, v.args.referenceErrorDir, error)) e.error = error;
    logLine(v.eventLog, {{"event", "reference_error_written"}, {"dir", v.args.referenceErrorDir}, {"error", e.error}});
  }
  makeViews(v);
  updateLiveViews(v);  // the maps join the frame's views
}

bool updateReferenceError(Viewer& v) {
  ViewerModel& m = v.model;
  auto& e = m.referenceError;
  // --reference-error DIR: computed once at start.
  if (!v.args.referenceErrorDir.empty() && !v.referenceJob.valid() && !v.referenceResult && !v.referenceStarted && v.frameValid)
    e.computeRequested = true;
  if (e.computeRequested && !e.computing && v.frameValid && m.source == FrameSource::Live) {
    v.referenceStarted = true;
    start(v);
  }
  e.computeRequested = false;
  if (e.cancelRequested && e.computing && !v.referenceProgress->cancelled()) {
    v.referenceProgress->cancel = true;
    v.referenceCancelAt = std::chrono::steady_clock::now();
  }
  e.cancelRequested = false;
  if (e.computing) {
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - v.referenceStart).count();
    e.seconds = seconds;
    e.progress = v.referenceProgress->fraction();
    const int tenth = int(e.progress * 10.0);
    if (tenth > v.referenceLoggedTenth) {  // for tests and scripts: every tenth of the rows
      v.referenceLoggedTenth = tenth;
      logLine(v.eventLog, {{"event", "reference_error_progress"}, {"fraction", e.progress}, {"seconds", seconds}});
    }
    if (v.referenceJob.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return true;
    finish(v, seconds);
  }
  if (v.referenceResult) updateMapRanges(v);
  e.stale = e.ready && (v.referenceCamera != v.cameraVersion || v.referenceLights != v.lightsVersion ||
                        frameOutdated(v.referenceOptions, v.fullOptions));
  return false;
}

void stopReferenceError(Viewer& v) {
  if (v.referenceProgress) v.referenceProgress->cancel = true;
  if (v.referenceJob.valid()) v.referenceJob.wait();
  destroyViewImages(v.referenceImages, v.ctx);
}

}  // namespace gb
