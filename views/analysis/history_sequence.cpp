// History targets across a sequence (history.h): every quantity with history_of checked pair by pair,
// three frames in memory at a time, summed up as one verdict; the report as JSON and text.
#include <algorithm>
#include <cstdio>

#include "views/analysis/history.h"
#include "views/analysis/temporal.h"

namespace gb {

namespace {

// The history quantities of a layout (or the one named), or why none.
bool historyTargets(const Layout& l, const std::string& named, std::vector<HistoryTarget>& out, std::string& error) {
  for (const Quantity& q : l.quantities)
    if (!q.historyOf.empty() && (named.empty() || q.name == named))
      out.push_back({q.name, q.historyOf, q.historyCurrent ? "current" : "previous"});
  if (!out.empty()) return true;
  if (named.empty()) error = "the layout has no history quantity (none declares \"history_of\")";
  else if (l.findByName(named)) error = "--history " + named + ": not a history (its quantity has no \"history_of\")";
  else error = "--history " + named + ": not a quantity of the layout";
  return false;
}

}  // namespace

bool checkHistorySequence(const Sequence& seq, const HistoryOptions& o, HistoryReport& out, std::string& error) {
  out = HistoryReport{};
  bool anyDecided = false;
  const bool ok = walkFramePairs(seq, "history", [&](size_t i, const TemporalFrame* before, const TemporalFrame* prev,
                                          const TemporalFrame& cur, std::string& why) {
    if (!prev) {
      if (!historyTargets(cur.frame->layout, o.history, out.histories, why)) {
        why = seq.captureDir(i) + ": " + why;
        return false;
      }
      return true;
    }
    if (o.progress) o.progress("frames " + std::to_string(prev->number) + " -> " + std::to_string(cur.number));
    for (const HistoryTarget& t : out.histories) {
      const Quantity* q = cur.frame->layout.findByName(t.name);
      if (!q || q->historyOf.empty()) {
        why = seq.captureDir(i) + ": no history quantity " + t.name;
        return false;
      }
      HistoryPair p;
      if (!checkHistoryPair(before, *prev, cur, *q, o, p, why)) {
        why = seq.dir + ": " + why;
        return false;
      }
      anyDecided = anyDecided || !p.found.empty();
      for (const std::string& d : p.differences) addFindingOnce(out.findings, t.name + " (history of " + t.of + "): " + d);
      out.pairs.push_back(std::move(p));
    }
    return true;
  }, error);
  if (!ok) return false;
  out.verdict = sequenceVerdict(out.findings, anyDecided);
  return true;
}

nlohmann::json historyReportJson(const HistoryReport& r, const std::string& dir) {
  nlohmann::json histories = nlohmann::json::array(), pairs = nlohmann::json::array();
  for (const HistoryTarget& t : r.histories)
    histories.push_back({{"name", t.name}, {"history_of", t.of}, {"history_space", t.space}});
  for (const HistoryPair& p : r.pairs) {
    nlohmann::json hyps = nlohmann::json::object();
    for (const HistoryHypothesis& h : p.hypotheses)
      hyps[h.name] = {{"tested", h.tested},
                      {"pixels", h.pixels},
                      {"median_difference", h.tested ? nlohmann::json(h.medianDifference) : nlohmann::json()},
                      {"median_ratio", h.tested ? nlohmann::json(h.medianRatio) : nlohmann::json()},
                      {"fits", h.fits}};
    pairs.push_back({{"previous", p.previous},
                     {"current", p.current},
                     {"history", p.history},
                     {"history_of", p.of},
                     {"declared", p.declared},
                     {"found", p.found.empty() ? nlohmann::json() : nlohmann::json(p.found)},
                     {"undecided", p.undecided.empty() ? nlohmann::json() : nlohmann::json(p.undecided)},
                     {"comparable_pixels", p.comparable},
                     {"differences", p.differences},
                     {"hypotheses", hyps}});
  }
  return {{"format", "gblens-history"}, {"version", 1},           {"sequence", dir}, {"histories", histories},
          {"verdict", r.verdict},       {"findings", r.findings}, {"pairs", pairs}};
}

std::string historyReportText(const HistoryReport& r) {
  std::string s;
  for (const HistoryTarget& t : r.histories) s += "history " + t.name + ": of " + t.of + ", history_space " + t.space + "\n";
  char line[256];
  for (const HistoryPair& p : r.pairs) {
    std::snprintf(line, sizeof line, "frames %lld -> %lld, %s: %llu comparable pixels;", (long long)p.previous,
                  (long long)p.current, p.history.c_str(), (unsigned long long)p.comparable);
    s += line;
    for (const HistoryHypothesis& h : p.hypotheses) {
      if (!h.tested) {
        s += " " + h.name + " -";
        continue;
      }
      std::snprintf(line, sizeof line, " %s %.3g (x%.3g%s)", h.name.c_str(), h.medianDifference, h.medianRatio,
                    h.fits ? ", fits" : "");
      s += line;
    }
    s += "\n  " + (p.found.empty() ? "undecided (" + p.undecided + ")" : "holds: " + p.found) + "\n";
    for (const std::string& d : p.differences) s += "  DIFFERS: " + d + "\n";
  }
  s += "verdict: " + r.verdict;
  if (r.verdict == "agrees") s += " (every history holds what its layout declares)";
  s += "\n";
  for (const std::string& f : r.findings) s += "  " + f + "\n";
  return s;
}

}  // namespace gb
