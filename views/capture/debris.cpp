// Debris of interrupted runs (see debris.h): names stamped with the writer's pid and start time,
// removed by a later run once that process is gone.
#include "views/capture/debris.h"

#include <signal.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>

namespace gb {

namespace fs = std::filesystem;

namespace {

// Field 22 of /proc/PID/stat (its start time in clock ticks after boot); "" when unreadable.
std::string startTime(long pid) {
  std::ifstream in("/proc/" + std::to_string(pid) + "/stat");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const size_t comm = text.rfind(')');  // the command name may hold spaces and parentheses
  if (comm == std::string::npos) return "";
  std::istringstream fields(text.substr(comm + 1));
  std::string field;
  for (int i = 3; i <= 22 && fields >> field; ++i)
    if (i == 22) return field;
  return "";
}

// The leading numbers of a stamp ("123-456-7..." -> 123, 456, 7), at most three.
std::vector<unsigned long long> stampNumbers(const std::string& stamp) {
  std::vector<unsigned long long> out;
  size_t at = 0;
  while (out.size() < 3 && at < stamp.size() && std::isdigit(static_cast<unsigned char>(stamp[at]))) {
    size_t end = at;
    while (end < stamp.size() && std::isdigit(static_cast<unsigned char>(stamp[end]))) ++end;
    if (end - at > 19) break;
    out.push_back(std::stoull(stamp.substr(at, end - at)));
    if (end >= stamp.size() || stamp[end] != '-') break;
    at = end + 1;
  }
  return out;
}

bool ownedByMe(const fs::path& p) {
  struct stat st {};
  return lstat(p.c_str(), &st) == 0 && st.st_uid == getuid();
}

}  // namespace

std::string processStamp() {
  const long pid = long(getpid());
  const std::string start = startTime(pid);
  return std::to_string(pid) + "-" + (start.empty() ? "0" : start);
}

namespace {

// Whether process `pid` has ended; with `start`, also when that pid now belongs to another process.
bool processGone(unsigned long long pid, const unsigned long long* start) {
  if (pid == 0 || pid > 0x7FFFFFFFull || pid == (unsigned long long)getpid()) return false;
  if (kill(pid_t(pid), 0) != 0 && errno == ESRCH) return true;
  if (!start) return false;
  const std::string now = startTime(long(pid));
  return !now.empty() && now != std::to_string(*start);
}

}  // namespace

bool stampGone(const std::string& stamp) {
  const std::vector<unsigned long long> n = stampNumbers(stamp);
  if (n.size() < 2) return false;
  // PID-START-N; an old name PID-N: its second number is no start time, judged by the pid alone.
  return processGone(n[0], n.size() >= 3 ? &n[1] : nullptr);
}

std::vector<std::string> removeDebris(const std::string& pathText) {
  std::vector<std::string> said;
  fs::path path = fs::absolute(fs::path(pathText)).lexically_normal();
  if (path.filename().empty()) path = path.parent_path();
  const fs::path parent = path.parent_path();
  const std::string base = "." + path.filename().string() + ".";
  std::error_code ec;
  for (fs::directory_iterator it(parent, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(base, 0) != 0) continue;
    const std::string rest = name.substr(base.size());
    std::string kind;
    for (const char* k : {"partial-", "old-", "tmp-"})
      if (rest.rfind(k, 0) == 0) kind = k;
    if (kind.empty() || !ownedByMe(it->path())) continue;
    const std::string stamp = rest.substr(kind.size());
    if (!stampGone(stamp)) continue;
    const std::string who = " (left by process " + std::to_string(stampNumbers(stamp)[0]) + ", which is gone)";
    std::error_code e;
    if (kind == "old-" && !fs::exists(fs::symlink_status(path, e))) {
      fs::rename(it->path(), path, e);
      if (!e) said.push_back("moved " + it->path().string() + " back to " + path.string() + who);
      continue;
    }
    if (fs::remove_all(it->path(), e) != static_cast<std::uintmax_t>(-1) && !e)
      said.push_back("removed " + it->path().string() + who);
  }
  return said;
}

std::vector<std::string> removeDebrisNamed(const std::string& folder, const std::string& prefix) {
  std::vector<std::string> said;
  std::error_code ec;
  for (fs::directory_iterator it(folder, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind(prefix, 0) != 0 || !ownedByMe(it->path())) continue;
    const std::string stamp = name.substr(prefix.size());
    const std::vector<unsigned long long> n = stampNumbers(stamp);  // PID-START-XXXXXX
    if (n.size() < 2 || !processGone(n[0], &n[1])) continue;
    std::error_code e;
    if (fs::remove_all(it->path(), e) != static_cast<std::uintmax_t>(-1) && !e)
      said.push_back("removed " + it->path().string() + " (left by process " + std::to_string(n[0]) + ", which is gone)");
  }
  return said;
}

}  // namespace gb
