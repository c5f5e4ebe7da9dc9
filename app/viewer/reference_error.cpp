// The reference error, live: the frame on screen rendered once more as `gblens error` renders it
// (views/analysis/accuracy.h measuredSnapshot), then the reference and the error computed in a
// worker thread from copies (the scene, the snapshot), so the viewer keeps answering; the map the
// window shows is uploaded into a renderer of its own and drawn through the view pipeline.
#include <cstdio>
#include <filesystem>

#include "app/viewer/viewer.h"
#include "renderer/session.h"
#include "renderer/upload_targets.h"
#include "views/analysis/accuracy.h"
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
    ReferenceCache cache(scene);
    const ReferenceView ref = cache.get(frame.camera, o.time, kShadowBandTexels, o.shadowMapSize);
    return measureError(frame, ref);
  });
  e.computing = true;
  e.ready = false;
}

// Every map into `dir`, through a temporary folder renamed at the end (nothing half-written).
static bool writeMaps(const FrameError& fe, const std::string& dir, std::string& error) {
  const fs::path tmp = dir + ".tmp-reference-error";
  std::error_code ec;
  fs::remove_all(tmp, ec);
  fs::create_directories(tmp, ec);
  if (ec) return error = tmp.string() + ": " + ec.message(), false;
  for (const ErrorMapDef& map : errorMaps())
    if (!writePng((tmp / (std::string(map.name) + ".png")).string(), map.make(fe), error)) return false;
  fs::remove_all(dir, ec);
  fs::rename(tmp, dir, ec);
  if (ec) error = dir + ": " + ec.message();
  return !ec;
}

static void show(Viewer& v) {
  auto& e = v.model.referenceError;
  const Rgba8Image map = errorMaps()[size_t(e.map)].make(*v.referenceResult);
  CpuImage image;
  image.name = "final";
  image.channels = {"R", "G", "B", "A"};
  image.width = map.width;
  image.height = map.height;
  image.type = PixelType::U8;
  image.encoding = Encoding::Srgb;
  image.data = map.pixels;
  RenderOptions o = v.referenceOptions;
  o.width = map.width;
  o.height = map.height;
  if (!v.referenceShown && v.rendererRef.ctx == nullptr) {
    Camera camera;
    camera.width = map.width, camera.height = map.height;
    v.sceneRef = emptyScene(camera);
    initRenderer(v.rendererRef, v.ctx, v.sceneRef);
  }
  std::array<const CpuImage*, kTargetCount> images{};
  images[size_t(Target::Final)] = &image;
  uploadTargets(v.rendererRef, o, images);
  e.width = map.width;
  e.height = map.height;
  e.mapChanged = false;
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
    const FrameError& fe = *v.referenceResult;
    char summary[160];
    std::snprintf(summary, sizeof summary, "%ux%u at time %.3f s, %llu surface pixels, %llu silhouettes", fe.width,
                  fe.height, v.referenceOptions.time, (unsigned long long)fe.surface, (unsigned long long)fe.silhouette);
    e.summary = summary;
    logLine(v.eventLog, {{"event", "reference_error"}, {"seconds", seconds}, {"size", {fe.width, fe.height}}});
    if (!v.args.referenceErrorDir.empty()) {
      std::string error;
      if (!writeMaps(fe, v.args.referenceErrorDir, error)) e.error = error;
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
