// Error of a GPU frame against the CPU reference, per quantity: normal (angle), albedo and
// specular (8-bit steps), eye depth, reconstructed positions (every source), shadow (lit/shadowed
// disagreements outside a penumbra band), final HDR colour, and the lighting passes alone.
// Silhouette pixels (the rasterizer and the ray caster see different triangles) are counted
// separately and left out of every per-surface figure.
#pragma once
#include <nlohmann/json.hpp>

#include <vector>

#include "renderer/core/snapshot.h"
#include "renderer/reference/reference.h"
#include "shaders/shared.h"
#include "views/capture/image_io.h"

namespace gb {

// Distribution of a per-pixel error over the pixels it was measured on.
struct ErrorStats {
  uint64_t count = 0;
  double max = 0.0, mean = 0.0, rms = 0.0, p99 = 0.0;
};
ErrorStats errorStats(std::vector<double> values);

// The reference for the same view, and the stated penumbra band.
struct ReferenceView {
  const reference::Frame* frame = nullptr;
  const reference::Shaded* shaded = nullptr;  // shading of the reference surfaces
  const std::vector<uint8_t>* band = nullptr;
  double bandTexels = 0.0, bandRadius = 0.0;  // band half-width in shadow-map texels and world units
};

// Pixel classes (FrameError::pixelClass).
enum class PixelClass : uint8_t { Sky, Surface, Silhouette, CoverageOnlyGpu, CoverageOnlyReference };
// Shadow comparison per pixel (FrameError::shadowClass).
enum class ShadowClass : uint8_t { None, AgreeLit, AgreeShadowed, Band, FalseShadow, FalseLight, NotCompared };

struct PositionError {
  ErrorStats relative;  // |P - P_ref| / eye depth
  ErrorStats absolute;  // scene units
};

struct FrameError {
  uint32_t width = 0, height = 0;
  bool primitiveIds = false;  // silhouettes from primitive_id (else from a depth-difference fallback)
  uint64_t surface = 0, sky = 0, silhouette = 0, coverageOnlyGpu = 0, coverageOnlyReference = 0;
  ErrorStats normalDeg;
  ErrorStats albedoUntextured, albedoTextured, specular;  // in steps of the 8-bit value (1/255)
  ErrorStats eyeDepthRelative, eyeDepthUlps;              // the eye-depth target
  PositionError fromEyeDepth, fromHardwareDepth, fromPosition, used;
  bool storedPosition = false;
  struct Shadow {
    uint64_t compared = 0, band = 0, mismatched = 0, falseShadow = 0, falseLight = 0, notCompared = 0;
    uint64_t bandMismatched = 0;
    double fraction = 0.0;          // mismatched / compared (outside the band)
    double fractionWithBand = 0.0;  // including the band
  } shadow;
  struct Hdr {
    ErrorStats absolute, relative;  // per pixel: max over R, G, B
  } hdr, hdrUntexturedOutsideBand;
  // The device's sRGB decode (what the lighting passes read albedo through) vs the exact curve:
  // largest relative deviation over the 255 non-zero byte values (-1: not probed).
  double srgbDecodeMaxRelative = -1.0;
  struct Lighting {
    ErrorStats relative;         // |hdr - shade(GPU G-buffer)| / |shade|
    ErrorStats perContribution;  // |hdr - shade| / (contributions * sum |contribution|)
    uint32_t maxContributions = 0;
  } lighting;
  // Where: one entry per pixel, rows top to bottom.
  std::vector<PixelClass> pixelClass;
  std::vector<ShadowClass> shadowClass;
  std::vector<float> normalErrorDeg, hdrRelative;
};

// The targets measureError reads under these options (position when stored, primitive_id when on).
std::vector<Target> measuredTargets(const RenderOptions& options);
// The error of a frame (its albedo_specular, normal_shadow, depth, depth_stencil and hdr, whole;
// position and primitive_id when present) against the reference of the same view.
FrameError measureError(const FrameSnapshot& frame, const ReferenceView& ref, unsigned threads = 2);
nlohmann::json errorJson(const ErrorStats& s);
nlohmann::json errorJson(const FrameError& e);

// Images of where the errors are (see the legend in error.cpp).
Rgba8Image shadowErrorImage(const FrameError& e);
Rgba8Image silhouetteImage(const FrameError& e);
Rgba8Image normalErrorImage(const FrameError& e);
Rgba8Image hdrErrorImage(const FrameError& e);

}  // namespace gb
