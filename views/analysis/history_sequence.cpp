// History targets across a sequence (history.h): every quantity with history_of checked pair by pair,
// three frames in memory at a time, summed up as one verdict; the report as JSON and text.
#include <algorithm>
#include <cstdio>
#include <deque>
#include <memory>

#include "views/analysis/history.h"

namespace gb {

namespace {

struct HistoryFrame {
  std::shared_ptr<Capture> capture;
  TemporalFrame frame;
};

bool loadHistoryFrame(const Sequence& seq, size_t i, HistoryFrame& out, std::string& error) {
  out.capture = std::make_shared<Capture>();
  if (!loadCapture(seq.captureDir(i), *out.capture, error)) return false;
  out.frame.frame = &out.capture->frame;
  out.frame.number = seq.frames[i].number;
  out.frame.time = seq.frames[i].time;
  out.frame.jitter = seq.frames[i].jitter;
  return true;
}

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
  if (seq.frames.size() < 2) {
    error = seq.dir + ": history needs two frames at least (the sequence has " + std::to_string(seq.frames.size()) + ")";
    return false;
  }
  std::deque<HistoryFrame> window;
  bool anyDecided = false;
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    HistoryFrame f;
    if (!loadHistoryFrame(seq, i, f, error)) return false;
    window.push_back(std::move(f));
    if (window.size() > 3) window.pop_front();
    if (i == 0) {
      if (!historyTargets(window.back().frame.frame->layout, o.history, out.histories, error)) {
        error = seq.captureDir(i) + ": " + error;
        return false;
      }
      continue;
    }
    if (o.progress)
      o.progress("frames " + std::to_string(seq.frames[i - 1].number) + " -> " + std::to_string(seq.frames[i].number));
    const TemporalFrame& cur = window.back().frame;
    const TemporalFrame& prev = window[window.size() - 2].frame;
    const TemporalFrame* before = window.size() == 3 ? &window[0].frame : nullptr;
    for (const HistoryTarget& t : out.histories) {
      const Quantity* q = cur.frame->layout.findByName(t.name);
      if (!q || q->historyOf.empty()) {
        error = seq.captureDir(i) + ": no history quantity " + t.name;
        return false;
      }
      HistoryPair p;
      if (!checkHistoryPair(before, prev, cur, *q, o, p, error)) {
        error = seq.dir + ": " + error;
        return false;
      }
      anyDecided = anyDecided || !p.found.empty();
      for (const std::string& d : p.differences) {
        const std::string s = t.name + " (history of " + t.of + "): " + d;
        if (std::find(out.findings.begin(), out.findings.end(), s) == out.findings.end()) out.findings.push_back(s);
      }
      out.pairs.push_back(std::move(p));
    }
  }
  out.verdict = !out.findings.empty() ? "differs" : anyDecided ? "agrees" : "undecided";
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
