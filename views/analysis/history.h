// History targets checked across a sequence (`gblens history SEQ`, docs/temporal.md): a quantity the
// layout declares "history_of" X holds X one frame earlier, at the previous frame's pixels or
// reprojected into this frame's. For each pair N-1 -> N the stored history is set against what it
// could hold (X(N-1) at the same pixels, X(N-1) reprojected by depth and cameras, X one frame older,
// the previous frame's history, X(N)); the hypothesis that fits is named against the declared space.
#pragma once
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/layout.h"
#include "views/analysis/motion.h"
#include "views/capture/sequence.h"

namespace gb {

// What a history may hold, as HistoryHypothesis::name says it (the rig's truth files use the same words):
//   "previous"   X(N-1) at the same pixels (history_space previous)
//   "current"    X(N-1) reprojected into N's pixels: sampled bilinearly where N's static point was (current)
//   "stale"      X(N-2) as the declared space puts it: the history is one frame late
//   "frozen"     the previous frame's stored history: the history never updates
//   "this_frame" X(N): not delayed at all
struct HistoryHypothesis {
  std::string name;
  bool tested = false;        // the pair has what the hypothesis needs (N-2, the history of N-1)
  uint64_t pixels = 0;        // comparable pixels it was evaluated on
  double medianDifference = 0.0;  // median over the pixels of max over components |H - prediction|
  double medianRatio = 0.0;       // median of max over components |H - prediction| / bound
  bool fits = false;              // medianRatio <= 1
};

struct HistoryPair {
  int64_t previous = 0, current = 0;
  std::string history, of;        // the history quantity and the quantity it holds
  std::string declared;           // "previous" or "current" (the layout's history_space)
  std::string found;              // the hypothesis that fits alone; "none": none fits; "" undecided
  std::string undecided;          // why nothing was decided ("" when found is set)
  std::vector<HistoryHypothesis> hypotheses;
  std::vector<std::string> differences;  // found vs declared, as people say it
  uint64_t comparable = 0;        // pixels of N whose static point N-1 saw (depth, ids)
};

struct HistoryOptions {
  std::string history;  // one history quantity ("": every quantity with history_of)
  double bound = 0.0;   // absolute, in the quantity's decoded units (0: the storages' rounding)
  std::function<void(const std::string&)> progress;
};

// One pair: `before` (N-2) may be null; then "stale" is not tested. Fails only on a layout mistake
// (no such quantity), with one line.
bool checkHistoryPair(const TemporalFrame* before, const TemporalFrame& previous, const TemporalFrame& current,
                      const Quantity& history, const HistoryOptions& options, HistoryPair& out, std::string& error);
// What differs between the declared space and a found hypothesis ("the history is not reprojected").
std::vector<std::string> historyDifferences(const std::string& declared, const std::string& found);

struct HistoryTarget {
  std::string name, of, space;  // the history quantity, the quantity it holds, its declared history_space
};

struct HistoryReport {
  std::vector<HistoryTarget> histories;
  std::vector<HistoryPair> pairs;      // every history's pairs, in sequence order
  std::vector<std::string> findings;   // each once, after "NAME (history of X): "
  std::string verdict;                 // "agrees", "differs" (a finding), "undecided" (no pair decided)
};

// Loads three frames at a time. False with one line when a frame cannot be read, the layout has no
// history quantity (or not the one named), or the sequence has fewer than two frames.
bool checkHistorySequence(const Sequence& seq, const HistoryOptions& options, HistoryReport& out, std::string& error);
nlohmann::json historyReportJson(const HistoryReport& r, const std::string& sequenceDir);
std::string historyReportText(const HistoryReport& r);

}  // namespace gb
