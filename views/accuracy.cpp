// ReferenceCache and measureFrame (see accuracy.h).
#include "views/accuracy.h"

#include <algorithm>
#include <chrono>
#include <sstream>

namespace gb {

ReferenceCache::ReferenceCache(const Scene& scene, unsigned threads)
    : scene_(scene), threads_(threads), rays_(std::make_unique<reference::RayScene>(scene, threads)) {}

ReferenceView ReferenceCache::get(const View& view, double time, double bandTexels, uint32_t shadowMapSize) {
  auto start = std::chrono::steady_clock::now();
  std::ostringstream key;
  key.precision(17);
  key << view.width << 'x' << view.height;
  for (int c = 0; c < 4; ++c)
    for (int k = 0; k < 4; ++k) key << ' ' << view.worldFromEye[c][k];
  key << ' ' << view.yfov << ' ' << view.aspect;
  Entry& e = entries_[key.str()];
  if (e.frame.pixels.empty()) e.frame = reference::renderFrame(*rays_, view, threads_);
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
                 .emplace(lightKey.str(), reference::shade(in, view, reference::eyeLights(scene_, view, time),
                                                           reference::sunOf(scene_, view), threads_))
                 .first;
  }
  seconds += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return {&e.frame, &shaded->second, &band->second, bandTexels, radius};
}

FrameError measureFrame(Renderer& r, const RenderOptions& options, ReferenceCache& cache, double bandTexels,
                        const MeasureExtras& extras) {
  RenderOptions o = options;
  o.primitiveId = true;  // silhouettes: where the rasterizer and the ray caster see different triangles
  o.fairies = false;     // sprites over the surfaces are not part of the reference
  FrameRequest request;
  request.readback = {Target::AlbedoSpecular, Target::NormalShadow, Target::Depth, Target::DepthStencil, Target::Hdr};
  if (o.position != PositionSource::Depth) request.readback.push_back(Target::Position);
  const bool ids = primitiveIdOn(*r.ctx, o);
  if (ids) request.readback.push_back(Target::PrimitiveId);
  for (Target t : extras.readback)
    if (std::find(request.readback.begin(), request.readback.end(), t) == request.readback.end())
      request.readback.push_back(t);
  // Forward has no G-buffer: the surface figures come from the deferred frame of the same
  // options (the same rasterized surfaces), the colour from the forward frame itself.
  CpuImage forwardHdr;
  if (o.method == Method::Forward) {
    RenderOptions forward = o;
    forward.primitiveId = false;
    renderFrame(r, forward, {{Target::Hdr}});
    forwardHdr = r.readback[size_t(Target::Hdr)];
    o.method = Method::Deferred;
  }
  renderFrame(r, o, request);
  if (!forwardHdr.empty()) {
    r.readback[size_t(Target::Hdr)] = forwardHdr;
    o.method = Method::Forward;
  }
  GpuFrame g;
  g.albedoSpecular = &r.readback[size_t(Target::AlbedoSpecular)];
  g.normalShadow = &r.readback[size_t(Target::NormalShadow)];
  g.depth = &r.readback[size_t(Target::Depth)];
  g.depthStencil = &r.readback[size_t(Target::DepthStencil)];
  g.hdr = &r.readback[size_t(Target::Hdr)];
  if (o.position != PositionSource::Depth) g.position = &r.readback[size_t(Target::Position)];
  if (ids) g.primitiveId = &r.readback[size_t(Target::PrimitiveId)];
  g.options = o;
  g.frame = r.frameData;
  g.lights = r.lights.eye;
  g.srgbDecode = &probeSrgbDecode(r);
  ReferenceView ref = cache.get(extras.referenceView ? *extras.referenceView : r.view, o.time, bandTexels, o.shadowMapSize);
  return measureError(g, ref);
}

}  // namespace gb
