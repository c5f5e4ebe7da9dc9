// Live sources (`gblens attach`, docs/layout-format.md): each form parses to the attachment pick it
// names, every malformed one is refused naming the target and the field, they round-trip through
// JSON (capture manifests), and the layout becomes the layer's request: targets without a source
// read the image of their own name, RenderDoc texture names are debug names, a RenderDoc resource id
// or a file is refused. camera.live (the bytes a pass binds) parses, round-trips, is requested with
// its byte count, names the field of each mistake, and is refused by an import.
#include <gtest/gtest.h>

#include "renderer/core/layout_json.h"
#include "views/live/live.h"

namespace gb {
namespace {

using json = nlohmann::json;

json withSource(const json& source) {
  json l = json::parse(R"({"format": "gblens-layout", "version": 1, "targets": [
    {"name": "albedo", "format": "rgba8_srgb", "quantities": [{"quantity": "albedo", "channels": [0, 1, 2]}]},
    {"name": "z", "format": "d16", "quantities": [{"quantity": "depth", "channels": [0], "encoding": "eye"}]}]})");
  if (!source.is_null()) l["targets"][0]["source"] = source;
  return l;
}

bool parse(const json& j, Layout& out, std::string& error) { return parseLayout(j, "l.json", out, error); }

TEST(LayoutLive, EveryFormParses) {
  Layout l;
  std::string error;
  ASSERT_TRUE(parse(withSource({{"live", "GBuffer.Albedo"}}), l, error)) << error;
  const TargetSource& s = l.targets[0].source;
  EXPECT_EQ(s.kind, TargetSource::Kind::Live);
  EXPECT_EQ(s.live.name, "GBuffer.Albedo");
  EXPECT_EQ(s.live.passIndex, -1);
  ASSERT_TRUE(parse(withSource({{"live", {{"pass", "Lighting"}, {"color", 2}}}}), l, error)) << error;
  EXPECT_EQ(l.targets[0].source.live.pass, "Lighting");
  EXPECT_EQ(l.targets[0].source.live.color, 2);
  ASSERT_TRUE(parse(withSource({{"live", {{"pass", 3}, {"depth", true}}}}), l, error)) << error;
  EXPECT_EQ(l.targets[0].source.live.passIndex, 3);
  EXPECT_TRUE(l.targets[0].source.live.depth);
  ASSERT_TRUE(parse(withSource({{"live", {{"pass", 0}, {"format", "rgba16f"}}}}), l, error)) << error;
  EXPECT_EQ(l.targets[0].source.live.format, "rgba16f");
  // A subpass's colour attachment (a G-buffer read as input attachments later), the render pass's attachment N.
  ASSERT_TRUE(parse(withSource({{"live", {{"pass", 0}, {"subpass", 0}, {"color", 2}}}}), l, error)) << error;
  EXPECT_EQ(l.targets[0].source.live.subpass, 0);
  EXPECT_EQ(l.targets[0].source.live.color, 2);
  ASSERT_TRUE(parse(withSource({{"live", {{"pass", 0}, {"attachment", 5}}}}), l, error)) << error;
  EXPECT_EQ(l.targets[0].source.live.attachment, 5);
  EXPECT_EQ(l.targets[0].source.live.subpass, -1);
  // The storage image a compute dispatch binds at set 0 binding 3 (inside the debug label "Resolve").
  ASSERT_TRUE(parse(withSource({{"live", {{"pass", "Resolve"}, {"storage", {{"set", 0}, {"binding", 3}}}}}}), l, error)) << error;
  EXPECT_EQ(l.targets[0].source.live.storageSet, 0);
  EXPECT_EQ(l.targets[0].source.live.storageBinding, 3);
  EXPECT_EQ(l.targets[0].source.live.pass, "Resolve");
}

TEST(LayoutLive, MistakesNameTheField) {
  const std::pair<json, std::string> cases[] = {
      {{{"live", {{"pass", 0}}}}, "source: live: name: give exactly one of"},
      {{{"live", {{"name", "a"}, {"color", 1}}}}, "source: live: name: give exactly one of"},
      {{{"live", {{"color", 9}}}}, "source: live: color: expected a colour attachment index 0..7"},
      {{{"live", {{"color", 1.5}}}}, "source: live: color: expected a colour attachment index 0..7"},
      {{{"live", {{"pass", -1}, {"color", 0}}}}, "source: live: pass: expected a label"},
      {{{"live", {{"format", "rgb99"}}}}, "source: live: format: unknown storage format \"rgb99\""},
      {{{"live", {{"name", "a"}, {"subpass", 1}}}}, "source: live: subpass: goes with \"color\": N or \"depth\": true"},
      {{{"live", {{"subpass", 64}, {"color", 0}}}}, "source: live: subpass: expected a subpass index 0..63"},
      {{{"live", {{"attachment", 2}, {"color", 0}}}}, "source: live: name: give exactly one of"},
      {{{"live", {{"attachment", -1}}}}, "source: live: attachment: expected the render pass's attachment index 0..63"},
      {{{"live", {{"name", "a"}, {"samples", 1}}}}, "source: live: samples: unknown field"},
      {{{"live", "a"}, {"file", "a.exr"}}, "source: live: a live source has no other fields"},
      {{{"live", ""}}, "source: live: expected an attachment's debug name"},
      {{{"live", 3}}, "source: live: expected a debug name or"},
      {{{"live", {{"storage", {{"set", 0}}}}}}, "source: live: storage: binding: expected a binding number"},
      {{{"live", {{"storage", {{"set", 32}, {"binding", 0}}}}}}, "source: live: storage: set: expected a set number 0..31"},
      {{{"live", {{"pass", 1}, {"storage", {{"set", 0}, {"binding", 0}}}}}}, "source: live: pass: with \"storage\": a debug label"},
      {{{"live", {{"name", "a"}, {"storage", {{"set", 0}, {"binding", 0}}}}}}, "source: live: name: give exactly one of"},
      {{{"live", {{"storage", 2}}}}, "source: live: storage: expected {\"set\": S"},
      {{{"live", {{"storage", {{"set", 0}, {"binding", 1}, {"index", 0}}}}}}, "source: live: storage: index: unknown field"},
  };
  for (const auto& [source, want] : cases) {
    Layout l;
    std::string error;
    EXPECT_FALSE(parse(withSource(source), l, error)) << source.dump();
    EXPECT_NE(error.find("l.json: targets[0]: \"albedo\": " + want), std::string::npos) << error;
  }
}

TEST(LayoutLive, RoundTripsThroughJson) {
  for (const json& source : {json{{"live", "a"}}, json{{"live", {{"pass", "L"}, {"color", 1}}}},
                             json{{"live", {{"pass", 2}, {"depth", true}}}}, json{{"live", {{"format", "r32f"}}}},
                             json{{"live", {{"pass", 0}, {"subpass", 1}, {"depth", true}}}}, json{{"live", {{"attachment", 3}}}},
                             json{{"live", {{"pass", "R"}, {"storage", {{"set", 1}, {"binding", 2}}}}}}}) {
    Layout a, b;
    std::string error;
    ASSERT_TRUE(parse(withSource(source), a, error)) << error;
    ASSERT_TRUE(parse(layoutJson(a), b, error)) << error;
    const TargetSource::LivePick &x = a.targets[0].source.live, &y = b.targets[0].source.live;
    EXPECT_EQ(b.targets[0].source.kind, TargetSource::Kind::Live);
    EXPECT_TRUE(x.pass == y.pass && x.passIndex == y.passIndex && x.name == y.name && x.color == y.color &&
                x.depth == y.depth && x.format == y.format && x.subpass == y.subpass && x.attachment == y.attachment &&
                x.storageSet == y.storageSet && x.storageBinding == y.storageBinding)
        << source.dump();
  }
}

TEST(LayoutLive, TheLayerIsAskedForWhatTheLayoutNames) {
  Layout l;
  std::string error;
  json j = withSource({{"live", {{"pass", "GBuffer"}, {"color", 1}}}});
  j["camera"] = {{"renderdoc", {{"buffer", "frame"}, {"clip_from_view", {{"offset", 0}}}, {"view_from_world", {{"offset", 64}}}}}};
  ASSERT_TRUE(parse(j, l, error)) << error;
  LiveOptions o;
  o.every = 3;
  const json r = liveRequest(l, o);
  EXPECT_EQ(r["type"], "request");
  EXPECT_EQ(r["every"], 3);
  EXPECT_EQ(r["camera"]["buffer"], "frame");
  EXPECT_EQ(r["camera"]["bytes"], 128);  // the last matrix's offset + 64
  ASSERT_EQ(r["targets"].size(), 2u);
  EXPECT_EQ(r["targets"][0]["live"]["pass"], "GBuffer");
  EXPECT_EQ(r["targets"][0]["live"]["color"], 1);
  EXPECT_EQ(r["targets"][0]["format"], "rgba8_srgb");
  EXPECT_EQ(r["targets"][0]["explicit"], true);
  // No source: the image of the target's name, not reported when the application has none.
  EXPECT_EQ(r["targets"][1]["live"]["name"], "z");
  EXPECT_EQ(r["targets"][1]["explicit"], false);

  ASSERT_TRUE(parse(withSource({{"renderdoc", "albedo_tex"}}), l, error)) << error;
  ASSERT_TRUE(liveLayout(l, error)) << error;
  EXPECT_EQ(l.targets[0].source.live.name, "albedo_tex");
  ASSERT_TRUE(parse(withSource({{"renderdoc", "#127"}}), l, error)) << error;
  EXPECT_FALSE(liveLayout(l, error));
  EXPECT_NE(error.find("targets[0]: \"albedo\": source.renderdoc: \"#127\" is a RenderDoc resource id"), std::string::npos) << error;
  ASSERT_TRUE(parse(withSource({{"file", "a.png"}}), l, error)) << error;
  EXPECT_FALSE(liveLayout(l, error));
  EXPECT_NE(error.find("targets[0]: \"albedo\": source.file: gblens attach streams render-pass attachments"), std::string::npos)
      << error;
}

}  // namespace
}  // namespace gb

namespace gb {
namespace {

json withLiveCamera(const json& camera) {
  json l = withSource({{"live", {{"pass", 0}, {"color", 0}}}});
  l["camera"] = camera;
  return l;
}

// camera.live (docs/layout-format.md): the bytes a render pass binds at a set / binding / index, or its
// push constants; the matrices' offsets count from the bound range's start.
TEST(LayoutLive, CameraLiveParsesRoundTripsAndIsRequested) {
  Layout l, back;
  std::string error;
  ASSERT_TRUE(parse(withLiveCamera({{"live", {{"pass", 0}, {"set", 0}, {"binding", 2}}},
                                    {"view_from_world", {{"offset", 64}}}, {"clip_from_view", {{"offset", 0}}}}),
                    l, error))
      << error;
  ASSERT_TRUE(l.camera.live);
  EXPECT_EQ(l.camera.live->passIndex, 0);
  EXPECT_EQ(l.camera.live->binding, 2u);
  EXPECT_EQ(l.camera.live->index, 0u);
  EXPECT_EQ(l.camera.live->matrices.viewOffset, 64u);
  EXPECT_EQ(l.camera.live->matrices.clipOffset, 0u);
  EXPECT_FALSE(l.camera.renderdoc);
  EXPECT_EQ(liveCameraText(*l.camera.live), "render pass 0, set 0 binding 2");
  ASSERT_TRUE(parse(layoutJson(l), back, error)) << error;
  ASSERT_TRUE(back.camera.live);
  EXPECT_EQ(back.camera.live->binding, 2u);
  EXPECT_EQ(back.camera.live->matrices.viewOffset, 64u);

  LiveOptions o;
  json r = liveRequest(l, o);
  EXPECT_EQ(r["camera"]["live"]["pass"], 0);
  EXPECT_EQ(r["camera"]["live"]["binding"], 2);
  EXPECT_EQ(r["camera"]["bytes"], 128);  // the last matrix's offset + 64, from the bound range's start
  EXPECT_FALSE(r.contains("bound_buffers"));
  o.boundBuffersPass = 3;
  r = liveRequest(l, o);
  EXPECT_EQ(r["bound_buffers"]["pass"], 3);
  EXPECT_EQ(r["bound_buffers"]["max_bytes"], 4u << 20);

  ASSERT_TRUE(parse(withLiveCamera({{"live", {{"pass", "GBuffer"}, {"push_constants", true}}}, {"matrix_order", "row_major"},
                                    {"world_from_view", {{"offset", 0}}}, {"clip_from_view", {{"offset", 64}}}}),
                    l, error))
      << error;
  EXPECT_TRUE(l.camera.live->pushConstants);
  EXPECT_TRUE(l.camera.live->matrices.worldFromView);
  EXPECT_TRUE(l.camera.live->matrices.rowMajor);
  EXPECT_EQ(liveCameraText(*l.camera.live), "render pass \"GBuffer\", push constants");
  ASSERT_TRUE(parse(layoutJson(l), back, error)) << error;
  EXPECT_TRUE(back.camera.live->pushConstants && back.camera.live->matrices.worldFromView && back.camera.live->matrices.rowMajor);
  EXPECT_EQ(liveRequest(l, o)["camera"]["live"]["push_constants"], true);
  // An import cannot read it: one line naming the field.
  EXPECT_NE(importCameraRefusal(l).find("l.json: camera: live: "), std::string::npos) << importCameraRefusal(l);
  ASSERT_TRUE(parse(withSource(nullptr), l, error)) << error;
  EXPECT_EQ(importCameraRefusal(l), "");
}

TEST(LayoutLive, CameraLiveMistakesNameTheField) {
  const json offsets = {{"view_from_world", {{"offset", 64}}}, {"clip_from_view", {{"offset", 0}}}};
  auto with = [&](json live, json extra = json::object()) {
    json c = offsets;
    c["live"] = std::move(live);
    for (auto& [k, v] : extra.items()) c[k] = v;
    return c;
  };
  const std::pair<json, std::string> cases[] = {
      {with({{"set", 0}, {"binding", 0}}), "camera: live: pass: expected a label"},
      {with({{"pass", -2}, {"set", 0}, {"binding", 0}}), "camera: live: pass: expected a label"},
      {with({{"pass", 0}, {"binding", 0}}), "camera: live: set: missing (or give \"push_constants\": true)"},
      {with({{"pass", 0}, {"set", 0}, {"binding", -1}}), "camera: live: binding: expected an integer"},
      {with({{"pass", 0}, {"push_constants", true}, {"set", 0}}), "camera: live: set: push constants have no set"},
      {with({{"pass", 0}, {"set", 0}, {"binding", 0}, {"offset", 4}}), "camera: live: offset: unknown field"},
      {with({{"pass", 0}, {"set", 0}, {"binding", 0}}, {{"clip_from_view", {{"offset", 6}}}}),
       "camera: clip_from_view: expected {\"offset\": BYTES} from the start of the bound range (a multiple of 4)"},
      {with({{"pass", 0}, {"set", 0}, {"binding", 0}}, {{"view_from_world", json::array({1, 0, 0, 0})}}),
       "camera: view_from_world: expected {\"offset\": BYTES}"},
      {with({{"pass", 0}, {"set", 0}, {"binding", 0}}, {{"renderdoc", {{"buffer", "b"}, {"view_from_world", {{"offset", 0}}},
                                                                        {"clip_from_view", {{"offset", 64}}}}}}),
       "camera: live: give one of \"live\", \"renderdoc\" and \"sidecar\""},
      {with(3), "camera: live: expected {\"pass\""},
  };
  for (const auto& [camera, want] : cases) {
    Layout l;
    std::string error;
    EXPECT_FALSE(parse(withLiveCamera(camera), l, error)) << camera.dump();
    EXPECT_NE(error.find("l.json: " + want), std::string::npos) << error;
  }
}

}  // namespace
}  // namespace gb
