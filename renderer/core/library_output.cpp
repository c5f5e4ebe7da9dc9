// LibraryOutput: fd 2 redirected into one anonymous file shared by every live capture.
#include "renderer/core/library_output.h"

#include <fcntl.h>
#include <sys/mman.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <mutex>
#include <vector>

// Under AddressSanitizer (make test-asan, make fuzz) its reports must reach the real stderr even
// when they happen while fd 2 is captured.
#if defined(__SANITIZE_ADDRESS__)
#define GBLENS_SANITIZED 1
#elif defined(__has_feature)
#if __has_feature(address_sanitizer)
#define GBLENS_SANITIZED 1
#endif
#endif
#ifdef GBLENS_SANITIZED
extern "C" void __sanitizer_set_report_fd(void* fd);
#endif

namespace gb {

namespace {

void reportSanitizerTo(int fd) {
#ifdef GBLENS_SANITIZED
  __sanitizer_set_report_fd(reinterpret_cast<void*>(intptr_t(fd)));
#else
  (void)fd;
#endif
}

std::mutex gMutex;
int gUsers = 0;       // live captures
int gSaved = -1;      // the real stderr while redirected
int gFile = -1;       // where fd 2 points meanwhile
bool gShow = false;

bool showing() {
  const char* v = std::getenv("GBLENS_VERBOSE");
  return gShow || (v && *v && std::string(v) != "0");
}

}  // namespace

void showLibraryOutput(bool show) { gShow = show; }

LibraryOutput::LibraryOutput() {
  std::lock_guard<std::mutex> lock(gMutex);
  if (showing()) return;
  if (gUsers == 0) {
    std::fflush(stderr);
    const int file = memfd_create("gblens-library-output", MFD_CLOEXEC);
    const int saved = file < 0 ? -1 : fcntl(2, F_DUPFD_CLOEXEC, 3);
    if (file < 0 || saved < 0 || dup2(file, 2) < 0) {  // cannot capture: let it through
      if (file >= 0) close(file);
      if (saved >= 0) close(saved);
      return;
    }
    gFile = file, gSaved = saved;
    reportSanitizerTo(saved);
  }
  ++gUsers;
  start_ = long(lseek(gFile, 0, SEEK_CUR));
}

std::string LibraryOutput::text() {
  std::lock_guard<std::mutex> lock(gMutex);
  if (start_ < 0) return "";
  std::fflush(stderr);
  const long end = long(lseek(gFile, 0, SEEK_CUR));
  std::string raw;
  if (end > start_) {
    raw.resize(size_t(end - start_));
    const ssize_t got = pread(gFile, raw.data(), raw.size(), start_);
    raw.resize(got > 0 ? size_t(got) : 0);
  }
  start_ = -1;
  if (--gUsers == 0) {
    dup2(gSaved, 2);
    reportSanitizerTo(2);
    close(gSaved);
    close(gFile);
    gSaved = gFile = -1;
  }
  // One line: lines joined with "; ", blank ones dropped, repeated ones once.
  std::string out, line;
  std::vector<std::string> seen;
  auto flush = [&] {
    while (!line.empty() && (line.back() == ' ' || line.back() == '\r' || line.back() == '\t')) line.pop_back();
    bool repeated = false;
    for (const std::string& s : seen) repeated = repeated || s == line;
    if (!line.empty() && !repeated) {
      out += (out.empty() ? "" : "; ") + line;
      seen.push_back(line);
    }
    line.clear();
  };
  for (char c : raw) {
    if (c == '\n')
      flush();
    else if (static_cast<unsigned char>(c) >= 0x20 || c == '\t')
      line += c;
  }
  flush();
  if (out.size() > 300) out = out.substr(0, 297) + "...";
  return out;
}

std::string LibraryOutput::suffix() {
  const std::string t = text();
  return t.empty() ? "" : " [" + t + "]";
}

LibraryOutput::~LibraryOutput() { text(); }

}  // namespace gb
