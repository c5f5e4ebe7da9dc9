// The GUI fixtures that also need gblens's device in the test (GpuTest: the frame the viewer should
// show, computed apart) and an Xvfb session (gui::Session): skipped without Xvfb, a folder per test.
#pragma once
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <string>

#include "tests/gpu/gpu_test.h"
#include "tests/gui/gui_util.h"

namespace gb {

class GpuGuiTest : public GpuTest, protected gui::Session {
 protected:
  // The test's folder is GBLENS_BUILD_DIR/<prefix><test name> (Session::openTestDisplay).
  virtual std::string folderPrefix() const = 0;
  void SetUp() override {
    if (!gui::haveTool("Xvfb")) GTEST_SKIP() << "Xvfb is not installed (apt-get install xvfb)";
    ASSERT_EQ(gui::missingTool(), "") << "is missing (debian-packages.txt lists it; run make deps)";
    GpuTest::SetUp();
    std::string error;
    ASSERT_TRUE(openTestDisplay(folderPrefix(), 1280, 720, error)) << error;
  }
  void TearDown() override {
    closeDisplay();
    if (!IsSkipped()) GpuTest::TearDown();
  }
};

}  // namespace gb
