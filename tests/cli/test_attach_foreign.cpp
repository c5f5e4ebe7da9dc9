// gblens attach on "another renderer": tests/subjects/foreign_deferred (unnamed images, no labels:
// its targets are named live by render pass and attachment index, as its README lists them), run
// with validation and synchronization validation on. Its layout.json with live sources streams, for
// the frame RenderDoc captured (the foreign_captures fixture: frame 2 of 3), every target equal bit
// for bit to the same .rdc imported with layout.json; the camera (a sidecar of the app's own dump
// of that frame, its uniform buffer having no name) equals the one import read from the buffer.
// attach --suggest with no layout drafts what import --suggest-layout drafts from that .rdc, and the
// draft streams each attachment the app dumps itself.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "tests/cli/attach_util.h"
#include "tests/support/capture_util.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

using nlohmann::json;

const std::string kLayout = FOREIGN_DEFERRED_DIR + "/layout.json";
const std::string kOut = GBLENS_BUILD_DIR + "/foreign";

// Where each target of layout.json is live: (render pass in the command buffer, colour index or -1
// for the depth attachment), from the app's README.
const std::map<std::string, std::pair<int, int>> kLive = {{"position", {0, 0}}, {"normal", {0, 1}},   {"albedo", {0, 2}},
                                                          {"depth", {0, -1}},   {"occlusion", {1, 0}}, {"hdr", {2, 0}},
                                                          {"final", {3, 0}}};

// Decoding fields today's gblens refuses (the foreign tests skip the checks that need them): left
// out of both layouts alike, which changes no source and no stored texel.
void reduce(json& layout) {
  for (json& t : layout["targets"])
    for (json& q : t["quantities"])
      if (q.value("quantity", "") == "depth") q.erase("scale");
  layout["camera"].erase("up");
}

TEST(ForeignAttach, StreamsWhatRenderDocCaptured) {
  const std::string dir = freshDir("attach_foreign");
  json layout = json::parse(std::ifstream(kLayout));
  json rdc = layout;
  reduce(rdc);
  std::ofstream(dir + "/rdc.json") << rdc.dump(2);
  RunResult imported = runGblens("import '" + kOut + "/foreign.rdc' --layout " + dir + "/rdc.json -o " + dir + "/imported");
  ASSERT_EQ(imported.exitCode, 0) << imported.output;

  json live = rdc;
  for (json& t : live["targets"]) {
    const auto [pass, color] = kLive.at(t["name"].get<std::string>());
    t["source"] = {{"live", color < 0 ? json{{"pass", pass}, {"depth", true}} : json{{"pass", pass}, {"color", color}}}};
  }
  // The camera from the app's own dump of that frame (the fixture's): the matrices, as a sidecar.
  const json dumped = json::parse(std::ifstream(kOut + "/dump/camera.json"));
  ASSERT_EQ(dumped.value("frame", -1), 2);
  std::ofstream(dir + "/camera.json") << json{{"view_from_world", dumped["view_from_world"]},
                                              {"clip_from_view", dumped["clip_from_view"]}}.dump(2);
  live["camera"].erase("renderdoc");
  live["camera"]["sidecar"] = dir + "/camera.json";
  std::ofstream(dir + "/live.json") << live.dump(2);
  RunResult streamed = runShell("GBLENS_VALIDATE=1 '" + std::string(GBLENS_BINARY) + "' attach --layout " + dir +
                                "/live.json --capture-frame 2 -o " + dir + "/live -- '" + FOREIGN_DEFERRED_BINARY +
                                "' --frames 3");
  ASSERT_EQ(streamed.exitCode, 0) << streamed.output;
  EXPECT_EQ(streamed.output.find("exited with status"), std::string::npos) << streamed.output;  // validation clean
  Capture a, b;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/live", a, error)) << error;
  ASSERT_TRUE(loadCapture(dir + "/imported", b, error)) << error;
  for (uint32_t t = 0; t < a.frame.layout.targets.size(); ++t)
    EXPECT_TRUE(a.frame.images[t].present()) << a.frame.layout.targets[t].name << "\n" << streamed.output;
  const std::vector<std::string> differ = attach::texelDifferences(a, b);
  EXPECT_TRUE(differ.empty()) << differ.front();
  EXPECT_TRUE(a.frame.camera.eyeFromWorld == b.frame.camera.eyeFromWorld);
  EXPECT_TRUE(a.frame.camera.clipFromEye == b.frame.camera.clipFromEye);
}

// The quantity fields a guess is made of.
json guessed(const json& q) {
  json g = {{"quantity", q["quantity"]}, {"name", q["name"]}, {"channels", q["channels"]}};
  for (const char* field : {"encoding", "space", "scale", "background", "normalized"})
    if (q.contains(field)) g[field] = q[field];
  return g;
}

std::string readBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// attach --suggest with no layout drafts, from the live attachments, the buffers the G-buffer pass binds
// and one streamed frame's texels, what import --suggest-layout drafts from the RenderDoc capture of the
// same application: the same targets and quantities, and the camera at the same offsets (read live
// from the binding, set 0 binding 0, where the capture names its buffer); streamed under that draft,
// every target is the attachment the application itself dumps for that frame.
TEST(ForeignAttach, SuggestDraftsWhatImportDraftsAndItsTargetsAreTheAppsAttachments) {
  const std::string dir = freshDir("attach_foreign_suggest");
  // 5000 frames (a minute or more): gblens returns once the draft is written, ending the application.
  RunResult suggested = runShell("cd '" + dir + "' && DISPLAY= WAYLAND_DISPLAY= GBLENS_VALIDATE=1 timeout 120 '" +
                                 GBLENS_BINARY + "' attach --suggest -o draft.json -- '" + FOREIGN_DEFERRED_BINARY +
                                 "' --frames 5000");
  ASSERT_EQ(suggested.exitCode, 0) << suggested.output;
  EXPECT_NE(suggested.output.find("once the draft was written (--keep-running lets it run on)"), std::string::npos)
      << suggested.output;
  EXPECT_NE(suggested.output.find("passes       4"), std::string::npos) << suggested.output;  // the layer's report
  RunResult imported = runGblens("import '" + kOut + "/foreign.rdc' --suggest-layout -o " + dir + "/rdc_draft.json");
  ASSERT_EQ(imported.exitCode, 0) << imported.output;
  const json live = json::parse(std::ifstream(dir + "/draft.json")), rdc = json::parse(std::ifstream(dir + "/rdc_draft.json"));
  ASSERT_EQ(live["targets"].size(), rdc["targets"].size());
  for (size_t t = 0; t < rdc["targets"].size(); ++t) {
    const json &a = live["targets"][t], &b = rdc["targets"][t];
    SCOPED_TRACE("target " + b["name"].get<std::string>());
    EXPECT_EQ(a["name"], b["name"]);
    EXPECT_EQ(a["format"], b["format"]);
    ASSERT_EQ(a["quantities"].size(), b["quantities"].size());
    for (size_t q = 0; q < b["quantities"].size(); ++q) EXPECT_EQ(guessed(a["quantities"][q]), guessed(b["quantities"][q]));
  }
  ASSERT_TRUE(live.contains("camera") && rdc.contains("camera")) << live.dump(1);
  EXPECT_EQ(live["camera"]["live"], json({{"pass", 0}, {"set", 0}, {"binding", 0}, {"index", 0}}));
  for (const char* m : {"view_from_world", "clip_from_view"})
    EXPECT_EQ(live["camera"][m]["offset"], rdc["camera"]["renderdoc"][m]["offset"]) << m;
  for (const char* field : {"convention", "view_handedness", "up", "projection", "matrix_order"})
    EXPECT_EQ(live["camera"][field], rdc["camera"][field]) << field;
  // Streamed under the draft as written: each target is the attachment the app dumps (its camera.json
  // says which render pass, 1-based, and attachment each file is).
  RunResult streamed = runShell("GBLENS_VALIDATE=1 '" + std::string(GBLENS_BINARY) + "' attach --layout " + dir +
                                "/draft.json --capture-frame 2 -o " + dir + "/live -- '" + FOREIGN_DEFERRED_BINARY + "' --frames 3");
  ASSERT_EQ(streamed.exitCode, 0) << streamed.output;
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/live", c, error)) << error;
  const json dumped = json::parse(std::ifstream(kOut + "/dump/camera.json"));
  ASSERT_EQ(dumped.value("frame", -1), 2);
  size_t compared = 0;
  for (const json& t : live["targets"]) {
    const json pick = t["source"]["live"];
    SCOPED_TRACE("target " + t["name"].get<std::string>() + " " + pick.dump());
    const json* file = nullptr;
    for (const json& d : dumped["targets"])
      if (d["render_pass"] == pick["pass"].get<int>() + 1 &&
          (pick.value("depth", false) ? d["vk_format"].get<std::string>().rfind("VK_FORMAT_D", 0) == 0
                                      : d["attachment"] == pick.value("color", -1)))
        file = &d;
    ASSERT_NE(file, nullptr);
    const int i = c.frame.indexOf(t["name"].get<std::string>());
    ASSERT_GE(i, 0);
    const std::string bytes = readBytes(kOut + "/dump/" + (*file)["file"].get<std::string>());
    const CpuImage& img = c.frame.images[size_t(i)].image;
    ASSERT_EQ(img.data.size(), bytes.size());
    EXPECT_EQ(std::memcmp(img.data.data(), bytes.data(), bytes.size()), 0);
    ++compared;
  }
  EXPECT_EQ(compared, 7u);
}

}  // namespace
}  // namespace gb
