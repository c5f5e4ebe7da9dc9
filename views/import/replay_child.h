// The RenderDoc replay's child process and its temporary folder, bounded: the child runs in its own
// process group, is killed with it at the time limit, when gblens is interrupted or terminated
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
  bool started = false, timedOut = false;
  int status = 0;  // waitpid's status when it ended by itself
};

// Runs argv[0] with argv (stdin /dev/null, stdout and stderr to the files), waits up to
// `timeoutSeconds`, and kills its whole process group on a time-out. `folder` is removed before
// gblens re-raises a stopping signal. False with `error` when it cannot be started.
bool runBoundedChild(const std::vector<std::string>& argv, const std::filesystem::path& stdoutFile,
                     const std::filesystem::path& stderrFile, int timeoutSeconds, ReplayFolder& folder,
                     ChildOutcome& outcome, std::string& error);

}  // namespace gb
