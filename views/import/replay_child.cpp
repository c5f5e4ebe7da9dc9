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
#include <fstream>
#include <sstream>
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

namespace {

// CPU time (clock ticks) the process and its waited-for children used: /proc/PID/stat's utime,
// stime, cutime, cstime (fields 14-17); 0 when it cannot be read.
unsigned long long cpuTicks(pid_t pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t close = text.rfind(')');  // the command name may hold spaces
  if (close == std::string::npos) return 0;
  std::istringstream fields(text.substr(close + 2));
  std::string f;
  unsigned long long sum = 0;
  for (int i = 3; i <= 17 && fields >> f; ++i)
    if (i >= 14) sum += std::strtoull(f.c_str(), nullptr, 10);
  return sum;
}

uintmax_t fileSize(const fs::path& p) {
  std::error_code ec;
  const uintmax_t n = fs::file_size(p, ec);
  return ec ? 0 : n;
}

}  // namespace

bool runBoundedChild(const std::vector<std::string>& args, const fs::path& stdoutFile, const fs::path& stderrFile,
                     const ChildLimits& limits, ReplayFolder& folder, ChildOutcome& outcome, std::string& error) {
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

  const auto start = std::chrono::steady_clock::now();
  const auto deadline = start + std::chrono::seconds(limits.limitSeconds);
  auto lastWord = start, lastWork = start;
  unsigned long long ticks = 0;
  uintmax_t logged = 0;
  int status = 0;
  for (int poll = 0; waitpid(pid, &status, WNOHANG) == 0; ++poll) {
    const auto now = std::chrono::steady_clock::now();
    if (poll % 10 == 0) {  // every 0.2 s: has it printed, or worked, since?
      const unsigned long long t = cpuTicks(pid);
      const uintmax_t n = fileSize(stderrFile);
      if (n > logged) lastWord = lastWork = now;
      if (t > ticks + 2) lastWork = now;
      ticks = std::max(ticks, t), logged = std::max(logged, n);
    }
    const bool idle = now - lastWork > std::chrono::seconds(limits.stallSeconds);
    const bool busy = now - lastWord > std::chrono::seconds(limits.busySeconds);
    if (gStopSignal || idle || busy || now > deadline) {
      kill(-pid, SIGKILL);
      waitpid(pid, &status, 0);
      outcome.stalled = !gStopSignal && (idle || busy);
      outcome.busy = outcome.stalled && !idle;
      outcome.timedOut = !gStopSignal && !outcome.stalled;
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
