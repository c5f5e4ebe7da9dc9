// The pixel probe: everything about one pixel of a frame, computed from a FrameSnapshot alone
// (a live frame in the viewer, a capture in `gblens probe`): raw stored values of every
// target, decoded G-buffer quantities, the eye/world position reconstructed both ways, the
// shadow-map texels the pixel sampled, every point light whose volume covers the pixel with its
// contribution, and the final colour.
//
// Region read-back (the viewer): the probe reads only
//   - the texel (x, y) of every screen-space target (a 1x1 TargetImage at x0 = x, y0 = y is
//     enough), and
//   - the 2x2 shadow-map block returned by shadowMapFootprint() (a 2x2 TargetImage there).
// Anything not in the snapshot is reported as missing, never guessed.
#pragma once
#include <nlohmann/json.hpp>

#include <optional>
#include <string>
#include <vector>

#include "renderer/core/snapshot.h"

namespace gb {

struct ProbeChannel {
  std::string name;       // e.g. "N.X"
  uint32_t bits = 0;      // the stored bits (8/16-bit integer, half bits, float bits, uint)
  double value = 0.0;     // decoded (CpuImage::value)
};
struct ProbeTarget {
  std::string target, type, encoding;  // "normal_shadow", "f16", "float"
  bool present = false;
  std::string absent;                  // why not (not computed, not read back, ...)
  std::vector<ProbeChannel> channels;
  // A multisampled target: every sample's channels (channels are sample 0's), and per channel the
  // spread of the decoded values (largest minus smallest) over the samples.
  std::vector<std::vector<ProbeChannel>> samples;
  std::vector<double> spread;
};

// One quantity of the frame's layout at the pixel, decoded (renderer/core/decode.h): what the
// probe shows for any G-buffer, gblens's own or imported.
struct ProbeQuantity {
  std::string name, kind, target;  // "Normal", "normal", "normal_shadow"
  std::string encoding;            // "octahedral (view space)", "hardware", "srgb", ...
  std::string space;               // what the values are: "linear", "view", "world (layout: Z-up)", "eye depth", ...
  bool present = false;            // the frame holds the texel
  // Decoded as the views show them (visualize.h viewValue): colours linear, normals unit in their own
  // space, depths as stored (hardware) or in their units (eye, radial), positions in their own space,
  // integers; empty where nothing was drawn (note says so).
  std::vector<double> values;
  std::optional<double> eyeDepth;  // depths: the eye depth they give
  std::string note;                // an id's name, stencil bits set, "no surface", a normal's length error
  // Its target multisampled: each sample decoded as `values` is (sample 0's), with its note.
  std::vector<std::vector<double>> sampleValues;
  std::vector<std::string> sampleNotes;
};

// A position the layout lets the probe reconstruct (from each depth quantity) or read (stored).
struct ProbeReconstruction {
  std::string quantity, method;    // "Depth", "eye depth" | "hardware depth" | "radial distance" | "stored"
  bool valid = false;
  glm::dvec3 eye{0.0};
  glm::dvec3 world{0.0};           // in the layout's own world axes (worldSpace says which is up)
  std::string worldSpace;          // "world (layout: Z-up)"
  bool hasStored = false;          // the layout stores a position: the difference to it
  double toStored = 0.0;           // scene units
  double toStoredUlps = 0.0;       // in ulps of the stored position's format at its largest coordinate
  std::string ulpOf;               // that format's channel type ("f16", "f32", ...)
};

struct ProbePosition {
  bool valid = false;
  glm::dvec3 eye{0.0}, world{0.0};
};

struct ProbeShadow {
  bool valid = false;
  std::string note;               // why not valid, or a remark
  glm::dvec3 lightClip{0.0};      // receiver in the sun's clip space (from the reconstructed position)
  double receiverDepth = 0.0;     // lightClip.z: what the compare uses
  glm::dvec2 texel{0.0};          // continuous texel coordinates of the sample (u * size - 0.5)
  int32_t x0 = 0, y0 = 0;         // top-left texel of the 2x2 bilinear footprint
  double stored[4] = {};          // stored depths (x0,y0), (x0+1,y0), (x0,y0+1), (x0+1,y0+1); border = 1
  double weight[4] = {};          // bilinear weights
  bool lit[4] = {};               // receiver <= stored (VK_COMPARE_OP_LESS_OR_EQUAL)
  bool outside[4] = {};           // beyond the map: the border colour (lit)
  double filtered = 0.0;          // sum of weight * lit: the expected shadow term
  double storedShadow = 0.0;      // what the G-buffer stored (normal_shadow.Shadow)
  double nearestMargin = 0.0;     // stored - receiver at the nearest texel (> 0: lit)
  float biasConstant = 0, biasSlope = 0, biasClamp = 0;  // applied when the map was rendered
};

struct ProbeLight {
  uint32_t index = 0;
  std::string lightClass;            // "stencil" or "near_plane" (the light is drawn)
  glm::dvec3 eyePosition{0.0}, color{0.0};
  double radius = 0.0;
  double enter = 0.0, exit = 0.0;    // eye depth where the pixel's ray enters / leaves the volume
  double distance = 0.0;             // surface point to light centre
  double attenuation = 0.0;
  glm::dvec3 contribution{0.0};      // to hdr (shading.h, double, from the stored G-buffer)
  bool stencilPass = false;          // the stencil/depth tests let the light's shader run here
};

// "Why is this pixel lit — or not": one entry per light that could matter at the pixel (the sun,
// and point lights near the surface point, drawn or culled), with the rule that decided its fate.
struct LedgerEntry {
  std::string light;          // "sun" or "point"
  uint32_t index = 0;         // point: the scene's light index
  // shaded, lit (sun), shadowed (sun), facing_away, out_of_range, volume_misses, stencil_test,
  // frustum_culled, sub_pixel, empty, no_sun
  std::string fate;
  std::string why;            // the rule, with this pixel's numbers
  std::string drawnAs;        // how the method drew it: "stencil class", "near-plane class", "tile (3, 2)", ...
  double distance = 0.0, radius = 0.0;  // surface point to the light's centre; its radius
  double nDotL = 0.0;
  glm::dvec3 contribution{0.0};
};
struct LightLedger {
  std::vector<LedgerEntry> entries;  // by contribution (luminance), then distance / radius
  std::string rule;                  // which lights are listed
  uint64_t notListed = 0;            // point lights farther than the rule
};

struct PixelDossier {
  uint32_t x = 0, y = 0, width = 0, height = 0;
  // The frame's layout is gblens's own: the sections about gblens's frame (its decoded G-buffer, both
  // reconstructions, shadow map, hdr and final) mean something. Other layouts get their quantities only.
  bool native = false;
  std::string error;  // non-empty: the pixel could not be probed (outside the frame)
  std::vector<std::string> missing;  // data the probe needed but the snapshot lacks
  std::vector<ProbeTarget> targets;  // raw values, every target (shadow map: see `shadow`)
  std::vector<ProbeQuantity> quantities;          // every quantity of the layout, decoded
  std::vector<ProbeReconstruction> reconstructions;  // every position the layout allows

  // Decoded G-buffer (each valid only with its target: has* say which were available).
  bool hasAlbedo = false, hasNormal = false, hasEyeDepth = false, hasHardwareDepth = false;
  bool hasSpecular = false, hasShadow = false, hasStencil = false;
  bool geometry = false;
  glm::dvec3 albedo{0.0};
  double specular = 0.0;
  glm::dvec3 normal{0.0}, normalStored{0.0};
  double normalLengthError = 0.0;  // | |stored| - 1 |
  bool unlit = false;              // the texel marks an unlit surface (KHR_materials_unlit): no normal
  double shadow = 0.0;
  double eyeDepth = 0.0;           // depth.Z
  double hardwareDepth = 0.0;      // depth_stencil.Depth
  uint32_t stencil = 0;

  // Positions, both ways, and how far apart.
  ProbePosition fromEyeDepth, fromHardwareDepth;
  std::string positionSource;      // which one the lighting passes used ("eye_depth" / "hardware_depth")
  double positionDifference = 0.0; // scene units
  double eyeDepthUlps = 0.0;       // |z difference| in float ulps of the eye depth
  double hardwareDepthUlps = 0.0;  // |stored depth - depth of the eye-depth position| in float ulps

  ProbeShadow shadowMap;

  // Lighting (evaluated for gblens's frames and layouts whose lights use gblens's model).
  std::string lightingNote;        // why lights were not evaluated ("" when they were)
  glm::dvec3 viewDirection{0.0};   // V (unit, toward the eye)
  glm::dvec3 directional{0.0};     // sun + ambient (shading.h)
  std::vector<ProbeLight> lights;  // every drawn light whose volume the pixel's ray meets
  glm::dvec3 pointLightTotal{0.0}; // sum of the contributions of lights that passed the stencil
  uint32_t shadedLights = 0;       // lights predicted to run their shader here
  LightLedger ledger;              // every light that could matter, and why it does or does not
  int64_t coverageMasked = -1, coverageFull = -1;  // the targets' counts (-1: not available)
  bool hasHdr = false, hasFinal = false;
  glm::dvec4 hdr{0.0};             // stored
  glm::dvec3 hdrExpected{0.0};     // directional + point-light total (fairy sprites not included)
  glm::dvec4 finalColor{0.0};      // stored, decoded to linear
  glm::dvec3 finalExpected{0.0};   // toneMap(stored hdr, exposure), linear
  glm::uvec3 finalExpectedSrgb8{0}; // the same, encoded as the final target stores it
};

// The 2x2 shadow-map block the probe of (x, y) reads (for region read-back): false when the
// pixel has no geometry or the snapshot lacks the depth targets it needs to place it.
bool shadowMapFootprint(const FrameSnapshot& frame, uint32_t x, uint32_t y, int32_t& x0, int32_t& y0);

// The dossier of pixel (x, y) (target coordinates, top-left origin).
PixelDossier probePixel(const FrameSnapshot& frame, uint32_t x, uint32_t y);

// The dossier as JSON (`gblens probe --json`, the viewer's "copy as JSON", --probe-log) and as
// the text `gblens probe` prints. The JSON is an interface (docs/schemas/probe.schema.json,
// "format": "gblens-probe", kProbeJsonVersion): every key is present for every layout, null where
// the frame does not hold it; a change of shape bumps the version.
constexpr int kProbeJsonVersion = 3;
nlohmann::json dossierJson(const PixelDossier& d);
std::string dossierText(const PixelDossier& d);

}  // namespace gb
