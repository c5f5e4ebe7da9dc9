// libFuzzer entry point for the import path (layouts, sidecars, image readers, raw unpackers,
// manifests; see import_entry.h): every input must be accepted or refused with one line; a crash,
// an uncaught exception, a sanitizer report or a hang is a bug.
#include <unistd.h>

#include <cstdlib>
#include <filesystem>

#include "tests/fuzz/import_entry.h"

namespace {
// The work folder (held by a pointer that outlives the static destructors: removed at exit).
const std::string& workDir() {
  static const std::string* dir = [] {
    const char* d = std::getenv("GBLENS_FUZZ_DIR");
    auto* path = new std::string(d ? d : (std::filesystem::temp_directory_path() / ("gblens-fuzz-" + std::to_string(getpid()))).string());
    std::atexit([] { std::error_code ec; std::filesystem::remove_all(workDir(), ec); });
    return path;
  }();
  return *dir;
}
}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  const std::string refusal = gb::fuzz::importOne(data, size, workDir());
  if (refusal.find('\n') != std::string::npos) std::abort();  // a refusal is one line
  return 0;
}
