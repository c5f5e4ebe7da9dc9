// A scan of every target of a frame (gblens's own or imported) for values nobody meant to store:
// NaN, +Inf, -Inf and denormals in float channels, and decoded values outside their quantity's range
// (unorm-like quantities outside [0, 1], normals whose length is far from 1 where the layout says
// they are unit, negative or out-of-[0, 1] depth, ...). `gblens check` prints it.
#pragma once
#include <array>
#include <map>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/snapshot.h"
#include "renderer/core/surface_normals.h"

namespace gb {

enum class Anomaly : uint8_t { Nan, PosInf, NegInf, Denormal, OutOfRange };
constexpr size_t kAnomalyCount = 5;
const char* name(Anomaly a);  // "nan", "+inf", "-inf", "denormal", "out_of_range"

struct AnomalyCount {
  uint64_t count = 0;
  // The first texel found (rows from the top, each left to right), its channel and value: the stored
  // value for NaN/Inf/denormal, the decoded value checked for out of range.
  uint32_t x = 0, y = 0;
  std::string channel;
  double value = 0.0;
};

// What a kind of finding means: a fault (exit 1), a warning (reported, exit 0), or nothing (not
// reported). Classes: "nan", "inf" (+Inf and -Inf), "denormal", "out_of_range", "position" (positions
// rebuilt from depth vs a stored position target), "normal" (stored normals vs the rebuilt surface),
// "motion" (a sequence's motion vectors vs the layout's convention, temporal.h: `gblens check SEQ`),
// "history" (a sequence's history targets vs their history_of and history_space, history.h).
enum class Severity : uint8_t { Fault, Warn, Ignore };
const char* name(Severity s);
struct CheckPolicy {
  std::map<std::string, Severity> classes;                               // every quantity
  std::map<std::string, std::map<std::string, Severity>> quantities;     // nameKey(quantity) -> class -> level
  Severity at(const std::string& quantity, const std::string& cls) const;
};
// The documented default: NaN, Inf, out of range and position mismatches are faults; denormals are
// warnings (a half-float G-buffer holds true subnormals: small normal components, dark albedo).
CheckPolicy defaultCheckPolicy();
// The policy of a frame: the default, then the layout's "check" fields (whole layout, then each
// quantity), then the command line's rules ("denormal=fault", "Normal.out_of_range=warn").
bool checkPolicy(const Layout& layout, const std::vector<std::string>& rules, CheckPolicy& out, std::string& error);
const char* anomalyClass(Anomaly a);  // "nan", "inf", "inf", "denormal", "out_of_range"

// Positions rebuilt from a camera depth against the layout's stored position, at every surface pixel:
// how many are farther apart than the bound of what both storages and fp32 arithmetic allow there
// (the stored format's rounding at the stored coordinates, the depth's rounding carried through the
// camera, 16 fp32 ulps of both), and whether the camera itself looks wrong (most pixels far off).
struct PositionCheck {
  std::string depth, stored, storedFormat;  // quantity names; the stored target's format
  uint64_t pixels = 0, overBound = 0;
  double maxDistance = 0.0, maxRatio = 0.0, medianRatio = 0.0;  // distance / bound
  uint32_t x = 0, y = 0;                                       // the worst pixel
  bool cameraSuspect = false;
  Severity severity = Severity::Fault;
};
std::vector<PositionCheck> checkPositions(const FrameSnapshot& frame, const CheckPolicy& policy);

// A stored normal against the normal of the surface the camera depth rebuilds (check_normals.cpp):
// its angles as the layout decodes it, and a mistake that fits far better when one does (stored in
// the other space, a component negated, x and y swapped), or normals that point away from the eye.
struct NormalCheck {
  std::string normal, depth, declared;  // quantity names; "xyz_unorm, view space"
  AngleStats stats;                     // as declared
  std::string better;                   // "" or the mistake that fits far better ("its y negated")
  AngleStats betterStats;
  bool facesAway = false;               // most stored normals point away from the camera
  Severity severity = Severity::Fault;
  bool wrong() const { return !better.empty() || facesAway; }
};
std::vector<NormalCheck> checkNormals(const FrameSnapshot& frame, const CheckPolicy& policy);

// One quantity of one target (or a channel no quantity of the layout claims).
struct CheckRow {
  std::string target, quantity;  // the layout's names; an unclaimed channel: its channel name
  std::string kind;              // the quantity's kind ("normal", "albedo", ...), "channel" when unclaimed
  std::string range;             // what out of range means here ("[0, 1]", "|n| = 1 ± 0.001", ...; "" none)
  bool surfacesOnly = false;     // scanned only where the frame holds a surface (docs/layout-format.md)
  uint64_t texels = 0;           // texels scanned
  std::array<AnomalyCount, kAnomalyCount> found{};
  std::array<Severity, kAnomalyCount> severity{};  // the policy's level of each class here
  uint64_t total() const;
};

struct CheckReport {
  std::vector<CheckRow> rows;
  std::vector<PositionCheck> positions;
  std::vector<NormalCheck> normals;
  std::string surfaces;  // which pixels the surface-only rows cover, for people ("where Depth ...: N of M pixels")
  std::vector<std::pair<std::string, std::string>> absent;  // targets the frame does not hold, and why
  uint64_t total() const;                 // findings the policy reports (faults and warnings)
  uint64_t count(Anomaly a) const;
  uint64_t count(Severity s) const;       // findings at that level (positions: pixels over the bound)
  bool clean() const { return count(Severity::Fault) == 0; }
};

// Quantities that mean something only where a surface was drawn (albedo, normal, ...): scanned, and
// summarised by `gblens stats`, over the surface pixels only.
bool surfaceQuantity(QuantityKind k);

// Scans every texel of every target the frame holds, and cross-checks positions, under `policy`.
CheckReport checkFrame(const FrameSnapshot& frame, const CheckPolicy& policy = defaultCheckPolicy());

// The report as a table for people, and as JSON (non-finite values as the strings "nan", "inf", "-inf").
std::string checkText(const CheckReport& report);
nlohmann::json checkJson(const CheckReport& report);

}  // namespace gb
