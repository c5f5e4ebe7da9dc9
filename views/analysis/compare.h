// Comparing two captures target by target with metrics that fit each kind of data, and
// pass/warn/fail decisions with OpenImageIO idiff's semantics and exit codes
// (docs/capture-format.md, "Compare").
#pragma once
#include <nlohmann/json.hpp>

#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "renderer/core/layout.h"
#include "views/analysis/flip.h"
#include "views/capture/capture.h"

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

struct GroupResult {
  ChannelGroup group;
  std::string target;
  uint64_t pixels = 0, overWarn = 0, overFail = 0;  // pixels: those compared (normals: with a surface)
  uint64_t coverageDiffers = 0;  // normals, depths, positions: a surface in one frame only
  double maxError = 0.0, meanError = 0.0;
  Thresholds thresholds;
  Verdict verdict = Verdict::Pass;
  // With --mask: the pixels masked out (reported apart, not deciding the verdict), their count
  // over the fail threshold and their largest error; the fields above are then the unmasked ones.
  bool masked = false;
  uint64_t maskedPixels = 0, maskedOverFail = 0;
  double maskedMaxError = 0.0;
  nlohmann::json metrics;         // the kind's metrics (see name(MetricKind))
  std::vector<float> errors;      // per-pixel error (the heat map), row major
  uint32_t width = 0, height = 0;
  std::string heatmap;            // file written, if any
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
  FlipPool pool;               // with --mask: the unmasked pixels
  std::optional<double> fail, warn;
  Verdict verdict = Verdict::Pass;
  bool masked = false;
  FlipPool maskedPool;         // with --mask: the masked pixels, reported apart
  std::vector<float> errors;   // per-pixel FLIP, row major
  uint32_t width = 0, height = 0;
  std::string heatmap;         // file written, if any
};
Verdict decideFlip(const FlipResult& r);
nlohmann::json flipJson(const FlipResult& r);  // the report's entry
std::string flipText(const FlipResult& r);     // the console lines
// Writes r's map as `dir`/flip_<target>.png (magma, 0 black to 1 light yellow).
bool writeFlipMap(FlipResult& r, const std::string& dir, std::string& error);

// idiff's exit codes.
enum CompareExit { kComparePass = 0, kCompareWarn = 1, kCompareFail = 2, kCompareMismatch = 3, kCompareFileError = 4 };

struct CompareReport {
  std::string a, b;
  int exitCode = kComparePass;
  std::vector<GroupResult> groups;
  std::vector<FlipResult> flips;
  std::vector<std::pair<std::string, std::string>> mismatches;  // target, reason
  std::vector<std::pair<std::string, std::string>> skipped;     // target, reason (absent in both)
  nlohmann::json differences = nlohmann::json::array();         // manifest fields that differ
  nlohmann::json json() const;
  std::string text() const;  // the console summary
};

// Compares two loaded captures. Threshold keys that name no compared target or group are an
// error (returned in `error`, exit 4: a usage error, like idiff's).
bool compareCaptures(const Capture& a, const Capture& b, const ThresholdSettings& thresholds, CompareReport& report,
                     std::string& error);

// Adds FLIP of `final` and `hdr` to a report compareCaptures made (its exit code included).
void compareFlip(const Capture& a, const Capture& b, const FlipSettings& settings, CompareReport& report);

// The same decision for one group of errors (exposed for tests): idiff's rule.
Verdict decide(const Thresholds& t, uint64_t pixels, uint64_t overWarn, uint64_t overFail, double maxError);

// Pixels to report apart (`gblens compare --mask silhouettes,penumbra,FILE`): bit 1 silhouettes
// (primitive_id differs from a 4-neighbour's, in A or B), bit 2 the shadow penumbra band (the
// stored shadow term strictly between 0 and 1, or differing from a 4-neighbour's, in A or B, grown
// by a pixel), bit 4 a user mask image (non-zero = masked; the frame's size).
struct CompareMask {
  uint32_t width = 0, height = 0;
  std::vector<uint8_t> bits;
  std::vector<std::string> parts;  // as given
};
// False with `error` naming the part that cannot be made (no primitive_id, no shadow term, a file
// that cannot be read or has another size).
bool buildCompareMask(const Capture& a, const Capture& b, const std::string& spec, CompareMask& mask, std::string& error);
// Each full-frame group's pass/fail decided over the unmasked pixels; the masked ones counted apart
// (FLIP: pooled apart; the map itself is computed over the whole frame, its filters see every pixel).
void applyCompareMask(CompareReport& report, const CompareMask& mask);

// Writes a heat map PNG per group that differs into `dir` (created), and each FLIP map (magma) as
// flip_<target>.png; records the file names.
bool writeHeatmaps(CompareReport& report, const std::string& dir, std::string& error);

// Angle in degrees between two vectors (0 when both are zero, 180 when only one is).
double angleDegrees(const glm::dvec3& a, const glm::dvec3& b);

}  // namespace gb
