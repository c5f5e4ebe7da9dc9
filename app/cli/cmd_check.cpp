// gblens check CAPTURE [--json] [--policy RULE]...: every target and quantity of a capture (gblens's own
// or imported) scanned for NaN, ±Inf, denormals and out-of-range decoded values, and positions rebuilt
// from depth checked against a stored position (views/analysis/check.h). What is a fault comes from the
// policy (default, the layout's "check" fields, --policy). A sequence: every frame, then the temporal
// classes (motion vectors vs the layout's convention, history targets vs their history_of). Exit 0 no
// fault, 1 faults, 2 unreadable.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "views/analysis/check.h"
#include "views/analysis/history.h"
#include "views/analysis/temporal.h"
#include "views/capture/capture.h"
#include "views/capture/sequence.h"

namespace gb {

namespace {
struct CheckArgs {
  std::string capture;
  bool json = false;
  std::vector<std::string> policy;
};
}  // namespace

// The temporal class history: every history target against its history_of (history.h), a fault by
// default ("history=warn" lowers it, per quantity too: "hist.history=warn").
bool checkSequenceHistory(const Sequence& seq, const CheckArgs& o, const CheckPolicy& policy, nlohmann::json& temporal,
                          std::string& text, bool& clean) {
  HistoryReport r;
  std::string error;
  if (!checkHistorySequence(seq, {}, r, error)) {
    std::fprintf(stderr, "gblens check: %s\n", error.c_str());
    return false;
  }
  Severity level = Severity::Ignore;  // the highest of the histories' levels
  for (const HistoryTarget& t : r.histories) level = std::min(level, policy.at(t.name, "history"));
  bool faulted = false;
  for (const HistoryPair& p : r.pairs)
    faulted = faulted || (!p.differences.empty() && policy.at(p.history, "history") == Severity::Fault);
  if (faulted) clean = false;
  temporal["history"] = historyReportJson(r, o.capture);
  temporal["history_severity"] = name(level);
  if (level != Severity::Ignore) text += "temporal, history (a finding is a " + std::string(name(level)) + "):\n" + historyReportText(r);
  return true;
}

// A sequence: every frame checked as a capture is, then the temporal classes: its motion vectors
// against the layout's convention (temporal.h) and its history targets (history.h), faults by default
// ("motion=warn", "history=warn" lower them).
int checkSequence(const CheckArgs& o) {
  Sequence seq;
  std::string error;
  if (!loadSequence(o.capture, seq, error)) {
    std::fprintf(stderr, "gblens check: %s\n", error.c_str());
    return 2;
  }
  nlohmann::json frames = nlohmann::json::array();
  bool clean = true;
  std::string text;
  CheckPolicy policy;
  Layout layout;  // the first frame's: which temporal classes apply
  for (size_t i = 0; i < seq.frames.size(); ++i) {
    Capture c;
    if (!loadCapture(seq.captureDir(i), c, error) || (i == 0 && !checkPolicy(c.frame.layout, o.policy, policy, error))) {
      std::fprintf(stderr, "gblens check: %s\n", error.c_str());
      return 2;
    }
    if (i == 0) layout = c.frame.layout;
    const CheckReport report = checkFrame(c.frame, policy);
    clean = clean && report.clean();
    frames.push_back({{"frame", seq.frames[i].number}, {"check", checkJson(report)}});
    text += "frame " + std::to_string(seq.frames[i].number) + ": " +
            (report.total() == 0 ? std::string("clean") : std::to_string(report.total()) + " findings") + "\n";
    if (report.total()) text += checkText(report);
  }
  nlohmann::json temporal = nlohmann::json();
  const Quantity* motion = layout.find(QuantityKind::Motion);
  if (motion && seq.frames.size() >= 2) {
    MotionReport r;
    if (!checkMotionSequence(seq, {}, r, error)) {
      std::fprintf(stderr, "gblens check: %s\n", error.c_str());
      return 2;
    }
    const Severity level = policy.at(motion->name, "motion");
    if (r.verdict == "differs" && level == Severity::Fault) clean = false;
    temporal = {{"motion", motionReportJson(r, o.capture)}, {"motion_severity", name(level)}};
    if (level != Severity::Ignore) text += "temporal, motion (a finding is a " + std::string(name(level)) + "):\n" + motionReportText(r);
  } else {
    text += "temporal: " + std::string(motion ? "one frame: no pair to check" : "the layout has no motion quantity") + "\n";
  }
  const bool histories = std::any_of(layout.quantities.begin(), layout.quantities.end(),
                                     [](const Quantity& q) { return !q.historyOf.empty(); });
  if (histories && seq.frames.size() >= 2) {
    if (temporal.is_null()) temporal = nlohmann::json::object();
    if (!checkSequenceHistory(seq, o, policy, temporal, text, clean)) return 2;
  }
  if (o.json)
    std::printf("%s\n", nlohmann::json({{"format", "gblens-check-sequence"}, {"version", 1}, {"sequence", o.capture},
                                        {"frames", frames}, {"temporal", temporal}}).dump(2).c_str());
  else
    std::printf("sequence %s\n%s", o.capture.c_str(), text.c_str());
  return clean ? 0 : 1;
}

Command addCheckCommand(CLI::App& root) {
  auto o = std::make_shared<CheckArgs>();
  CLI::App* cmd = root.add_subcommand(
      "check", "scan every target of a capture for NaN, Inf, denormals and out-of-range values (exit 1 when found)");
  cmd->add_option("CAPTURE", o->capture, "capture directory (gblens capture or gblens import), or a sequence (every frame, then its motion vectors and history targets)")->required();
  cmd->add_flag("--json", o->json, "print the report as JSON");
  cmd->add_option("--policy", o->policy,
                  "[QUANTITY.]CLASS=LEVEL: what a finding means (CLASS nan, inf, denormal, out_of_range, position, normal, motion, history; LEVEL "
                  "fault, warn, ignore); default: denormal=warn, the rest fault; the layout's \"check\" fields apply first")
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  return {cmd, [o]() -> int {
            if (isSequence(o->capture)) return checkSequence(*o);
            Capture c;
            std::string error;
            if (!loadCapture(o->capture, c, error)) {
              std::fprintf(stderr, "gblens check: %s\n", error.c_str());
              return 2;
            }
            CheckPolicy policy;
            if (!checkPolicy(c.frame.layout, o->policy, policy, error)) {
              std::fprintf(stderr, "gblens check: %s\n", error.c_str());
              return 2;
            }
            const CheckReport report = checkFrame(c.frame, policy);
            if (o->json)
              std::printf("%s\n", checkJson(report).dump(2).c_str());
            else
              std::printf("capture %s\n%s", o->capture.c_str(), checkText(report).c_str());
            return report.clean() ? 0 : 1;
          }};
}

}  // namespace gb
