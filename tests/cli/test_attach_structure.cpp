// The frame's structure as the layer reports it (--suggest), checked against what the test subjects'
// own READMEs and truth files say (never against gblens's guesses): per pass the attachments' image
// ids, the application's own load/store ops per aspect, the images its draws may read and those read
// after it; for vkcube, the swapchain image it presents. Validation on in every application.
// The bound buffers and camera.live: test_attach_buffers.cpp.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <fstream>
#include <set>

#include "tests/cli/attach_util.h"
#include "tests/gui/gui_util.h"
#include "tests/support/capture_util.h"
#include "views/infer/suggest_live.h"

namespace gb {
namespace {

using json = nlohmann::json;
using attach::passesReport;

std::set<uint32_t> ids(const json& list) { return list.get<std::set<uint32_t>>(); }

// The image id of each attachment, by pass and attachment index.
std::vector<std::vector<uint32_t>> imageIds(const json& passes) {
  std::vector<std::vector<uint32_t>> out;
  for (const json& p : passes) {
    out.emplace_back();
    for (const json& a : p["attachments"]) out.back().push_back(a["image_id"].get<uint32_t>());
  }
  return out;
}

// foreign_deferred's README: pass 1 writes position, normal, albedo and a D32 depth, pass 2 occlusion
// (reading position and normal), pass 3 hdr (the G-buffer and occlusion), pass 4 final (hdr); every
// attachment cleared and stored; nothing runs between the passes; no swapchain.
TEST(AttachStructure, ForeignDeferredsPassesReadsAndStoreOps) {
  const std::string dir = freshDir("attach_structure_foreign");
  const attach::Report r = passesReport({FOREIGN_DEFERRED_BINARY, "--frames", "2"}, {}, dir);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.status, 0) << r.log;  // validation clean
  const json& passes = r.passes["passes"];
  ASSERT_EQ(passes.size(), 4u) << r.passes.dump(1);
  const std::vector<std::vector<std::string>> formats = {
      {"VK_FORMAT_R32G32B32A32_SFLOAT", "VK_FORMAT_R8G8B8A8_UNORM", "VK_FORMAT_R8G8B8A8_SRGB", "VK_FORMAT_D32_SFLOAT"},
      {"VK_FORMAT_R8_UNORM"}, {"VK_FORMAT_R16G16B16A16_SFLOAT"}, {"VK_FORMAT_R8G8B8A8_UNORM"}};
  std::set<uint32_t> all;
  for (size_t p = 0; p < passes.size(); ++p) {
    ASSERT_EQ(passes[p]["attachments"].size(), formats[p].size()) << p;
    for (size_t a = 0; a < formats[p].size(); ++a) {
      const json& at = passes[p]["attachments"][a];
      SCOPED_TRACE("pass " + std::to_string(p) + " attachment " + std::to_string(a));
      EXPECT_EQ(at["vk_format"], formats[p][a]);
      EXPECT_EQ(at["load"], "clear");
      EXPECT_EQ(at["store"], "store");
      EXPECT_TRUE(at["stencil_store"].is_null());  // D32_SFLOAT has no stencil
      EXPECT_EQ(at["presented"], false);
      all.insert(at["image_id"].get<uint32_t>());
    }
    EXPECT_TRUE(passes[p]["reads_after"].empty()) << p;
  }
  EXPECT_EQ(all.size(), 7u);  // seven images, one id each
  const auto id = imageIds(passes);
  EXPECT_TRUE(ids(passes[0]["reads"]).empty());
  EXPECT_EQ(ids(passes[1]["reads"]), (std::set<uint32_t>{id[0][0], id[0][1]}));
  EXPECT_EQ(ids(passes[2]["reads"]), (std::set<uint32_t>{id[0][0], id[0][1], id[0][2], id[1][0]}));
  EXPECT_EQ(ids(passes[3]["reads"]), (std::set<uint32_t>{id[2][0]}));
  EXPECT_TRUE(r.passes["presented"].empty());
}

// gbuffer_zoo's truth files (written by hand from its code): every pass of every mode, its
// attachments' formats and store ops per aspect, and what it samples ([pass, attachment] pairs).
TEST(AttachStructure, GBufferZooMatchesItsTruthFiles) {
  const std::string dir = freshDir("attach_structure_zoo");
  for (const char* mode : {"world_tbn", "forward", "lighting_depth", "stencil_dontcare", "linear_depth", "view_oct", "y_down"}) {
    SCOPED_TRACE(mode);
    const json truth = json::parse(std::ifstream(std::string(GBUFFER_ZOO_DIR) + "/truth/" + mode + ".json"));
    const attach::Report r = passesReport({GBUFFER_ZOO_BINARY, "--mode", mode, "--frames", "1"}, {}, dir + "/" + mode);
    ASSERT_TRUE(r.error.empty()) << r.error;
    EXPECT_EQ(r.status, 0) << r.log;
    const json& passes = r.passes["passes"];
    ASSERT_EQ(passes.size(), truth["passes"].size());
    const auto id = imageIds(passes);
    for (size_t p = 0; p < passes.size(); ++p) {
      const json& want = truth["passes"][p];
      ASSERT_EQ(passes[p]["attachments"].size(), want["attachments"].size()) << p;
      for (size_t a = 0; a < want["attachments"].size(); ++a) {
        const json &at = passes[p]["attachments"][a], &w = want["attachments"][a];
        SCOPED_TRACE("pass " + std::to_string(p) + " attachment " + std::to_string(a));
        EXPECT_EQ(at["vk_format"], w["vk_format"]);
        EXPECT_EQ(at["store"], w["store"]);
        EXPECT_EQ(at["stencil_store"], w["stencil_store"]);
        EXPECT_EQ(at["load"], "clear");  // README: every attachment is cleared
      }
      std::set<uint32_t> samples;
      for (const json& s : want["samples"]) samples.insert(id[s[0].get<size_t>()][s[1].get<size_t>()]);
      EXPECT_EQ(ids(passes[p]["reads"]), samples) << p;
      EXPECT_TRUE(passes[p]["reads_after"].empty()) << p;  // one command buffer of render passes, no compute
    }
    EXPECT_TRUE(r.passes["presented"].empty());
    // What people read: only the aspect the application does not store is named.
    const std::string text = describeLivePasses(r.hello, r.passes);
    if (std::string(mode) == "stencil_dontcare")
      EXPECT_NE(text.find("(stencil not stored by the application: gblens stores it)"), std::string::npos) << text;
    if (std::string(mode) == "linear_depth")
      EXPECT_NE(text.find("(not stored by the application: gblens stores it)"), std::string::npos) << text;
    if (std::string(mode) != "stencil_dontcare" && std::string(mode) != "linear_depth")
      EXPECT_EQ(text.find("not stored"), std::string::npos) << text;
  }
}

// vkcube (cube.c: one render pass into the swapchain image, colour STORE, D16 depth DONT_CARE) under
// an Xvfb of the test's own: the colour attachment is the image it presents.
TEST(AttachStructure, VkcubesPresentedImage) {
  if (!gui::haveTool("Xvfb") || !gui::haveTool("vkcube")) GTEST_SKIP() << "needs Xvfb and vkcube";
  gui::Xvfb x;
  std::string error;
  ASSERT_TRUE(x.start(800, 600, error)) << error;
  const std::string dir = freshDir("attach_structure_vkcube");
  const attach::Report r = passesReport({"vkcube", "--c", "30", "--validate"}, {"DISPLAY=" + x.display, attach::kSyncValidation}, dir);
  x.stop();
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.log.find("VALIDATION"), std::string::npos) << r.log;
  const json& passes = r.passes["passes"];
  ASSERT_EQ(passes.size(), 1u) << r.passes.dump(1);
  const json& colour = passes[0]["attachments"][0];
  const json& depth = passes[0]["attachments"][1];
  EXPECT_EQ(colour["role"], "color 0");
  EXPECT_EQ(colour["presented"], true);
  EXPECT_EQ(colour["store"], "store");
  EXPECT_EQ(depth["role"], "depth");
  EXPECT_EQ(depth["presented"], false);
  EXPECT_EQ(depth["store"], "dont_care");
  EXPECT_EQ(depth["store_patched"], true);  // the layer stores it to copy it, as the application never sees
  EXPECT_EQ(ids(r.passes["presented"]), (std::set<uint32_t>{colour["image_id"].get<uint32_t>()}));
}

// gblens's own renderer as an application that names its images: with the tiled method and the
// compute tone map, the G-buffer is read by the tiled lighting's compute dispatch after the G-buffer
// pass (renderer/passes/tiled_lighting.cpp: gbufferReads, albedo, normal and the position source,
// with --eye-depth on the R32F eye depth "depth"), not by the pass's own draws.
TEST(AttachStructure, ComputeAfterAPassReadsItsAttachments) {
  const std::string dir = freshDir("attach_structure_gblens");
  const attach::Report r = passesReport({GBLENS_BINARY, "render", "--size", "96x54", "--lights", "8", "--method", "tiled",
                                         "--tonemap-pass", "compute", "--eye-depth", "on", "--frames", "2", "--validate", "-o", dir + "/f.png"},
                                        {}, dir);
  ASSERT_TRUE(r.error.empty()) << r.error;
  EXPECT_EQ(r.status, 0) << r.log;
  const json* gbuffer = nullptr;
  std::map<std::string, uint32_t> named;
  for (const json& p : r.passes["passes"])
    for (const json& a : p["attachments"]) {
      named[a["image"].get<std::string>()] = a["image_id"].get<uint32_t>();
      if (a["image"] == "albedo_specular") gbuffer = &p;
    }
  ASSERT_TRUE(gbuffer) << r.passes.dump(1);
  const std::set<uint32_t> after = ids((*gbuffer)["reads_after"]), reads = ids((*gbuffer)["reads"]);
  for (const char* image : {"albedo_specular", "normal_shadow", "depth"}) {
    ASSERT_TRUE(named.count(image)) << image;
    EXPECT_TRUE(after.count(named[image])) << image << "\n" << gbuffer->dump(1);
    EXPECT_FALSE(reads.count(named[image])) << image;
  }
}

}  // namespace
}  // namespace gb
