// ReferenceCache and measureFrame (see accuracy.h).
#include "views/analysis/accuracy.h"

#include <algorithm>
#include <chrono>
#include <sstream>

namespace gb {

ReferenceCache::ReferenceCache(const Scene& scene, unsigned threads)
    : scene_(scene), threads_(threads), rays_(std::make_unique<reference::RayScene>(scene, threads)) {}

ReferenceView ReferenceCache::get(const Camera& camera, double time, double bandTexels, uint32_t shadowMapSize) {
  auto start = std::chrono::steady_clock::now();
  std::ostringstream key;
  key.precision(17);
  key << camera.width << 'x' << camera.height;
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) key << ' ' << camera.worldFromEye[c][k];
  key << ' ' << camera.yfov << ' ' << camera.aspect;
  Entry& e = entries_[key.str()];
  if (e.frame.pixels.empty()) e.frame = reference::renderFrame(*rays_, camera, threads_);
  double radius = bandTexels * reference::shadowTexelSize(scene_, shadowMapSize);
  auto band = e.bands.find(radius);
  if (band == e.bands.end()) band = e.bands.emplace(radius, reference::shadowBand(*rays_, e.frame, radius, threads_)).first;
  std::ostringstream lightKey;
  lightKey.precision(17);
  lightKey << scene_.lights.size() << '@' << time;
  if (!scene_.lights.empty()) lightKey << ' ' << scene_.lights.back().radius << ' ' << scene_.lights.front().center.x;
  auto shaded = e.shaded.find(lightKey.str());
  if (shaded == e.shaded.end()) {
    std::vector<reference::ShadingInput> in;
    in.reserve(e.frame.pixels.size());
    for (const reference::Surface& s : e.frame.pixels) in.push_back(reference::shadingInput(s));
    shaded = e.shaded
                 .emplace(lightKey.str(), reference::shade(in, camera, reference::eyeLights(scene_, camera, time),
                                                           reference::sunOf(scene_, camera), threads_))
                 .first;
  }
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {&e.frame, &shaded->second, &band->second, bandTexels, radius};
}

FrameSnapshot measuredSnapshot(const FrameRender& render, const RenderOptions& options, const MeasureExtras& extras) {
  RenderOptions o = options;
  o.primitiveId = true;  // silhouettes: where the rasterizer and the ray caster see different triangles
  o.fairies = false;     // sprites over the surfaces are not part of the reference
  std::vector<Target> targets = measuredTargets(o);
  for (Target t : extras.readback)
    if (std::find(targets.begin(), targets.end(), t) == targets.end()) targets.push_back(t);
  if (o.method != Method::Forward) return render(o, targets);
  // Forward has no G-buffer: the surface figures come from the deferred frame of the same
  // options (the same rasterized surfaces), the colour from the forward frame itself.
  RenderOptions forward = o;
  forward.primitiveId = false;
  TargetImage forwardHdr = render(forward, {Target::Hdr}).target(Target::Hdr);
  RenderOptions deferred = o;
  deferred.method = Method::Deferred;
  FrameSnapshot f = render(deferred, targets);
  f.target(Target::Hdr) = std::move(forwardHdr);
  f.options.method = Method::Forward;
  return f;
}

MeasuredFrame measureFrame(const FrameRender& render, const RenderOptions& options, ReferenceCache& cache,
                           double bandTexels, const MeasureExtras& extras) {
  MeasuredFrame m;
  m.frame = measuredSnapshot(render, options, extras);
  ReferenceView ref = cache.get(extras.referenceCamera ? *extras.referenceCamera : m.frame.camera, options.time, bandTexels,
                                options.shadowMapSize);
  m.error = measureError(m.frame, ref);
  return m;
}

}  // namespace gb
