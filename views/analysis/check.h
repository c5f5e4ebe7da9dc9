// A scan of every target of a frame (gblens's own or imported) for values nobody meant to store:
// NaN, +Inf, -Inf and denormals in float channels, and decoded values outside their quantity's range
// (unorm-like quantities outside [0, 1], normals whose length is far from 1 where the layout says
// they are unit, negative or out-of-[0, 1] depth, ...). `gblens check` prints it.
#pragma once
#include <array>
#include <cstdint>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/snapshot.h"

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

// One quantity of one target (or a channel no quantity of the layout claims).
struct CheckRow {
  std::string target, quantity;  // the layout's names; an unclaimed channel: its channel name
  std::string kind;              // the quantity's kind ("normal", "albedo", ...), "channel" when unclaimed
  std::string range;             // what out of range means here ("[0, 1]", "|n| = 1 ± 0.001", ...; "" none)
  bool surfacesOnly = false;     // scanned only where the frame holds a surface (docs/layout-format.md)
  uint64_t texels = 0;           // texels scanned
  std::array<AnomalyCount, kAnomalyCount> found{};
  uint64_t total() const;
};

struct CheckReport {
  std::vector<CheckRow> rows;
  std::vector<std::pair<std::string, std::string>> absent;  // targets the frame does not hold, and why
  uint64_t total() const;
  uint64_t count(Anomaly a) const;
  bool clean() const { return total() == 0; }
};

// Quantities that mean something only where a surface was drawn (albedo, normal, ...): scanned, and
// summarised by `gblens stats`, over the surface pixels only.
bool surfaceQuantity(QuantityKind k);

// Scans every texel of every target the frame holds.
CheckReport checkFrame(const FrameSnapshot& frame);

// The report as a table for people, and as JSON (non-finite values as the strings "nan", "inf", "-inf").
std::string checkText(const CheckReport& report);
nlohmann::json checkJson(const CheckReport& report);

}  // namespace gb
