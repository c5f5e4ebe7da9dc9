// The camera search of import --suggest-layout on uniform buffers laid out by hand: a projection, the
// view matrix and decoys (a rigid model matrix, projection * view, the inverse projection), stored
// column- or row-major, with stored world-space positions of points placed on known pixels. The
// search must find the projection and the view matrix by their offsets, with the conventions, even
// when a decoy sits where the view matrix usually is and carries the name "view": the stored
// positions decide, not names or places.
#include <gtest/gtest.h>

#include <cstring>

#include <glm/gtc/matrix_transform.hpp>

#include "views/infer/suggest_camera.h"

namespace gb {
namespace {

constexpr uint32_t kCamW = 40, kCamH = 30;

struct CameraSetup {
  glm::dmat4 proj, view, model;
  bool rowMajor = false;
  bool leftHanded = false;  // D3D-style: the view looks down +Z, the projection's w is +z
};

void put(std::vector<uint8_t>& bytes, size_t offset, const glm::dmat4& m, bool rowMajor) {
  for (int i = 0; i < 16; ++i) {
    const float v = float(rowMajor ? m[i % 4][i / 4] : m[i / 4][i % 4]);
    std::memcpy(bytes.data() + offset + size_t(i) * 4, &v, 4);
  }
}

// The buffer: the model matrix (named "view_matrix", a lie) at 0, the projection at 64, the view
// matrix at 128, projection * view at 192, the inverse projection at 256.
RdcBinding buffer(const CameraSetup& s) {
  RdcBinding b;
  b.name = "camera_block";
  b.id = 77;
  b.kind = "uniform";
  b.bound = true;
  b.offset = 256;  // bound at byte 256 of a larger buffer: offsets in the draft count from the buffer's start
  b.data.assign(320, 0);
  put(b.data, 0, s.model, s.rowMajor);
  put(b.data, 64, s.proj, s.rowMajor);
  put(b.data, 128, s.view, s.rowMajor);
  put(b.data, 192, s.proj * s.view, s.rowMajor);
  put(b.data, 256, glm::inverse(s.proj), s.rowMajor);
  b.members = {{"view_matrix", "mat4", 0}};
  return b;
}

// World-space points on a grid of pixel centres at varying depth, placed through the setup's own
// matrices (by hand: the pixel's NDC, the projection's inverse, then the inverse view), and their
// hardware depth.
CameraEvidence evidence(const CameraSetup& s) {
  CameraEvidence e;
  e.width = kCamW, e.height = kCamH;
  const glm::dmat4 inverse = glm::inverse(s.proj * s.view);
  for (uint32_t y = 1; y < kCamH; y += 3)
    for (uint32_t x = 2; x < kCamW; x += 3) {
      const double depth = 0.2 + 0.7 * double((x * 7 + y * 3) % 11) / 10.0;
      const glm::dvec4 ndc((x + 0.5) / kCamW * 2.0 - 1.0, (y + 0.5) / kCamH * 2.0 - 1.0, depth, 1.0);
      const glm::dvec4 w = inverse * ndc;
      CameraEvidence::Sample sample;
      sample.x = x, sample.y = y;
      sample.hasPosition = true;
      sample.position = glm::dvec3(w) / w.w;
      sample.depth = depth;
      e.samples.push_back(sample);
    }
  return e;
}

CameraSetup perspective(bool rowMajor, bool yDown) {
  CameraSetup s;
  s.proj = glm::perspectiveRH_ZO(0.9, double(kCamW) / kCamH, 0.3, 50.0);
  s.proj[1][1] *= -1.0;  // Vulkan: y down the image
  const glm::dvec3 up(0.0, yDown ? -1.0 : 1.0, 0.0);
  s.view = glm::lookAtRH(glm::dvec3(3.0, 2.0 * up.y, 6.0), glm::dvec3(0.0, 0.5 * up.y, 0.0), up);
  s.model = glm::rotate(glm::translate(glm::dmat4(1.0), glm::dvec3(1.0, 0.0, -2.0)), 0.7, glm::dvec3(0, 1, 0));
  s.rowMajor = rowMajor;
  return s;
}

void expectFound(const CameraSetup& s, const char* up, const char* projection) {
  const FoundCamera f = searchCamera({buffer(s)}, evidence(s));
  ASSERT_TRUE(f.found);
  SCOPED_TRACE(f.camera.dump());
  EXPECT_TRUE(f.positionsChecked);
  EXPECT_EQ(f.positionSpace, Space::World);
  EXPECT_LT(f.pixelError, 1e-3);
  const nlohmann::json& r = f.camera["renderdoc"];
  EXPECT_EQ(r["buffer"], "camera_block");
  EXPECT_EQ(r["clip_from_view"]["offset"], 256 + 64);
  EXPECT_EQ(r["view_from_world"]["offset"], 256 + 128);
  EXPECT_EQ(f.camera["matrix_order"], s.rowMajor ? "row_major" : "column_major");
  EXPECT_EQ(f.camera["view_handedness"], s.leftHanded ? "left" : "right");
  EXPECT_EQ(f.camera["up"], up);
  EXPECT_EQ(f.camera["projection"], projection);
  EXPECT_EQ(f.camera["convention"], "vulkan");
}

TEST(SuggestCamera, FindsProjectionAndViewByStoredPositionsNotByNamesOrPlaces) {
  expectFound(perspective(false, false), "y", "perspective");
  expectFound(perspective(true, false), "y", "perspective");
  expectFound(perspective(false, true), "-y", "perspective");
}

TEST(SuggestCamera, FindsOrthographicAndReversedDepthAndLeftHandedViews) {
  CameraSetup ortho = perspective(false, false);
  ortho.proj = glm::orthoRH_ZO(-4.0, 4.0, -3.0, 3.0, 0.5, 40.0);
  ortho.proj[1][1] *= -1.0;
  expectFound(ortho, "y", "orthographic");
  CameraSetup reversed = perspective(true, false);
  reversed.proj = glm::perspectiveRH_ZO(0.9, double(kCamW) / kCamH, 50.0, 0.3);  // near and far swapped
  reversed.proj[1][1] *= -1.0;
  expectFound(reversed, "y", "perspective");
  CameraSetup left = perspective(false, false);
  left.leftHanded = true;
  left.proj = glm::perspectiveLH_ZO(0.9, double(kCamW) / kCamH, 0.3, 50.0);
  left.proj[1][1] *= -1.0;
  left.view = glm::lookAtLH(glm::dvec3(3.0, 2.0, 6.0), glm::dvec3(0.0, 0.5, 0.0), glm::dvec3(0, 1, 0));
  expectFound(left, "y", "perspective");
}

// The positions decide: placed where the model matrix is, the draft would not match them.
TEST(SuggestCamera, APlantedModelMatrixDoesNotFitThePositions) {
  CameraSetup s = perspective(false, false);
  const FoundCamera f = searchCamera({buffer(s)}, evidence(s));
  ASSERT_TRUE(f.found);
  EXPECT_NE(f.camera["renderdoc"]["view_from_world"]["offset"], 256);
  // Evidence without positions: only the depth's fit, the guess note says the camera is unchecked.
  CameraEvidence depthOnly = evidence(s);
  for (CameraEvidence::Sample& sample : depthOnly.samples) sample.hasPosition = false;
  const FoundCamera g = searchCamera({buffer(s)}, depthOnly);
  ASSERT_TRUE(g.found);
  EXPECT_FALSE(g.positionsChecked);
  EXPECT_EQ(g.camera["renderdoc"]["clip_from_view"]["offset"], 256 + 64);
  EXPECT_NE(g.camera["guess"].get<std::string>().find("not checked"), std::string::npos);
}

}  // namespace
}  // namespace gb
