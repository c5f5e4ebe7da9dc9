// The bounded replay child of replay_child.h: fork + exec into its own process group with
// PR_SET_PDEATHSIG, a wait loop with a deadline, and stop signals that take the child with gblens.
#include "views/import/replay_child.h"

#include <fcntl.h>
#include <signal.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <thread>

extern char** environ;

namespace gb {

namespace fs = std::filesystem;

namespace {

const char kPrefix[] = "gblens-rdc-";
const int kStopSignals[] = {SIGINT, SIGTERM, SIGHUP, SIGQUIT};

volatile sig_atomic_t gChildGroup = 0;  // the running child's process group (0: none)
volatile sig_atomic_t gStopSignal = 0;  // a stop signal that arrived while it ran

void onStop(int sig) {
  // Only async-signal-safe calls here: the wait loop does the rest.
  if (gChildGroup > 0) kill(-pid_t(gChildGroup), SIGKILL);
  gStopSignal = sig;
}

// Folders of gblens processes that are gone (killed outright while a replay ran).
void removeStaleFolders() {
  std::error_code ec;
  for (const auto& e : fs::directory_iterator(fs::temp_directory_path(ec), ec)) {
    const std::string name = e.path().filename().string();
    if (name.rfind(kPrefix, 0) != 0) continue;
    char* end = nullptr;
    const long pid = std::strtol(name.c_str() + sizeof(kPrefix) - 1, &end, 10);
    if (pid <= 0 || *end != '-' || pid == long(getpid())) continue;
    if (kill(pid_t(pid), 0) == -1 && errno == ESRCH) fs::remove_all(e.path(), ec);
  }
}

}  // namespace

ReplayFolder::ReplayFolder() {
  removeStaleFolders();
  std::error_code ec;
  std::string pattern = (fs::temp_directory_path(ec) / (kPrefix + std::to_string(getpid()) + "-XXXXXX")).string();
  if (mkdtemp(pattern.data())) path = pattern;
}

ReplayFolder::~ReplayFolder() {
  std::error_code ec;
  if (!path.empty()) fs::remove_all(path, ec);
}

bool runBoundedChild(const std::vector<std::string>& args, const fs::path& stdoutFile, const fs::path& stderrFile,
                     int timeoutSeconds, ReplayFolder& folder, ChildOutcome& outcome, std::string& error) {
  // Everything the child needs is prepared before fork (only async-signal-safe calls after it).
  std::vector<std::string> argv = args;
  std::vector<char*> cargv;
  for (std::string& a : argv) cargv.push_back(a.data());
  cargv.push_back(nullptr);
  const std::string out = stdoutFile.string(), err = stderrFile.string();
  const pid_t parent = getpid();

  struct sigaction stop {}, previous[4];
  stop.sa_handler = onStop;
  sigemptyset(&stop.sa_mask);
  gStopSignal = 0;
  for (int i = 0; i < 4; ++i) sigaction(kStopSignals[i], &stop, &previous[i]);
  auto restoreSignals = [&] {
    gChildGroup = 0;
    for (int i = 0; i < 4; ++i) sigaction(kStopSignals[i], &previous[i], nullptr);
  };

  const pid_t pid = fork();
  if (pid == 0) {
    setpgid(0, 0);                      // its own group: a time-out or a stop ends all of it
    prctl(PR_SET_PDEATHSIG, SIGKILL);   // and so does gblens's death
    if (getppid() != parent) _exit(127);
    const int in = open("/dev/null", O_RDONLY), o = open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600),
              e = open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    if (in < 0 || o < 0 || e < 0 || dup2(in, 0) < 0 || dup2(o, 1) < 0 || dup2(e, 2) < 0) _exit(127);
    struct sigaction deflt {};
    deflt.sa_handler = SIG_DFL;
    for (int s : kStopSignals) sigaction(s, &deflt, nullptr);
    execve(cargv[0], cargv.data(), environ);
    _exit(127);
  }
  if (pid < 0) {
    restoreSignals();
    error = "cannot run " + args[0] + ": " + std::strerror(errno);
    return false;
  }
  setpgid(pid, pid);  // also here, so that the group exists before any kill below
  gChildGroup = pid;
  outcome.started = true;

  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(timeoutSeconds);
  int status = 0;
  while (waitpid(pid, &status, WNOHANG) == 0) {
    if (gStopSignal || std::chrono::steady_clock::now() > deadline) {
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      outcome.timedOut = !gStopSignal;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  kill(-pid, SIGKILL);  // whatever the child started and left running
  outcome.status = status;
  const int stopped = gStopSignal;
  restoreSignals();
  if (stopped) {
    // gblens was told to stop: the child is gone; remove the folder, then stop as asked.
    std::error_code ec;
    fs::remove_all(folder.path, ec);
    folder.path.clear();
    raise(stopped);
  }
  return true;
}

}  // namespace gb
