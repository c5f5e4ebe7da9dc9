// What the layer copies of the buffers a pass binds, against tests/subjects/foreign_deferred's own
// truth (README; `--dump` writes the last frame's uniform buffer): bound_buffers of its first pass
// are its uniform buffer at set 0 binding 0 (uniforms.bin) and its last object's push constants;
// camera.live at set 0 binding 0 streams the camera its dump's camera.json holds, as a sidecar of
// those matrices does; camera.live in an import is refused with one line.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <glm/gtc/matrix_transform.hpp>

#include "tests/cli/attach_util.h"
#include "tests/support/capture_util.h"
#include "views/live/live.h"

namespace gb {
namespace {

using json = nlohmann::json;

// foreign_deferred's layout.json with live sources (render pass, colour index or depth: its README's
// table) and without the fields today's decoding refuses (as test_attach_foreign.cpp); no camera.
json foreignLiveLayout() {
  json l = json::parse(std::ifstream(FOREIGN_DEFERRED_DIR + "/layout.json"));
  const std::map<std::string, std::pair<int, int>> live = {{"position", {0, 0}}, {"normal", {0, 1}}, {"albedo", {0, 2}},
                                                           {"depth", {0, -1}},   {"occlusion", {1, 0}}, {"hdr", {2, 0}},
                                                           {"final", {3, 0}}};
  for (json& t : l["targets"]) {
    const auto [pass, color] = live.at(t["name"].get<std::string>());
    t["source"] = {{"live", color < 0 ? json{{"pass", pass}, {"depth", true}} : json{{"pass", pass}, {"color", color}}}};
    for (json& q : t["quantities"])
      if (q.value("quantity", "") == "depth") q.erase("scale");
  }
  l["camera"].erase("up");
  l["camera"].erase("renderdoc");
  return l;
}

std::vector<uint8_t> bytesOf(const std::string& file) {
  std::ifstream in(file, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), {}};
}

std::vector<float> floatsOf(const std::vector<uint8_t>& bytes) {
  std::vector<float> f(bytes.size() / 4);
  std::memcpy(f.data(), bytes.data(), f.size() * 4);
  return f;
}

// The camera where the README says it is: uniform buffer set 0 binding 0 of pass 0, projection at 0, view at 64.
json withLiveCamera(json layout) {
  layout["camera"]["live"] = {{"pass", 0}, {"set", 0}, {"binding", 0}};
  layout["camera"]["view_from_world"] = {{"offset", 64}};
  layout["camera"]["clip_from_view"] = {{"offset", 0}};
  return layout;
}

TEST(AttachStructure, BoundBuffersAreTheUniformBufferAndTheLastObjectsPushConstants) {
  const std::string dir = freshDir("attach_bound_buffers");
  std::ofstream(dir + "/live.json") << withLiveCamera(foreignLiveLayout()).dump(2);
  LiveOptions o;
  o.layout = dir + "/live.json";
  o.argv = {FOREIGN_DEFERRED_BINARY, "--frames", "3", "--dump", dir + "/dump"};
  o.environment = {"GBLENS_VALIDATE=1"};
  o.log = dir + "/app.log";
  o.captureFrame = 2;  // the application's last frame, the one it dumps
  o.boundBuffersPass = 0;
  LiveSession s;
  std::string error;
  ASSERT_TRUE(s.start(o, error)) << error;
  FrameSnapshot f;
  LiveFrameInfo info;
  ASSERT_TRUE(s.wait(f, 60.0, &info)) << (s.takeReports().empty() ? "" : s.takeReports()[0]);
  EXPECT_EQ(info.appFrame, 2u);
  const std::vector<RdcBinding> bound = s.boundBuffers();
  for (const std::string& r : s.takeReports()) ADD_FAILURE() << r;
  ASSERT_EQ(s.waitApplication(60.0), 0) << readText(o.log);  // validation clean, the dump written

  ASSERT_EQ(bound.size(), 2u);
  // README: the camera block, uniform buffer set 0 binding 0, 464 bytes, bound whole.
  const RdcBinding& ubo = bound[0];
  EXPECT_EQ(ubo.kind, "uniform");
  EXPECT_EQ(ubo.name, "set 0 binding 0");  // the application names nothing
  EXPECT_EQ(ubo.set, 0u);
  EXPECT_EQ(ubo.binding, 0u);
  EXPECT_EQ(ubo.index, 0u);
  EXPECT_TRUE(ubo.bound);
  EXPECT_EQ(ubo.offset, 0u);
  EXPECT_EQ(ubo.range, 464u);
  EXPECT_EQ(ubo.bytes, 464u);
  EXPECT_TRUE(ubo.data == bytesOf(dir + "/dump/uniforms.bin")) << ubo.data.size() << " bytes";
  // README: per draw a push constant block, mat4 world_from_object at 0 and vec4 albedo at 64; the last
  // object (scene.cpp) is the small sphere at (-2.6, -0.6, -2.2), half size 0.6, unturned, albedo (0.30, 0.75, 0.35, 1).
  const RdcBinding& push = bound[1];
  EXPECT_EQ(push.kind, "push_constants");
  EXPECT_EQ(push.offset, 0u);
  EXPECT_EQ(push.range, 80u);
  const std::vector<float> got = floatsOf(push.data);
  const std::vector<float> want = {0.6f, 0, 0, 0, 0, 0.6f, 0, 0, 0, 0, 0.6f, 0, -2.6f, -0.6f, -2.2f, 1,
                                   0.30f, 0.75f, 0.35f, 1};
  EXPECT_EQ(got, want);
}

// Two streams of frame 2: the camera from the bytes pass 0 binds at set 0 binding 0 (projection at 0,
// view at 64: README), and from the matrices the application dumped for that frame (a sidecar).
TEST(AttachStructure, CameraLiveIsTheCameraTheApplicationDumps) {
  const std::string dir = freshDir("attach_camera_live");
  std::ofstream(dir + "/live.json") << withLiveCamera(foreignLiveLayout()).dump(2);
  auto stream = [&](const std::string& layout, const std::string& out) {
    return runShell("GBLENS_VALIDATE=1 '" + std::string(GBLENS_BINARY) + "' attach --layout " + layout + " --capture-frame 2 -o " +
                    out + " -- '" + FOREIGN_DEFERRED_BINARY + "' --frames 3 --dump " + out + "_dump");
  };
  RunResult a = stream(dir + "/live.json", dir + "/live");
  ASSERT_EQ(a.exitCode, 0) << a.output;
  EXPECT_EQ(a.output.find("exited with status"), std::string::npos) << a.output;  // validation clean
  const json dumped = json::parse(std::ifstream(dir + "/live_dump/camera.json"));
  ASSERT_EQ(dumped.value("frame", -1), 2);
  std::ofstream(dir + "/camera.json") << json{{"view_from_world", dumped["view_from_world"]},
                                              {"clip_from_view", dumped["clip_from_view"]}}.dump(2);
  json side = foreignLiveLayout();
  side["camera"]["sidecar"] = dir + "/camera.json";
  std::ofstream(dir + "/side.json") << side.dump(2);
  RunResult b = stream(dir + "/side.json", dir + "/side");
  ASSERT_EQ(b.exitCode, 0) << b.output;

  Capture x, y;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/live", x, error)) << error;
  ASSERT_TRUE(loadCapture(dir + "/side", y, error)) << error;
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r) {  // the matrices as stored (column-major floats), exactly
      EXPECT_EQ(x.frame.layout.camera.viewFromWorld[c][r], dumped["view_from_world"][c * 4 + r].get<float>());
      EXPECT_EQ(x.frame.layout.camera.clipFromView[c][r], dumped["clip_from_view"][c * 4 + r].get<float>());
    }
  EXPECT_TRUE(x.frame.camera.eyeFromWorld == y.frame.camera.eyeFromWorld);
  EXPECT_TRUE(x.frame.camera.clipFromEye == y.frame.camera.clipFromEye);
  EXPECT_NE(x.frame.layout.camera.from.find("render pass 0, set 0 binding 0"), std::string::npos) << x.frame.layout.camera.from;
  const std::vector<std::string> differ = attach::texelDifferences(x, y);
  EXPECT_TRUE(differ.empty()) << differ.front();
}

TEST(AttachStructure, CameraLiveInAnImportIsRefused) {
  const std::string dir = freshDir("attach_camera_live_import");
  json l = foreignLiveLayout();
  l["camera"]["live"] = {{"pass", 0}, {"push_constants", true}};
  l["camera"]["view_from_world"] = {{"offset", 0}};
  l["camera"]["clip_from_view"] = {{"offset", 64}};
  std::ofstream(dir + "/l.json") << l.dump(2);
  std::ofstream(dir + "/position.exr") << "not read";
  RunResult r = runGblens("import " + dir + "/position.exr --layout " + dir + "/l.json -o " + dir + "/out");
  EXPECT_NE(r.exitCode, 0);
  EXPECT_NE(r.output.find(dir + "/l.json: camera: live: "), std::string::npos) << r.output;
  EXPECT_EQ(std::count(r.output.begin(), r.output.end(), '\n'), 1) << r.output;
}

}  // namespace
}  // namespace gb
