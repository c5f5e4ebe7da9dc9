// Layout files: gblens's own layout (assets/layouts/gblens.json) describes exactly the targets the
// renderer's target table makes, for every storage variant; every malformed layout is refused with
// a message naming the file, the target or quantity and the field; layouts round-trip through JSON.
#include <gtest/gtest.h>

#include "renderer/core/layout_json.h"
#include "renderer/core/targets.h"

namespace gb {

using json = nlohmann::json;

TEST(Layout, GblensLayoutDescribesTheTargetTableInEveryStorageVariant) {
  int variants = 0;
  for (const char* normal : {"rgba16f", "rgba8-snorm", "oct-rg16", "rgb10a2"})
    for (const char* depth : {"d32s8", "d24s8"})
      for (const char* accum : {"rgba16f", "rgba32f", "rgba8"})
        for (const char* shadow : {"d32f", "d16"})
          for (const char* position : {"depth", "rgba16f", "rgba32f"})
            for (const char* space : {"world", "camera"}) {
              RenderOptions o;
              std::string error;
              for (auto [n, v] : {std::pair{"normal_format", normal}, {"depth_format", depth}, {"accum_format", accum},
                                  {"shadow_format", shadow}, {"position", position}, {"position_space", space}})
                ASSERT_TRUE(setOption(o, n, v, error)) << error;
              const Layout& l = nativeLayout(o);
              ASSERT_EQ(l.targets.size(), targetTable().size());
              for (const TargetInfo& t : targetTable()) {
                const int i = l.findTarget(t.name);
                ASSERT_GE(i, 0) << t.name;
                EXPECT_EQ(l.targets[i].format.name, texelFormatInfo(t.format(o)).name) << t.name << " " << normal;
                // Octahedral normals store two channels (U, V); the third is unused whatever the table calls it.
                std::vector<std::string> expected = t.channels;
                if (std::string(normal) == "oct-rg16" && t.name == std::string("normal_shadow"))
                  expected = {"N.U", "N.V", "unused", "Shadow"};
                EXPECT_EQ(l.targets[i].channels, expected) << t.name;
              }
              ++variants;
            }
  EXPECT_EQ(variants, 4 * 2 * 3 * 2 * 3 * 2);
}

TEST(Layout, OctahedralNormalsUseTwoChannelsAndTheOthersThree) {
  RenderOptions o;
  std::string error;
  ASSERT_TRUE(setOption(o, "normal_format", "oct-rg16", error));
  const Quantity* n = nativeLayout(o).find(QuantityKind::Normal);
  ASSERT_NE(n, nullptr);
  EXPECT_EQ(n->normal, NormalEncoding::Octahedral);
  EXPECT_EQ(n->channels, (std::vector<uint32_t>{0, 1}));
  ASSERT_TRUE(setOption(o, "normal_format", "rgb10a2", error));
  n = nativeLayout(o).find(QuantityKind::Normal);
  EXPECT_EQ(n->normal, NormalEncoding::XyzUnorm);
  EXPECT_EQ(n->channels.size(), 3u);
}

static json minimal() {
  return json::parse(R"({"format": "gblens-layout", "version": 1, "size": [4, 2], "targets": [
    {"name": "gbuf", "format": "rgba16f", "quantities": [
      {"quantity": "normal", "name": "N", "channels": [0, 1], "encoding": "octahedral"},
      {"quantity": "roughness", "channels": [2]}]},
    {"name": "z", "format": "r32f", "quantities": [{"quantity": "depth", "channels": [0], "encoding": "eye"}]}],
    "camera": {"view_from_world": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1],
               "clip_from_view": [1,0,0,0, 0,1,0,0, 0,0,-1,-1, 0,0,-0.1,0], "convention": "gl"}})");
}

TEST(Layout, ReadsAndRoundTripsThroughJson) {
  Layout l;
  std::string error;
  ASSERT_TRUE(parseLayout(minimal(), "my.json", l, error)) << error;
  ASSERT_EQ(l.targets.size(), 2u);
  EXPECT_EQ(l.targets[0].channels, (std::vector<std::string>{"N.X", "N.Y", "roughness", "C3"}));
  EXPECT_EQ(l.quantities.size(), 3u);
  EXPECT_EQ(l.camera.convention, LayoutCamera::Convention::Gl);
  Layout again;
  ASSERT_TRUE(parseLayout(layoutJson(l), "again", again, error)) << error;
  EXPECT_EQ(layoutJson(again), layoutJson(l));
}

// Each malformed case: (what to change, the text the one-line message must contain).
TEST(Layout, EveryMalformedLayoutNamesTheFileTheTargetAndTheField) {
  struct Case {
    std::string pointer;  // JSON pointer of the value to replace ("" : remove `remove`)
    json value;
    std::string expected;
  };
  const std::vector<Case> cases = {
      {"/format", "nope", "my.json: format: expected \"gblens-layout\""},
      {"/version", 2, "my.json: version: this gblens reads version 1"},
      {"/targets/0/format", "rgba9_unorm", "targets[0]: \"gbuf\": format: unknown storage format \"rgba9_unorm\""},
      {"/targets/0/quantities/0/encoding", "octahedral_wrong", "quantities[0] \"N\": encoding: \"octahedral_wrong\" is not one of"},
      {"/targets/0/quantities/0/channels", json::array({0, 1, 2}), "encoding \"octahedral\" needs 2 channels, has 3"},
      {"/targets/0/quantities/0/channels", json::array({0, 7}), "channels: channel 7 is beyond the 4 channels of format rgba16f"},
      {"/targets/0/quantities/1/quantity", "colour", "quantity: unknown kind \"colour\""},
      {"/targets/1/name", "gbuf", "targets[1]: name: \"gbuf\" names another target too"},
      {"/targets/1/name", "Z Buffer", "name: \"Z Buffer\": use a-z, 0-9 and _"},
      {"/targets/1/quantities/0/encoding", "linear", "\"z\": quantities[0]: encoding: \"linear\" is not one of hardware, eye, radial"},
      {"/targets/1/format", "r32_uint", ""},  // eye depth in integers is allowed; hardware is not (next)
      {"/camera/clip_from_view", json::array({0, 0, 0, 0, 0, 1, 0, 0, 0, 0, -1, -1, 0, 0, -0.1, 0}), "camera: clip_from_view: the matrix is singular"},
      {"/camera/view_from_world", json::array({1, 2, 3}), "camera: view_from_world: expected 16 numbers"},
      {"/camera/convention", "opengl", "camera: convention: \"opengl\" is not one of vulkan, d3d, gl"},
      {"/size", json::array({0, 5}), "my.json: size: expected [width, height]"},
      {"/targets/0/colour", 1, "\"gbuf\": colour: unknown field"},
  };
  for (const Case& c : cases) {
    json j = minimal();
    j[json::json_pointer(c.pointer)] = c.value;
    Layout l;
    std::string error;
    const bool ok = parseLayout(j, "my.json", l, error);
    if (c.expected.empty()) {
      EXPECT_TRUE(ok) << c.pointer << ": " << error;
      continue;
    }
    EXPECT_FALSE(ok) << c.pointer;
    EXPECT_NE(error.find(c.expected), std::string::npos) << c.pointer << ": got \"" << error << "\"";
    EXPECT_EQ(error.find('\n'), std::string::npos) << "one line: " << error;
  }
  json j = minimal();
  j["targets"][1]["format"] = "r32_uint";
  j["targets"][1]["quantities"][0]["encoding"] = "hardware";
  Layout l;
  std::string error;
  EXPECT_FALSE(parseLayout(j, "my.json", l, error));
  EXPECT_NE(error.find("hardware depth cannot be held by the integer format r32_uint"), std::string::npos) << error;
}

TEST(Layout, ParametersPickCasesAndWhenDropsTargets) {
  json j = json::parse(R"({"format": "gblens-layout", "version": 1, "targets": [
    {"name": "a", "format": {"by": "normal_format", "cases": {"rgba16f": "rgba16f", "oct-rg16": "rg16_snorm"}},
     "quantities": [{"quantity": "scalar", "channels": [0]}]},
    {"name": "b", "when": {"position": ["rgba32f"]}, "format": "r32f", "quantities": [{"quantity": "scalar", "name": "s2", "channels": [0]}]}]})");
  RenderOptions o;
  std::string error;
  ASSERT_TRUE(setOption(o, "normal_format", "oct-rg16", error));
  json r = j;
  ASSERT_TRUE(resolveLayoutParameters(r, layoutParameters(o), "p.json", error)) << error;
  Layout l;
  ASSERT_TRUE(parseLayout(r, "p.json", l, error)) << error;
  EXPECT_EQ(l.targets.size(), 1u);
  EXPECT_EQ(l.targets[0].format.name, "rg16_snorm");
  ASSERT_TRUE(setOption(o, "normal_format", "rgb10a2", error));
  r = j;
  EXPECT_FALSE(resolveLayoutParameters(r, layoutParameters(o), "p.json", error));
  EXPECT_NE(error.find("no case for normal_format = rgb10a2"), std::string::npos) << error;
}

}  // namespace gb
