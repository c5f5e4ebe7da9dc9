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

// Where the GPU puts a surface, relative to its eye depth: the vertex stage sums its terms in
// float (3 roundings of vertexTerms), and the rasterizer forms framebuffer coordinates and the
// attribute planes in float, so an interpolated attribute is exact for the triangle moved by about
// 2^-24 x its framebuffer coordinates (screenExtent pixels: the frame, or farther for off-screen
// vertices); the eye depth moves by that times its change per pixel.
// 2^-24 (3 vertexTerms + 2 screenExtent eyeDepthChange) / eyeDepth; the factor 2 is over the
// largest ratio measured on llvmpipe (docs/accuracy.md). Devices that interpolate from positions
// snapped to their sub-pixel grid move the triangle further.
double placementAllowance(const reference::Surface& s, uint32_t width, uint32_t height);

struct FrameError {
  uint32_t width = 0, height = 0;
  bool primitiveIds = false;  // silhouettes from primitive_id (else from a depth-difference fallback)
  uint64_t surface = 0, sky = 0, silhouette = 0, coverageOnlyGpu = 0, coverageOnlyReference = 0;
  uint64_t unlit = 0, unlitMismatched = 0;  // surface pixels unlit in either (KHR_materials_unlit), and in one only
  ErrorStats normalDeg;
  ErrorStats albedoUntextured, albedoTextured, specular;  // in steps of the 8-bit value (1/255)
  ErrorStats eyeDepthRelative, eyeDepthUlps;              // the eye-depth target
  PositionError fromEyeDepth, fromHardwareDepth, fromPosition, used;
  // From eye depth, what the float placement of the surface does not explain: per pixel
  // max(0, relative error - placementAllowance). Storage and reconstruction alone (<= 1e-6).
  ErrorStats fromEyeDepthBeyondPlacement;
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
  std::vector<float> eyeDepthPositionRelative;  // |P - P_ref| / depth of the eye-depth reconstruction
  std::vector<float> lightingPerContribution;   // the lighting passes' error per light contribution
};

// The lighting passes' error per light contribution (FrameError::lighting.perContribution) that
// float shading and the accumulation format allow: one rounding of the sum in the format (2^-10
// fp16, 2^-23 fp32, 2^-8 rgba8), plus the Blinn-Phong lobe: x^32 turns a relative error of n.h
// into 32 times that, and n.h carries up to six float roundings (the decoded normal, V, H, the
// dot): 32 x 6 x 2^-24 = 1.14e-5 (docs/accuracy.md: what VC's near-black, specular-only pixels
// reach).
double lightingBoundPerContribution(AccumFormat format);

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
Rgba8Image positionErrorImage(const FrameError& e);  // from eye depth, relative, 1e-8 .. 1e-4
Rgba8Image lightingErrorImage(const FrameError& e);  // per light contribution, 1e-8 .. 1e-4

// The error maps under their one name (gblens error -o NAME.png, the viewer's "Reference error"
// window), with their legend for people.
struct ErrorMapDef {
  const char* name;
  const char* legend;
  Rgba8Image (*make)(const FrameError&);
};
const std::vector<ErrorMapDef>& errorMaps();

}  // namespace gb
