// gblens history SEQ [--json] [--history NAME] [--bound V]: a sequence's history targets (quantities
// the layout declares "history_of" X) set against what they could hold, pair by pair, and the
// hypothesis that fits named against the declared history_space (views/analysis/history.h,
// docs/temporal.md). Exit 0: they hold what the layout says (or nothing could be decided); 1: a
// finding; 2: bad input.
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "app/cli/messages.h"
#include "views/analysis/history.h"

namespace gb {

namespace {
struct HistoryArgs {
  std::string sequence, history;
  double bound = 0.0;
  bool json = false;
};

int historyFail(const std::string& message) {
  std::fprintf(stderr, "gblens history: %s\n", oneLine(message).c_str());
  return 2;
}
}  // namespace

Command addHistoryCommand(CLI::App& root) {
  auto o = std::make_shared<HistoryArgs>();
  CLI::App* cmd = root.add_subcommand(
      "history", "check a sequence's history targets (history_of): stale, not reprojected, or this frame's value");
  cmd->add_option("SEQUENCE", o->sequence, "a sequence folder (capture --sequence, import --frames)")->required();
  cmd->add_option("--history", o->history, "the history quantity to check (default: every quantity with history_of)");
  cmd->add_option("--bound", o->bound, "the agreement bound in the quantity's units (default: the storages' rounding)")
      ->check(CLI::Range(0.0, 1e30));
  cmd->add_flag("--json", o->json, "print the report as JSON (docs/schemas/history.schema.json)");
  return {cmd, [o]() -> int {
            Sequence seq;
            std::string error;
            if (!loadSequence(o->sequence, seq, error)) return historyFail(error);
            HistoryOptions ho;
            ho.history = o->history;
            ho.bound = o->bound;
            ho.progress = terminalProgress();
            HistoryReport r;
            if (!checkHistorySequence(seq, ho, r, error)) return historyFail(error);
            if (o->json)
              std::printf("%s\n", historyReportJson(r, o->sequence).dump(2).c_str());
            else
              std::printf("sequence %s\n%s", o->sequence.c_str(), historyReportText(r).c_str());
            return r.verdict == "differs" ? 1 : 0;
          }};
}

}  // namespace gb
