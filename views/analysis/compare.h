// Comparing two captures target by target with metrics that fit each kind of data, and
// pass/warn/fail decisions with OpenImageIO idiff's semantics and exit codes
// (docs/capture-format.md, "Compare").
#pragma once
#include <nlohmann/json.hpp>

#include <functional>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "renderer/core/layout.h"
#include "views/analysis/flip.h"
#include "views/capture/capture.h"
#include "views/capture/image_io.h"

namespace gb {

// How a quantity is compared, and what its per-pixel error (the number thresholds apply to)
// means. Each side is decoded with its own layout (renderer/core/decode.h), so two frames that
// store a quantity differently compare by meaning; where both store it the same way the stored
// values are compared (sRGB-stored channels in stored units: one 8-bit step = 1/255).
//   Colour   max over components of |a - b| (colours, specular, shadow, scalars, vectors)
//   Normal   angle between the decoded unit normals, degrees (pixels where either frame has a surface)
//   Depth    relative error |a - b| / max(|a|, |b|): stored values, or eye depths across encodings
//   Position Euclidean length of the difference, scene units (motion: pixels)
//   Exact    max over components of |a - b| (integers: stencil, counts, ids)
enum class MetricKind { Colour, Normal, Depth, Position, Exact };
const char* name(MetricKind k);
MetricKind metricOf(QuantityKind k);

// One quantity of one target, compared as a whole. Its key is the target's name when the target
// holds one quantity, else "<target>.<quantity>" (e.g. "normal_shadow.N", "normal_shadow.Shadow").
struct ChannelGroup {
  std::string key, group;   // group: the quantity's name
  MetricKind kind = MetricKind::Colour;
  std::vector<uint32_t> channels;  // of A's target
};
std::vector<ChannelGroup> channelGroups(const Layout& layout, uint32_t target);

// idiff's thresholds; each may be set globally (key "") or per target / group key. The most
// specific setting wins: "<target>.<group>", then "<target>", then global, then idiff's default.
struct Thresholds {
  double fail = 1e-6, failPercent = 0.0, hardFail = std::numeric_limits<double>::infinity();
  double warn = 1e-6, warnPercent = 0.0;
};
struct ThresholdSettings {
  std::map<std::string, std::map<std::string, double>> byKey;  // key -> {"fail": 0.01, ...}
  // Parses "VALUE" or "KEY=VALUE" for parameter `param` ("fail", "failpercent", "hardfail",
  // "warn", "warnpercent"). False with a message on a malformed value.
  bool add(const std::string& param, const std::string& text, std::string& error);
  Thresholds resolve(const std::string& target, const std::string& key) const;
};

enum class Verdict { Pass = 0, Warn = 1, Fail = 2 };

// The pixels a figure covers: every compared pixel, or (with --mask) the unmasked pixels, which
// decide, or the masked ones, reported apart. Every figure of one line covers one set.
enum class PixelSet : uint8_t { All, Unmasked, Masked };
const char* name(PixelSet s);  // "all", "unmasked", "masked"

// A group's figures over one set of pixels.
struct GroupFigures {
  PixelSet covers = PixelSet::All;
  uint64_t pixels = 0, overWarn = 0, overFail = 0;  // pixels: those compared (normals: with a surface)
  uint64_t coverageDiffers = 0;  // normals, depths, positions: a surface in one frame only
  double maxError = 0.0, meanError = 0.0;
  nlohmann::json metrics;        // the kind's metrics (see name(MetricKind)), over the same pixels
};

struct GroupResult {
  ChannelGroup group;
  std::string target;
  Thresholds thresholds;
  Verdict verdict = Verdict::Pass;
  GroupFigures figures;             // the pixels that decide: all, or the unmasked ones with --mask
  std::vector<GroupFigures> apart;  // with --mask: the masked pixels, then all of them (deciding nothing)
  std::vector<float> errors;        // per-pixel error (the heat map), row major; NaN: not compared
  uint32_t width = 0, height = 0;
  std::string heatmap;              // file written, if any
  double seconds = 0.0;             // wall time comparing it (JUnit's time)
  const GroupFigures* figuresOver(PixelSet s) const;  // null when not computed
};

// FLIP (flip.h) of `final` (LDR-FLIP: the sRGB display output, decoded to linear) and `hdr`
// (HDR-FLIP: linear radiance) where both captures hold them at one size, pooled as the FLIP tool
// does. Thresholds apply to the mean FLIP (idiff-style: over --fail-flip fails, over --warn-flip
// warns); without them FLIP is reported and leaves the verdict alone.
struct FlipSettings {
  double ppd = flipDefaultPpd();
  std::map<std::string, double> fail, warn;  // key "" (both targets), "final" or "hdr"
  // Parses "VALUE" or "TARGET=VALUE" for `flag` ("--fail-flip", "--warn-flip"). False with a
  // message naming the flag on a malformed value or target.
  bool add(const std::string& flag, const std::string& text, std::string& error);
};
struct FlipResult {
  std::string target, method;  // "final", "ldr" / "hdr", "hdr"
  double ppd = 0.0;
  FlipExposures exposures;     // HDR-FLIP only
  PixelSet covers = PixelSet::All;  // the pixels `pool` covers (with --mask: the unmasked ones)
  FlipPool pool;               // the pixels that decide
  std::optional<double> fail, warn;
  Verdict verdict = Verdict::Pass;
  bool masked = false;
  FlipPool maskedPool, allPool;  // with --mask: the masked pixels and all of them, reported apart
  std::vector<float> errors;   // per-pixel FLIP, row major (computed over the whole frame)
  uint32_t width = 0, height = 0;
  std::string heatmap;         // file written, if any
  double seconds = 0.0;        // wall time computing it (JUnit's time)
};
Verdict decideFlip(const FlipResult& r);
nlohmann::json flipJson(const FlipResult& r);  // the report's entry
std::string flipText(const FlipResult& r);     // the console lines

// idiff's exit codes.
enum CompareExit { kComparePass = 0, kCompareWarn = 1, kCompareFail = 2, kCompareMismatch = 3, kCompareFileError = 4 };

// Pixels to report apart (`gblens compare --mask silhouettes,penumbra,FILE`): bit 1 silhouettes
// (primitive_id differs from a 4-neighbour's, in A or B), bit 2 the shadow penumbra band (the
// stored shadow term strictly between 0 and 1, or differing from a 4-neighbour's, in A or B, grown
// by a pixel), bit 4 a user mask image (non-zero = masked; the frame's size).
struct CompareMask {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> bits;
  std::vector<std::string> parts;  // as given
  uint64_t count() const;          // masked pixels
  bool empty() const { return parts.empty(); }
};
// False with `error` naming the part that cannot be made (no primitive_id, no shadow term, a file
// that cannot be read or has another size).
bool buildCompareMask(const Capture& a, const Capture& b, const std::string& spec, CompareMask& mask, std::string& error);
// The mask as an image of the frame's size: red = silhouettes, green = penumbra, blue = the mask
// file's pixels, black = unmasked (non-zero = masked: it can be given back to --mask).
Rgba8Image maskImage(const CompareMask& mask);

struct CompareReport {
  std::string a, b;
  int exitCode = kComparePass;
  std::string error;     // why the pair could not be compared (exit 4; `compare --pairs`), else ""
  double seconds = 0.0;  // wall time of the whole comparison
  std::vector<GroupResult> groups;
  std::vector<FlipResult> flips;
  std::vector<std::pair<std::string, std::string>> mismatches;  // target, reason
  std::vector<std::pair<std::string, std::string>> skipped;     // target, reason (absent in both, excluded)
  nlohmann::json differences = nlohmann::json::array();         // manifest fields both hold that differ
  // Manifest fields only one side holds (the other's source does not say them): reported apart.
  nlohmann::json onlyInA = nlohmann::json::array(), onlyInB = nlohmann::json::array();
  CompareMask mask;                                             // --mask (empty: none)
  std::string maskImage;                                        // file written, if any
  nlohmann::json json() const;
  std::string text() const;  // the console summary
};
std::string groupText(const GroupResult& g);  // a group's console lines

// What `gblens compare` (and gblens.compare in Python) is asked to do.
struct CompareSettings {
  ThresholdSettings thresholds;
  FlipSettings flip;
  bool flipOn = true;                 // --flip on|off: FLIP of final and hdr
  std::string mask;                   // --mask spec ("": none)
  std::vector<std::string> exclude;   // --exclude TARGET: left out, listed as skipped
  // Progress (fraction done, what is being compared); null: silent. The CLI prints it on stderr.
  std::function<void(double, const std::string&)> progress;
};

// Compares two loaded captures: the mask first (a part that cannot be made fails before any work),
// then every group, then FLIP. Threshold keys or --exclude names that name no target are an error
// (returned in `error`, exit 4: a usage error, like idiff's).
bool compare(const Capture& a, const Capture& b, const CompareSettings& settings, CompareReport& report,
             std::string& error);
// The same without mask, FLIP or progress (the viewer's summary).
bool compareCaptures(const Capture& a, const Capture& b, const ThresholdSettings& thresholds, CompareReport& report,
                     std::string& error);

// Adds FLIP of `final` and `hdr` to a report (its exit code included), pooled apart over the
// report's mask (compare() calls it with --flip on).
void compareFlip(const Capture& a, const Capture& b, const FlipSettings& settings, CompareReport& report);

// The same decision for one group of errors (exposed for tests): idiff's rule.
Verdict decide(const Thresholds& t, uint64_t pixels, uint64_t overWarn, uint64_t overFail, double maxError);

// A group's heat map with its legend below (black = equal or not compared, blue -> red = 0 -> the
// largest finite error, white = infinite), and a FLIP map (magma, 0 to 1) with its legend. The map
// is the image's top-left width x height pixels; the legend strip below it makes the image at least
// kLegendMinWidth wide, and its bar and labels span at most kLegendMaxWidth from the left. Empty with
// `error` when the legend cannot be drawn (no font).
constexpr uint32_t kLegendMinWidth = 360, kLegendMaxWidth = 720, kLegendHeight = 34;
Rgba8Image heatmapImage(const GroupResult& g, std::string& error);
// What a group's per-pixel error is measured in (the heat map's and the report's legends).
std::string errorUnit(const GroupResult& g);
// |a - b| as compare measures it per component: 0 for two NaNs or equal infinities, infinite for
// NaN against a number (the report's page repeats this rule).
double absDifference(double a, double b);
Rgba8Image flipMapImage(const FlipResult& r, std::string& error);

// Writes into `dir` (created): a heat map with legend per compared group (<key>.png, every group,
// equal or not), each FLIP map (flip_<target>.png) and the mask (mask.png, with --mask); records
// the file names in the report.
bool writeCompareImages(CompareReport& report, const std::string& dir, std::string& error);
// The file name a group key is written under (one place, so every writer agrees); "" when the key
// could not be a file name (a layout's quantity name with a '/').
std::string compareFileName(const std::string& key, const std::string& suffix);

// Angle in degrees between two vectors (0 when both are zero, 180 when only one is).
double angleDegrees(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace gb
