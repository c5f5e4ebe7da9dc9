// The import path's deterministic crash corpus (tests/fuzz/import_corpus): every input that crashed,
// hung or was silently accepted before issue 29 (number overflow, deep nesting, directories and
// devices as sources, huge declared image sizes, channel and offset overflows, paths in names,
// manifests a reader would refuse), run through the fuzz target's entry in-process. Files named
// "*valid*" must be accepted, every other one refused with one line, each within seconds.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "tests/fuzz/import_entry.h"

namespace gb {
namespace {

namespace fs = std::filesystem;

TEST(ImportCorpus, EveryCrashCaseIsRefusedInOneLine) {
  const fs::path corpus = fs::path(GBLENS_SOURCE_DIR) / "tests/fuzz/import_corpus";
  const std::string work = (fs::temp_directory_path() / ("gblens-corpus-" + std::to_string(getpid()))).string();
  std::vector<fs::path> files(fs::directory_iterator(corpus), fs::directory_iterator{});
  std::sort(files.begin(), files.end());
  ASSERT_GE(files.size(), 30u);
  size_t refused = 0;
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const auto start = std::chrono::steady_clock::now();
    const std::string refusal = fuzz::importOne(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), work);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    EXPECT_LT(seconds, 10.0);  // a hang, not a speed target
    if (f.filename().string().find("valid") != std::string::npos) {
      EXPECT_EQ(refusal, "");
    } else {
      EXPECT_NE(refusal, "");
      EXPECT_EQ(refusal.find('\n'), std::string::npos) << refusal;
      refused += !refusal.empty();
    }
  }
  EXPECT_GE(refused, 25u);
  fs::remove_all(work);
}

}  // namespace
}  // namespace gb
