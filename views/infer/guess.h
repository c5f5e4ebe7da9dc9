// What a draft says about each quantity it guessed: the quantity decided (or "unknown"), the evidence
// that decided it, a confidence, and the hypotheses the evidence rejected, written into the draft as
// the quantity's "guess" object (docs/import.md "How gblens decides"). Below kDecide a channel group
// is drafted as stored values, never as a quantity the evidence does not carry.
#pragma once
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

namespace gb {

// The confidence a guess needs to be drafted as its quantity (else: unknown, shown as stored).
constexpr double kDecide = 0.5;

struct Rejected {
  std::string hypothesis;  // "normal (view space)", "position"
  std::string evidence;    // "angle to the rebuilt surface: median 71°"
};

struct Guess {
  std::string quantity = "unknown";  // a layout quantity kind, or "unknown"
  std::string evidence;
  double confidence = 0.0;           // 0..1: 1 - (the evidence for it) / (the evidence for the next best)
  std::vector<Rejected> rejected;
  std::vector<std::string> undecided;  // fields the evidence did not decide (the draft holds a default)
  nlohmann::json json() const;
  bool decided() const { return quantity != "unknown" && confidence >= kDecide; }
};

// A confidence from a score (lower is better) and the next best hypothesis's: 1 - best / next,
// clamped to [0, 1] (equal scores: 0; the next best far worse: near 1).
double marginConfidence(double best, double next);

}  // namespace gb
