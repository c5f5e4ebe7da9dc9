// `gblens attach --suggest`'s draft layout (views/infer/suggest_live.cpp) from a report of one
// frame's passes written here by hand as the layer reports them: for foreign_deferred's four passes
// (its README's table: pass 0 writes position, normal, albedo and depth; passes 1-3 occlusion, hdr,
// final), and for vkcube's one named pass. The G-buffer pass, the targets, their formats and live
// sources are the ones the README names; the draft parses, and becomes a layer request as it is.
#include <gtest/gtest.h>

#include "renderer/core/layout_json.h"
#include "views/live/live.h"
#include "views/infer/suggest_live.h"

namespace gb {
namespace {

using json = nlohmann::json;

json attachment(const std::string& role, const std::string& format, const std::string& image = "", uint32_t w = 320) {
  return {{"role", role}, {"image", image}, {"format", format}, {"vk_format", "VK_FORMAT_X"}, {"width", w}, {"height", 180},
          {"why", ""}};
}

json pass(int ordinal, json attachments) {
  return {{"ordinal", ordinal}, {"labels", json::array()}, {"render_pass", ""}, {"attachments", attachments}};
}

TEST(SuggestLive, ForeignDeferredsGBufferPassAndLaterTargets) {
  json report = {{"frame", 0},
                 {"passes", {pass(0, {attachment("color 0", "rgba32f"), attachment("color 1", "rgba8_unorm"),
                                      attachment("color 2", "rgba8_srgb"), attachment("depth", "d32f")}),
                             pass(1, {attachment("color 0", "r8_unorm")}), pass(2, {attachment("color 0", "rgba16f")}),
                             pass(3, {attachment("color 0", "rgba8_unorm")}),
                             pass(4, {attachment("color 0", "rgba8_unorm", "", 64)})}}};  // another size: left out
  std::vector<std::string> summary;
  const json draft = draftLiveLayout(report, summary);
  ASSERT_EQ(draft["targets"].size(), 7u) << draft.dump(2);
  const std::vector<std::pair<std::string, json>> expected = {
      {"rgba32f", {{"pass", 0}, {"color", 0}}}, {"rgba8_unorm", {{"pass", 0}, {"color", 1}}},
      {"rgba8_srgb", {{"pass", 0}, {"color", 2}}}, {"d32f", {{"pass", 0}, {"depth", true}}},
      {"r8_unorm", {{"pass", 1}, {"color", 0}}}, {"rgba16f", {{"pass", 2}, {"color", 0}}},
      {"rgba8_unorm", {{"pass", 3}, {"color", 0}}}};
  for (size_t t = 0; t < expected.size(); ++t) {
    EXPECT_EQ(draft["targets"][t]["format"], expected[t].first) << t;
    EXPECT_EQ(draft["targets"][t]["source"]["live"], expected[t].second) << t;
  }
  EXPECT_EQ(summary.front(), "G-buffer pass: #0 (the most colour targets with a depth target; the frame says nothing of what reads "
                             "them)");
  Layout layout;
  std::string error;
  ASSERT_TRUE(parseLayout(draft, "draft", layout, error)) << error;
  EXPECT_TRUE(liveLayout(layout, error)) << error;  // every source streams
}

TEST(SuggestLive, NamedImagesArePickedByName) {
  json p = pass(0, {attachment("color 0", "rgba8_unorm", "SwapchainImage(0)", 500), attachment("depth", "d16", "DepthImage", 500)});
  p["labels"] = {"DrawBegin", "InsideRenderPass"};
  std::vector<std::string> summary;
  const json draft = draftLiveLayout({{"frame", 0}, {"passes", {p}}}, summary);
  ASSERT_EQ(draft["targets"].size(), 2u);
  EXPECT_EQ(draft["targets"][0]["source"]["live"], json({{"name", "SwapchainImage(0)"}}));
  EXPECT_EQ(draft["targets"][1]["source"]["live"], json({{"name", "DepthImage"}}));
  EXPECT_EQ(draft["targets"][1]["format"], "d16");
  const std::string text = describeLivePasses({{"application", "vkcube"}, {"device", "llvmpipe"}}, {{"frame", 0}, {"passes", {p}}});
  EXPECT_NE(text.find("#0   DrawBegin > InsideRenderPass"), std::string::npos) << text;
  EXPECT_NE(text.find("source: {\"live\":{\"name\":\"DepthImage\"}}"), std::string::npos) << text;
}

// The store ops per aspect (the layer reports the application's own): a stored depth with a DONT_CARE
// stencil is a stencil not stored (gbuffer_zoo --mode stencil_dontcare), not the whole attachment.
TEST(SuggestLive, WhatTheApplicationDoesNotStoreIsNamedPerAspect) {
  auto depth = [](const std::string& format, json store, json stencil, bool patched) {
    json a = attachment("depth", format);
    a["store"] = store, a["stencil_store"] = stencil, a["store_patched"] = patched;
    return a;
  };
  auto text = [](const json& a) {
    return describeLivePasses({{"application", "zoo"}, {"device", "llvmpipe"}}, {{"frame", 0}, {"passes", {pass(0, {a})}}});
  };
  EXPECT_NE(text(depth("d32s8", "store", "dont_care", true)).find("(stencil not stored by the application: gblens stores it)"),
            std::string::npos);
  EXPECT_NE(text(depth("d32f", "dont_care", nullptr, true)).find("(not stored by the application: gblens stores it)"),
            std::string::npos);
  EXPECT_NE(text(depth("d24s8", "dont_care", "dont_care", true)).find("(depth and stencil not stored by the application"),
            std::string::npos);
  EXPECT_EQ(text(depth("d24s8", "store", "store", false)).find("not stored"), std::string::npos);
  EXPECT_NE(text(depth("d16", "none", nullptr, false)).find("(not stored by the application)"), std::string::npos);
}

TEST(SuggestLive, NothingALayoutCanHold) {
  json bad = attachment("color 0", "");
  bad["why"] = "BGRA packed";
  std::vector<std::string> summary;
  const json draft = draftLiveLayout({{"frame", 0}, {"passes", {pass(0, {bad})}}}, summary);
  EXPECT_TRUE(draft["targets"].empty());
  EXPECT_EQ(summary.front(), "no render pass writes an attachment a layout can hold");
}

}  // namespace
}  // namespace gb

namespace gb {
namespace {

// A visibility-buffer frame as the layer reports it, written by hand: pass 0 draws depth and a
// triangle id, which a dispatch after it reads; that dispatch binds three storage images of the
// frame's size and one smaller (a histogram); pass 1 lights from them. No render pass's colour
// targets are read together, so the draft would call it forward rendering: the summary says compute
// may write the G-buffer, and names each frame-sized storage image, once, with a source (its name;
// unnamed: its set and binding in the innermost label), drafting none of them.
TEST(SuggestLive, StorageImagesComputeBindsAreNamedNotDrafted) {
  auto storage = [](int id, const std::string& image, const std::string& format, uint32_t binding, uint32_t w = 320) {
    return json{{"image", image}, {"view", ""}, {"image_id", id}, {"format", format}, {"vk_format", "VK_FORMAT_X"},
                {"width", w}, {"height", 180}, {"samples", 1}, {"set", 1}, {"binding", binding},
                {"labels", {"frame", "resolve"}}, {"why", ""}};
  };
  json p0 = pass(0, {attachment("depth", "d32f"), attachment("color 0", "r32_uint")});
  p0["attachments"][0]["image_id"] = 1, p0["attachments"][1]["image_id"] = 2;
  p0["reads"] = json::array(), p0["reads_after"] = {1, 2, 3, 4, 5};
  p0["storage_after"] = {storage(3, "gb.albedo", "rgba8_unorm", 2), storage(4, "", "rgba16f", 3),
                         storage(5, "gb.depth", "r32f", 4), storage(6, "histogram", "r32_uint", 5, 64),
                         storage(3, "gb.albedo", "rgba8_unorm", 2)};
  json p1 = pass(1, {attachment("color 0", "rgba16f")});
  p1["attachments"][0]["image_id"] = 7;
  p1["reads"] = {3, 4, 5}, p1["reads_after"] = json::array();
  std::vector<std::string> summary;
  const json report = {{"frame", 0}, {"passes", {p0, p1}}};
  const json draft = draftLiveLayout(report, summary);
  ASSERT_EQ(draft["targets"].size(), 3u) << draft.dump(2);  // depth, id, and pass 1's colour: no storage image
  std::string all;
  for (const std::string& line : summary) all += line + "\n";
  EXPECT_NE(all.find("; or compute writes it: dispatches bind 3 storage images of the frame's size (below)"), std::string::npos)
      << all;
  EXPECT_NE(all.find("not drafted: storage image gb.albedo (rgba8_unorm) bound by compute after #0: "), std::string::npos) << all;
  EXPECT_NE(all.find("\"source\": {\"live\":{\"pass\":\"resolve\",\"storage\":{\"binding\":3,\"set\":1}}}"), std::string::npos)
      << all;
  EXPECT_NE(all.find("\"source\": {\"live\":{\"name\":\"gb.depth\"}}"), std::string::npos) << all;
  EXPECT_EQ(all.find("histogram"), std::string::npos) << all;  // another size
  size_t notes = 0;
  for (size_t at = all.find("not drafted:"); at != std::string::npos; at = all.find("not drafted:", at + 1)) ++notes;
  EXPECT_EQ(notes, 3u) << all;
  // The printed report lists all four where the dispatch binds them.
  const std::string text = describeLivePasses({{"application", "vb"}, {"device", "llvmpipe"}}, report);
  EXPECT_NE(text.find("(bound by a compute dispatch after it, set 1 binding 5)"), std::string::npos) << text;
  // The source printed for the unnamed one streams: it parses as a live pick.
  json layout = draft;
  layout["targets"].push_back({{"name", "n"}, {"format", "rgba16f"},
                               {"source", {{"live", {{"pass", "resolve"}, {"storage", {{"set", 1}, {"binding", 3}}}}}}},
                               {"quantities", {{{"quantity", "vector"}, {"name", "nv"}, {"channels", {0, 1, 2, 3}}}}}});
  Layout l;
  std::string error;
  ASSERT_TRUE(parseLayout(layout, "draft", l, error)) << error;
  EXPECT_TRUE(liveLayout(l, error)) << error;
}

}  // namespace
}  // namespace gb
