// libFuzzer entry point for the capture readers (loadCapture: manifest, lights.json, file list,
// EXRs; see capture_entry.h): every input must be loaded or refused with one line; a crash, an
// uncaught exception, a sanitizer report or a hang is a bug.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "tests/fuzz/capture_entry.h"

namespace {
// The work folder (held by a pointer that outlives the static destructors: removed at exit).
const std::string& workDir() {
  static const std::string* dir = [] {
    auto* path = new std::string((std::filesystem::temp_directory_path() / ("gblens-fuzz-capture-" + std::to_string(getpid()))).string());
    std::atexit([] { std::error_code ec; std::filesystem::remove_all(workDir(), ec); });
    return path;
  }();
  return *dir;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string refusal = gb::fuzz::captureOne(data, size, workDir());
  if (refusal.find('\n') != std::string::npos) std::abort();  // a refusal is one line
  return 0;
}
