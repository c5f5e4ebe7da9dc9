// The capture readers' and attach's command-line fuzz corpora (tests/fuzz/capture_corpus,
// tests/fuzz/attach_corpus), run through the fuzz targets' entries in-process: the seeds and every
// case found (issue 36: manifests that contradict their images, attach command lines that crashed).
// Files named "*valid*" must be accepted, every other one refused with one line, each within seconds.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <unistd.h>

#include <chrono>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>

#include "tests/fuzz/attach_entry.h"
#include "tests/fuzz/capture_entry.h"

namespace gb {
namespace {

namespace fs = std::filesystem;

using Entry = std::function<std::string(const uint8_t*, size_t, const std::string&)>;

// Runs every file of `corpus` through `entry`; returns how many were refused.
size_t runCorpus(const std::string& corpus, const Entry& entry) {
  const fs::path folder = fs::path(GBLENS_SOURCE_DIR) / "tests/fuzz" / corpus;
  const std::string work = (fs::temp_directory_path() / ("gblens-" + corpus + "-" + std::to_string(getpid()))).string();
  std::vector<fs::path> files(fs::directory_iterator(folder), fs::directory_iterator{});
  std::sort(files.begin(), files.end());
  size_t refused = 0;
  for (const fs::path& f : files) {
    SCOPED_TRACE(f.filename().string());
    std::ifstream in(f, std::ios::binary);
    const std::string bytes((std::istreambuf_iterator<char>(in)), {});
    const auto start = std::chrono::steady_clock::now();
    const std::string refusal = entry(reinterpret_cast<const uint8_t*>(bytes.data()), bytes.size(), work);
    EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 10.0);
    if (f.filename().string().find("valid") != std::string::npos) {
      EXPECT_EQ(refusal, "");
    } else {
      EXPECT_NE(refusal, "");
      EXPECT_EQ(refusal.find('\n'), std::string::npos) << refusal;
      refused += !refusal.empty();
    }
  }
  fs::remove_all(work);
  return refused;
}

TEST(FuzzCorpus, CaptureReadersAcceptOrRefuseInOneLine) {
  EXPECT_GE(runCorpus("capture_corpus", fuzz::captureOne), 8u);
}

TEST(FuzzCorpus, AttachCommandLinesAcceptOrRefuseInOneLine) {
  EXPECT_GE(runCorpus("attach_corpus", fuzz::attachOne), 8u);
}

}  // namespace
}  // namespace gb
