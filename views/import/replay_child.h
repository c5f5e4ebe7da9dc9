// The RenderDoc replay's child process and its temporary folder, bounded: the child runs in its own
// process group, is killed with it when it stops making progress or at the overall limit, when gblens is interrupted or terminated
// (SIGINT, SIGTERM, SIGHUP, SIGQUIT: the group is killed, the folder removed, then gblens ends by
// the same signal), and when gblens dies outright (the kernel kills the child: PR_SET_PDEATHSIG;
// the folder, named with gblens's process id, is removed by the next replay).
#pragma once
#include <filesystem>
#include <string>
#include <vector>

namespace gb {

// A private folder (gblens-rdc-<pid>-XXXXXX in the temporary directory), removed with its contents
// when destroyed. Creating one first removes those left by gblens processes that no longer exist.
struct ReplayFolder {
  std::filesystem::path path;  // empty when it could not be created
  ReplayFolder();
  ~ReplayFolder();
  ReplayFolder(const ReplayFolder&) = delete;
  ReplayFolder& operator=(const ReplayFolder&) = delete;
};

struct ChildOutcome {
  bool started = false;
  bool stalled = false;   // ended: no progress for a stall limit
  bool busy = false;      // ... the busy one (it used CPU time, silently)
  bool timedOut = false;  // ended: the overall limit
  int status = 0;         // waitpid's status when it ended by itself
};

// How long a child may run: while it reports progress (its stderr grows). Silent, it is ended after
// `stallSeconds` without CPU time (waiting on nothing: hung), or after `busySeconds` of working without
// a word (RenderDoc can spin in one of its threads on a broken capture; a replay step of a large
// capture on a busy machine is slow, so this one is longer); and in any case after `limitSeconds`.
struct ChildLimits {
  int stallSeconds = 30;
  int busySeconds = 120;
  int limitSeconds = 600;
};

// Runs argv[0] with argv (stdin /dev/null, stdout and stderr to the files), waits while it makes
// progress, and kills its whole process group when it stalls or runs out of time. `folder` is removed
// before gblens re-raises a stopping signal. False with `error` when it cannot be started.
bool runBoundedChild(const std::vector<std::string>& argv, const std::filesystem::path& stdoutFile,
                     const std::filesystem::path& stderrFile, const ChildLimits& limits, ReplayFolder& folder,
                     ChildOutcome& outcome, std::string& error);

}  // namespace gb
