// The reference error, live: the frame on screen rendered once more as `gblens error` renders it
// (views/analysis/accuracy.h measuredSnapshot), then the reference and the error computed in a
// worker thread from copies (the scene, the snapshot), so the viewer keeps answering; the map the
// window shows is uploaded into a renderer of its own and drawn through the view pipeline.
#include <algorithm>
#include <cstdio>
#include <cstring>
#include <filesystem>

#include "app/viewer/viewer.h"
#include "renderer/session.h"
#include "renderer/upload_targets.h"
#include "views/analysis/accuracy.h"
#include "views/capture/exr.h"
#include "views/capture/image_io.h"

namespace gb {

namespace fs = std::filesystem;

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
  v.referenceJob = std::async(std::launch::async, [scene = v.scene, frame = std::move(frame), o]() {
    Viewer::ReferenceResult result;
    ReferenceCache cache(scene);
    const ReferenceView ref = cache.get(frame.camera, o.time, kShadowBandTexels, o.shadowMapSize);
    result.error = measureError(frame, ref);
    decomposeLighting(frame, result.decomposition, result.decomposeError, 2);
    return result;
  });
  e.computing = true;
  e.ready = false;
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

// The selected map as a target of the window's renderer: an error map (sRGB) as `final`, a
// decomposition term (linear) as `hdr`, the light count as `coverage_full` (a heat map).
static CpuImage selectedMap(Viewer& v, Visual& mapping, bool& srgbMap, float& white) {
  const auto& e = v.model.referenceError;
  const Viewer::ReferenceResult& r = *v.referenceResult;
  CpuImage image;
  white = 1.0f;
  if (size_t(e.map) < errorMaps().size()) {
    const Rgba8Image map = errorMaps()[size_t(e.map)].make(r.error);
    image.name = "final";
    image.channels = {"R", "G", "B", "A"};
    image.width = map.width, image.height = map.height;
    image.type = PixelType::U8;
    image.encoding = Encoding::Srgb;
    image.data = map.pixels;
    mapping = Visual::Color;
    srgbMap = true;
    return image;
  }
  const LightingTerm term = LightingTerm(size_t(e.map) - errorMaps().size());
  if (!r.decomposeError.empty()) return image;
  const CpuImage& src = r.decomposition.images[size_t(term)];
  image.width = src.width, image.height = src.height;
  float largest = 0.0f;
  if (term == LightingTerm::LightCount) {
    image.name = "coverage_full";
    image.channels = {"Volumes"};
    image.type = PixelType::U32;
    image.encoding = Encoding::Uint;
    image.data.resize(size_t(src.width) * src.height * 4);
    for (uint32_t y = 0; y < src.height; ++y)
      for (uint32_t x = 0; x < src.width; ++x) {
        const uint32_t n = uint32_t(src.value(x, y, 0));
        std::memcpy(image.data.data() + (size_t(y) * src.width + x) * 4, &n, 4);
        largest = std::max(largest, float(n));
      }
    mapping = Visual::Count;
  } else {
    image = src;
    image.name = "hdr";
    for (uint32_t y = 0; y < src.height; ++y)
      for (uint32_t x = 0; x < src.width; ++x)
        for (int c = 0; c < 3; ++c) largest = std::max(largest, float(src.value(x, y, uint32_t(c))));
    mapping = Visual::Color;
    srgbMap = false;
  }
  white = largest;
  return image;
}

static void show(Viewer& v) {
  auto& e = v.model.referenceError;
  const CpuImage image = selectedMap(v, e.mapping, e.srgbMap, e.white);
  e.mapChanged = false;
  e.decomposeNote = v.referenceResult->decomposeError.empty() ? "" : "decomposition: " + v.referenceResult->decomposeError;
  if (image.empty()) return;
  RenderOptions o = v.referenceOptions;
  o.width = image.width;
  o.height = image.height;
  o.accumFormat = AccumFormat::Rgba32f;  // hdr holds the decomposition's floats as they are
  o.coverage = true;                     // coverage_full at full size holds the light count
  if (v.rendererRef.ctx == nullptr) {
    Camera camera;
    camera.width = image.width, camera.height = image.height;
    v.sceneRef = emptyScene(camera);
    initRenderer(v.rendererRef, v.ctx, v.sceneRef);
  }
  std::array<const CpuImage*, kTargetCount> images{};
  images[size_t(e.mapping == Visual::Count ? Target::CoverageFull : e.srgbMap ? Target::Final : Target::Hdr)] = &image;
  uploadTargets(v.rendererRef, o, images);
  e.width = image.width;
  e.height = image.height;
  v.referenceShown = true;
}

bool updateReferenceError(Viewer& v) {
  ViewerModel& m = v.model;
  auto& e = m.referenceError;
  if (!v.args.referenceErrorDir.empty() && !v.referenceJob.valid() && !v.referenceResult && v.frameValid) e.computeRequested = true;
  if (e.computeRequested && !e.computing && v.frameValid && m.source == FrameSource::Live) start(v);
  e.computeRequested = false;
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - v.referenceStart).count();
  if (e.computing) {
    e.seconds = seconds;
    if (v.referenceJob.wait_for(std::chrono::seconds(0)) != std::future_status::ready) return true;
    v.referenceResult = v.referenceJob.get();
    e.computing = false;
    e.ready = true;
    const FrameError& fe = v.referenceResult->error;
    char summary[160];
    std::snprintf(summary, sizeof summary, "%ux%u at time %.3f s, %llu surface pixels, %llu silhouettes", fe.width,
                  fe.height, v.referenceOptions.time, (unsigned long long)fe.surface, (unsigned long long)fe.silhouette);
    e.summary = summary;
    logLine(v.eventLog, {{"event", "reference_error"}, {"seconds", seconds}, {"size", {fe.width, fe.height}}});
    if (!v.args.referenceErrorDir.empty()) {
      std::string error;
      if (!writeMaps(*v.referenceResult, v.args.referenceErrorDir, error)) e.error = error;
      logLine(v.eventLog, {{"event", "reference_error_written"}, {"dir", v.args.referenceErrorDir}, {"error", e.error}});
    }
    e.mapChanged = true;
  }
  if (e.ready && e.mapChanged) show(v);
  e.stale = e.ready && (v.referenceCamera != v.cameraVersion || v.referenceLights != v.lightsVersion ||
                        frameOutdated(v.referenceOptions, v.fullOptions));
  return false;
}

}  // namespace gb
