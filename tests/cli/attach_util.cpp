// Helpers of the attach tests (see attach_util.h).
#include "tests/support/test_paths.h"
#include "tests/cli/attach_util.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <glm/gtc/matrix_transform.hpp>

#include <gtest/gtest.h>

#include "tests/support/capture_util.h"
#include "views/live/live.h"
#include "views/live/live_wire.h"

namespace gb::attach {

std::string layerEnvironment(const std::string& socket, const std::string& dumpFile) {
  std::string dirs = std::string(GBLENS_BUILD_DIR) + "/layer";
  std::string env = "ENABLE_GBLENS_LIVE=1 ";
  if (!dumpFile.empty()) {
    dirs = std::string(GBLENS_BUILD_DIR) + "/present_dump:" + dirs;
    env += "ENABLE_GBLENS_TEST_DUMP=1 GBLENS_TEST_DUMP_FILE='" + dumpFile + "' ";
  }
  if (!socket.empty()) env += "GBLENS_LIVE_SOCKET='" + socket + "' ";
  return env + "XDG_DATA_DIRS=" + dirs + ":/usr/local/share:/usr/share ";
}

Report passesReport(const std::vector<std::string>& argv, const std::vector<std::string>& environment, const std::string& dir) {
  Report r;
  std::filesystem::create_directories(dir);
  LiveOptions o;
  o.argv = argv;
  o.suggest = true;
  o.environment = environment;
  o.environment.push_back("GBLENS_VALIDATE=1");
  o.log = dir + "/app.log";
  LiveSession s;
  if (!s.start(o, r.error)) return r;
  for (auto start = std::chrono::steady_clock::now(); !s.suggestion() && std::chrono::steady_clock::now() - start < std::chrono::seconds(60);) {
    FrameSnapshot unused;
    s.wait(unused, 0.2);
    if (!s.running() && !s.attached()) break;
  }
  if (!s.suggestion()) {
    r.error = "no passes report came";
    for (const std::string& t : s.takeReports()) r.error += "\n" + t;
  } else {
    r.passes = *s.suggestion();
    r.hello = s.hello();
  }
  r.status = s.waitApplication(60.0);
  if (r.status < 0) s.stop();
  r.log = readText(o.log);
  return r;
}

void expectPacedStream(LiveOptions o, int cycles, bool oneTime, bool stop) {
  o.paced = true;
  o.ringOffThread = true;  // a stream, as the viewer's
  LiveSession s;
  std::string error;
  ASSERT_TRUE(s.start(o, error)) << error;
  FrameSnapshot f;
  LiveFrameInfo info;
  ASSERT_TRUE(s.wait(f, 60.0, &info)) << (s.takeReports().empty() ? "" : s.takeReports()[0]);
  auto figure = [&](const char* name) { return s.counts().layer.value(name, uint64_t(0)); };
  EXPECT_TRUE(s.counts().layer.value("paced", false));
  for (int c = 0; c < cycles; ++c) {
    SCOPED_TRACE("after frame " + std::to_string(info.appFrame));
    const uint64_t frames = figure("frames"), copied = figure("copied_frames");
    if (c == 0) {  // a second of not asking
      const bool came = s.wait(f, 1.0, &info);
      EXPECT_FALSE(came) << "frame " << info.appFrame << " came unasked";
    }
    const uint64_t asked = wire::monotonicNs();
    s.ready();
    ASSERT_TRUE(s.wait(f, 30.0, &info)) << "no frame after ready()";
    EXPECT_GT(info.endNs, asked) << "frame " << info.appFrame << " ended before it was asked for";
    if (c == 0) {  // the hold: the application rendered on, and copied only what it had in flight
      EXPECT_GE(figure("frames") - frames, 5u);
      if (oneTime) EXPECT_LE(figure("copied_frames") - copied, 3u);  // those in flight, and this one
    }
  }
  for (const std::string& r : s.takeReports()) ADD_FAILURE() << r;
  if (stop) return s.stop();
  s.detach();
  EXPECT_EQ(s.waitApplication(120.0), 0) << readText(o.log);
}

bool readDump(const std::string& file, Dump& out) {
  std::ifstream in(file, std::ios::binary);
  std::string header;
  if (!std::getline(in, header)) return false;
  std::istringstream h(header);
  h >> out.width >> out.height >> out.format;
  out.texels.assign(std::istreambuf_iterator<char>(in), {});
  return out.width && out.texels.size() == size_t(out.width) * out.height * 4;
}

std::vector<std::string> texelDifferences(const Capture& a, const Capture& b) {
  std::vector<std::string> out;
  for (uint32_t t = 0; t < a.frame.layout.targets.size(); ++t) {
    const std::string& name = a.frame.layout.targets[t].name;
    const int u = b.frame.indexOf(name);
    const bool inA = a.frame.images[t].present(), inB = u >= 0 && b.frame.images[size_t(u)].present();
    if (inA != inB) {
      out.push_back(name + ": only in " + (inA ? "the first" : "the second"));
      continue;
    }
    if (!inA) continue;
    const CpuImage& x = a.frame.images[t].image;
    const CpuImage& y = b.frame.images[size_t(u)].image;
    if (x.width != y.width || x.height != y.height || x.type != y.type || x.data.size() != y.data.size()) {
      out.push_back(name + ": size or type differ");
      continue;
    }
    const size_t texel = x.texelBytes();
    size_t differ = 0;
    for (size_t i = 0; i < x.data.size(); i += texel) differ += std::memcmp(&x.data[i], &y.data[i], texel) != 0;
    if (differ) out.push_back(name + ": " + std::to_string(differ) + " texels differ");
  }
  return out;
}

namespace {

// cube.c's matrices, column-major as linmath.h stores them (m[column][row], as glm).
glm::dmat4 vkcubeClipFromModel(uint32_t frame) {
  const double a = 1.0 / std::tan(glm::radians(45.0) / 2.0), n = 0.1, f = 100.0;
  glm::dmat4 p(0.0);
  p[0][0] = a;
  p[1][1] = -a;  // "Flip projection matrix from GL to Vulkan orientation"
  p[2][2] = -(f + n) / (f - n);
  p[2][3] = -1.0;
  p[3][2] = -(2.0 * f * n) / (f - n);
  const glm::dvec3 eye(0.0, 3.0, 5.0), forward = glm::normalize(-eye), up(0.0, 1.0, 0.0);
  const glm::dvec3 s = glm::normalize(glm::cross(forward, up)), t = glm::cross(s, forward);
  glm::dmat4 v(1.0);
  for (int i = 0; i < 3; ++i) v[i][0] = s[i], v[i][1] = t[i], v[i][2] = -forward[i];
  v[3] = glm::dvec4(-glm::dot(s, eye), -glm::dot(t, eye), glm::dot(forward, eye), 1.0);
  // mat4x4_rotate_Y(Q, M, angle) = M * R with R's columns (c, 0, s), (0, 1, 0), (-s, 0, c); frame k
  // has been turned k + 1 times by 4 degrees.
  const double angle = glm::radians(4.0 * double(frame + 1));
  glm::dmat4 r(1.0);
  r[0] = glm::dvec4(std::cos(angle), 0.0, std::sin(angle), 0.0);
  r[2] = glm::dvec4(-std::sin(angle), 0.0, std::cos(angle), 0.0);
  return p * v * r;
}

// The ray through a point of the image against the cube in model space: the entry face (axis * 2 +
// side, -1: a miss) and the hardware depth there.
int castRay(const glm::dmat4& clipFromModel, uint32_t width, uint32_t height, double px, double py, double& depth) {
  const double side = std::min(width, height), ox = (width - side) / 2.0, oy = (height - side) / 2.0;
  const double nx = (px - ox) / side * 2.0 - 1.0, ny = (py - oy) / side * 2.0 - 1.0;
  const glm::dmat4 inv = glm::inverse(clipFromModel);
  glm::dvec4 a = inv * glm::dvec4(nx, ny, 0.5, 1.0), b = inv * glm::dvec4(nx, ny, 0.99, 1.0);
  const glm::dvec3 o = glm::dvec3(a) / a.w, d = glm::dvec3(b) / b.w - o;
  double enter = -1e300, leave = 1e300;
  int face = -1;
  for (int i = 0; i < 3; ++i) {
    if (d[i] == 0.0) {
      if (std::abs(o[i]) > 1.0) return -1;
      continue;
    }
    double t0 = (-1.0 - o[i]) / d[i], t1 = (1.0 - o[i]) / d[i];
    const int near = t0 < t1 ? 0 : 1;
    if (t0 > t1) std::swap(t0, t1);
    if (t0 > enter) enter = t0, face = i * 2 + near;
    leave = std::min(leave, t1);
  }
  if (enter > leave) return -1;
  const glm::dvec4 clip = clipFromModel * glm::dvec4(o + enter * d, 1.0);
  depth = clip.z / clip.w;
  return face;
}

}  // namespace

double vkcubeDepth(uint32_t frame, uint32_t width, uint32_t height, uint32_t x, uint32_t y, bool& nearEdge) {
  const glm::dmat4 m = vkcubeClipFromModel(frame);
  double depth = 1.0, other = 0.0;
  const int face = castRay(m, width, height, x + 0.5, y + 0.5, depth);
  nearEdge = false;
  for (double dx : {-0.1, 0.1})
    for (double dy : {-0.1, 0.1}) nearEdge |= castRay(m, width, height, x + 0.5 + dx, y + 0.5 + dy, other) != face;
  return face < 0 ? 1.0 : depth;
}

}  // namespace gb::attach
