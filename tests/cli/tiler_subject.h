// tests/subjects/tiler_deferred as the attach and import tests use it: where it is, and its own dump
// of a frame compared with a capture's target bit for bit (tests/cli/test_attach_tiler.cpp,
// test_suggest_compute.cpp).
#pragma once
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <string>

#include "tests/support/test_paths.h"
#include "views/capture/capture.h"

namespace gb::tiler_test {

inline std::string tiler() { return GBLENS_BUILD_DIR + "/tests/subjects/tiler_deferred/tiler_deferred"; }
inline std::string tilerDir() { return GBLENS_SOURCE_DIR + "/tests/subjects/tiler_deferred"; }

inline std::string tilerBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// The capture's texels of `target` (its sample `sample`; -1: the target's image) equal the dump's file `file`.
inline void expectDumped(const Capture& c, const std::string& target, const std::string& file, int sample = -1) {
  SCOPED_TRACE(target + (sample >= 0 ? " sample " + std::to_string(sample) : ""));
  const int i = c.frame.indexOf(target);
  ASSERT_GE(i, 0);
  ASSERT_TRUE(c.frame.images[size_t(i)].present());
  std::string bytes = tilerBytes(file);
  const TargetImage& ti = c.frame.images[size_t(i)];
  if (sample >= 0) ASSERT_LT(size_t(sample), ti.samples.size());
  const CpuImage& img = sample >= 0 ? ti.samples[size_t(sample)] : ti.image;
  if (c.frame.layout.targets[size_t(i)].format.name == "rgb10a2_unorm") {  // a capture holds it as 4 x u16 codes
    std::string unpacked(bytes.size() * 2, '\0');
    for (size_t t = 0; t + 4 <= bytes.size(); t += 4) {
      uint32_t v;
      std::memcpy(&v, bytes.data() + t, 4);
      const uint16_t codes[4] = {uint16_t(v & 1023), uint16_t(v >> 10 & 1023), uint16_t(v >> 20 & 1023), uint16_t(v >> 30)};
      std::memcpy(unpacked.data() + t * 2, codes, 8);
    }
    bytes = unpacked;
  }
  ASSERT_EQ(img.data.size(), bytes.size());
  EXPECT_EQ(std::memcmp(img.data.data(), bytes.data(), bytes.size()), 0);
}

}  // namespace gb::tiler_test
