// Measuring a frame against the reference: asks its frame source for a frame with the targets the
// measure needs (primitive_id on, fairies off: sprites are not part of the reference) and keeps the
// reference of a scene per view, light set and band width, so a sweep pays for each only once.
// The frame source is a function (a HeadlessSession's renderSnapshot): analysis never sees a renderer.
#pragma once
#include <functional>
#include <map>
#include <memory>
#include <string>

#include "renderer/reference/reference.h"
#include "views/analysis/error.h"

namespace gb {

class ReferenceCache {
 public:
  explicit ReferenceCache(const Scene& scene, unsigned threads = 2);
  // The reference for this view and time: surfaces, penumbra band, shading of the scene's lights.
  ReferenceView get(const Camera& camera, double time, double bandTexels, uint32_t shadowMapSize);
  const reference::RayScene& rays() const { return *rays_; }
  double seconds = 0.0;  // CPU time spent building references (reported by bench)

 private:
  const Scene& scene_;
  unsigned threads_;
  std::unique_ptr<reference::RayScene> rays_;
  struct Entry {
    reference::Frame frame;
    std::map<double, std::vector<uint8_t>> bands;      // by radius
    std::map<std::string, reference::Shaded> shaded;   // by light set and time
  };
  std::map<std::string, Entry> entries_;
};

// The penumbra band used for shadow comparisons, in shadow-map texels (half-width).
constexpr double kShadowBandTexels = 2.0;

// What a caller may add to a measurement: more targets read back in the same frame (gblens
// stress scans every target), and the view to take the reference from when the frame's own is
// not the one (a scene moved far from the origin is measured against the same view at the
// origin: everything the reference computes is relative to the camera).
struct MeasureExtras {
  std::vector<Target> readback;
  const Camera* referenceCamera = nullptr;
};

// A frame of these options with these targets read back (whole), as a snapshot.
using FrameRender = std::function<FrameSnapshot(const RenderOptions&, const std::vector<Target>&)>;

struct MeasuredFrame {
  FrameSnapshot frame;  // what was measured, with the extra read-backs
  FrameError error;
};
// The frame a measurement reads: `options` with primitive_id on and fairies off, every measured
// target read back (forward: the surfaces from the deferred frame of the same options).
FrameSnapshot measuredSnapshot(const FrameRender& render, const RenderOptions& options, const MeasureExtras& extras = {});
// Renders `options` once more with the measure's read-backs and returns the frame and its error.
// Method forward: surface figures from the deferred frame of the same options, hdr from forward.
MeasuredFrame measureFrame(const FrameRender& render, const RenderOptions& options, ReferenceCache& cache,
                           double bandTexels = kShadowBandTexels, const MeasureExtras& extras = {});

}  // namespace gb
