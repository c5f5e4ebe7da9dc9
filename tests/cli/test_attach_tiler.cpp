// gblens attach on tests/subjects/tiler_deferred: a Vulkan 1.0 application (no device extension,
// render pass 1) whose G-buffer lives in one render pass of two subpasses, written by subpass 0 with
// DONT_CARE stores into transient images and read by subpass 1 as input attachments. Streamed with
// validation on, every attachment of the captured frame equals, bit for bit, the application's own
// read-back of that frame (its --dump, a run that stores and copies the G-buffer itself), and the
// frame is exactly the one --capture-frame names (the id target's clear value holds the frame index).
// The MSAA mode's 4x G-buffer (resolved in the lighting shader, no resolve attachment) streams every
// sample: each of them equals the application's own dump of that sample (a shader of its own that
// reads each sample into a buffer), and a capture keeps them all.
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>

#include <cstring>
#include <fstream>
#include <iterator>
#include <map>
#include <sstream>
#include <nlohmann/json.hpp>

#include "tests/cli/tiler_subject.h"
#include "tests/support/capture_util.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

using nlohmann::json;

using tiler_test::expectDumped;
using tiler_test::tiler;
using tiler_test::tilerBytes;
using tiler_test::tilerDir;

// attach --capture-frame `frame` of a 4-frame run in `mode` with the subject's own layout.
RunResult attachTiler(const std::string& dir, const std::string& mode, int frame, const std::string& env = "") {
  return runShell(env + " GBLENS_VALIDATE=1 '" + std::string(GBLENS_BINARY) + "' attach --layout '" + tilerDir() + "/layout_" +
                  mode + ".json' --capture-frame " + std::to_string(frame) + " -o '" + dir + "/live' -- '" + tiler() +
                  "' --mode " + mode + " --frames 4");
}

// The application's own dump of frame `k` of a 4-frame run in `mode`, then attach --capture-frame k
// (validation on in the application): every target of the dump's frame.json equals the capture's.
// The frame.json (null on a failure, reported) and the capture.
json dumpedAndStreamed(const std::string& dir, const std::string& mode, int k, Capture& c, std::string& output) {
  const RunResult dump = runShell("GBLENS_VALIDATE=1 '" + tiler() + "' --mode " + mode + " --frames 4 --dump '" + dir +
                                  "/dump' --dump-frame " + std::to_string(k));
  EXPECT_EQ(dump.exitCode, 0) << dump.output;
  const RunResult r = attachTiler(dir, mode, k);
  output = r.output;
  EXPECT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("exited with status"), std::string::npos) << r.output;  // validation clean
  EXPECT_NE(r.output.find("wrote application frame " + std::to_string(k)), std::string::npos) << r.output;
  std::string error;
  EXPECT_TRUE(loadCapture(dir + "/live", c, error)) << error;
  if (dump.exitCode != 0 || r.exitCode != 0 || !error.empty()) return json();
  const json frame = json::parse(std::ifstream(dir + "/dump/frame.json"));
  EXPECT_EQ(frame["frame"], k);
  for (const json& t : frame["targets"]) expectDumped(c, t["name"], dir + "/dump/" + t["files"][0].get<std::string>());
  return frame;
}

TEST(TilerAttach, ASubpassGBufferOfAVulkan10ApplicationIsItsOwnDumpOfTheFrameAskedFor) {
  const std::string dir = freshDir("attach_tiler_subpass");
  Capture c;
  std::string output;
  const json frame = dumpedAndStreamed(dir, "subpass", 2, c, output);
  ASSERT_TRUE(frame.is_object());
  EXPECT_EQ(frame["targets"].size(), 6u);
  // The frame asked for, by the application's own count: the id target's background is 0xF0000000 | k.
  const int id = c.frame.indexOf("id");
  ASSERT_GE(id, 0);
  uint32_t corner = 0;
  std::memcpy(&corner, c.frame.images[size_t(id)].image.data.data(), 4);
  EXPECT_EQ(corner, 0xF0000002u);
}

// --mode compute: albedo and normal written by a compute dispatch into storage images (bound through
// vkUpdateDescriptorSets and vkCmdBindDescriptorSets, named tiler.albedo / tiler.normal, moved to
// SHADER_READ_ONLY by a barrier before the lighting pass reads them), picked by name: every target of
// the frame asked for equals the application's own dump of it bit for bit, with validation on.
TEST(TilerAttach, AGBufferWrittenByComputeIsItsOwnDumpOfTheFrameAskedFor) {
  Capture c;
  std::string output;
  const std::string dir = freshDir("attach_tiler_compute");
  const json frame = dumpedAndStreamed(dir, "compute", 1, c, output);
  ASSERT_TRUE(frame.is_object());
  EXPECT_NE(output.find("albedo               rgba8_unorm    320x180  compute dispatch"), std::string::npos) << output;
  EXPECT_EQ(frame["targets"].size(), 5u);
  size_t storage = 0;
  for (const json& t : frame["targets"]) storage += t["render_pass"] == -1;
  EXPECT_EQ(storage, 2u);  // albedo and normal: no render pass holds them
  // A correct frame raises no fault (its normals were 0.2 % off unit before the subject renormalised them).
  const RunResult check = runShell("'" + std::string(GBLENS_BINARY) + "' check '" + dir + "/live'");
  EXPECT_EQ(check.exitCode, 0) << check.output;
  EXPECT_NE(check.output.find("clean: no fault"), std::string::npos) << check.output;
}

// A Vulkan 1.0 application's ring is shared memory too (the layer enables the instance and device
// extensions VK_EXT_external_memory_host needs): the layer's thread copies nothing out of it.
// `attach --frames K --stats` of `mode` with `env`: the JSON it prints (null, with the output in the
// failure, when it does not run or print one). The application renders 24 frames for the 2 or 3
// received: its first ones go without copies while the ring is made, and on a loaded machine the
// receiver, still busy, lets some go (8 were too few for 2 once under make test's load).
json tilerStats(const std::string& env, const std::string& mode, int frames) {
  const RunResult r = runShell(env + " GBLENS_VALIDATE=1 '" + std::string(GBLENS_BINARY) + "' attach --layout '" + tilerDir() +
                               "/layout_" + mode + ".json' --frames " + std::to_string(frames) + " --stats -- '" + tiler() +
                               "' --mode " + mode + " --frames 24");
  EXPECT_EQ(r.exitCode, 0) << r.output;
  const size_t brace = r.output.find("{\n");
  const json stats = brace == std::string::npos ? json() : json::parse(r.output.substr(brace, r.output.rfind('}') - brace + 1), nullptr, false);
  EXPECT_TRUE(stats.is_object()) << r.output;
  return stats.is_object() ? stats : json();
}

TEST(TilerAttach, AVulkan10ApplicationsRingIsSharedMemory) {
  const json stats = tilerStats("", "subpass", 3);
  ASSERT_TRUE(stats.is_object());
  EXPECT_EQ(stats["received"], 3);
  EXPECT_EQ(stats["layer"]["ring_shared"], true) << stats.dump();
  EXPECT_EQ(stats["layer"]["shm_bytes"], 0) << stats.dump();  // no file of the layer's own for copied-out frames
}

// The MSAA frame 1 attached with `env`: every sample of every target is the dump's.
// Every target of the dump's frame.json, every sample of each, equals the capture's; the number of
// multisampled planes compared.
size_t expectEverySampleDumped(const Capture& c, const json& frame, const std::string& dump) {
  size_t samples = 0;
  for (const json& t : frame["targets"]) {
    const std::string name = t["name"];
    const int count = t["samples"];
    EXPECT_EQ(t["files"].size(), size_t(count)) << name;
    if (count == 1) {
      expectDumped(c, name, dump + "/" + t["files"][0].get<std::string>());
      continue;
    }
    for (int k = 0; k < count; ++k, ++samples)
      expectDumped(c, name, dump + "/" + t["files"][size_t(k)].get<std::string>(), k);
    expectDumped(c, name, dump + "/" + t["files"][0].get<std::string>());  // the target's image is sample 0
  }
  return samples;
}

void expectEverySample(const std::string& dir, const std::string& env) {
  const RunResult dump = runShell("GBLENS_VALIDATE=1 '" + tiler() + "' --mode msaa --frames 4 --dump '" + dir +
                                  "/dump' --dump-frame 1");
  ASSERT_EQ(dump.exitCode, 0) << dump.output;
  const RunResult r = attachTiler(dir, "msaa", 1, env);
  ASSERT_EQ(r.exitCode, 0) << r.output;
  EXPECT_EQ(r.output.find("exited with status"), std::string::npos) << r.output;  // validation clean
  EXPECT_EQ(r.output.find("multisampled"), std::string::npos) << r.output;        // nothing refused
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/live", c, error)) << error;
  const json frame = json::parse(std::ifstream(dir + "/dump/frame.json"));
  ASSERT_EQ(frame["frame"], 1);
  // A capture with multisampled targets is of format version 2 (sample_files): a version-1 reader refuses it.
  EXPECT_EQ(json::parse(std::ifstream(dir + "/live/manifest.json"))["format_version"], 2);
  EXPECT_EQ(expectEverySampleDumped(c, frame, dir + "/dump"), 16u);  // albedo, normal, id, depth: 4 samples each
  // The samples differ somewhere (the subject's edges are multisampled), so a copy of sample 0 four times fails.
  const TargetImage& albedo = c.frame.images[size_t(c.frame.indexOf("albedo"))];
  ASSERT_EQ(albedo.samples.size(), 4u);
  EXPECT_NE(albedo.samples[0].data, albedo.samples[3].data);
  // The probe at an edge texel (found in the dump: its id samples differ) shows each sample's stored
  // bits as the dump has them, and the spread of the id's samples (two distinct values: 1).
  const std::string ids[2] = {tilerBytes(dir + "/dump/id.s0.bin"), tilerBytes(dir + "/dump/id.s3.bin")};
  const uint32_t width = frame["width"];
  size_t edge = 0;
  while (edge * 4 + 4 <= ids[0].size() && std::memcmp(ids[0].data() + edge * 4, ids[1].data() + edge * 4, 4) == 0) ++edge;
  ASSERT_LT(edge * 4 + 4, ids[0].size());
  const uint32_t x = uint32_t(edge % width), y = uint32_t(edge / width);
  const RunResult probe = runShell("'" + std::string(GBLENS_BINARY) + "' probe --json '" + dir + "/live' " + std::to_string(x) +
                                   " " + std::to_string(y));
  ASSERT_EQ(probe.exitCode, 0) << probe.output;
  const json dossier = json::parse(probe.output, nullptr, false);
  ASSERT_TRUE(dossier.is_object()) << probe.output;
  bool sawId = false;
  for (const json& t : dossier["targets"]) {
    if (t["target"] != "id") continue;
    sawId = true;
    ASSERT_EQ(t["samples"].size(), 4u) << t.dump();
    for (int k = 0; k < 4; ++k) {
      uint32_t stored = 0;
      const std::string bytes = tilerBytes(dir + "/dump/id.s" + std::to_string(k) + ".bin");
      std::memcpy(&stored, bytes.data() + edge * 4, 4);
      char hex[16];
      std::snprintf(hex, sizeof hex, "0x%08x", stored);
      EXPECT_EQ(t["samples"][size_t(k)][0]["bits"], hex) << k;
    }
    EXPECT_EQ(t["spread"][0], 1.0);
  }
  EXPECT_TRUE(sawId) << probe.output;
}

TEST(TilerAttach, EverySampleOfAMultisampledGBufferIsItsOwnDumpOfThatSample) {
  expectEverySample(freshDir("attach_tiler_msaa"), "");
}

// The staged ring of a discrete GPU (device-local ring buffers brought to the host after the frame;
// lavapipe has no queue to spare, so the download runs in the layer's batch on the application's
// queue): the same bits, its host buffers read in place (shared pages) or copied out.
TEST(TilerAttach, TheStagedRingStreamsTheSameBits) {
  expectEverySample(freshDir("attach_tiler_staged"), "GBLENS_LAYER_STAGED=1");
  expectEverySample(freshDir("attach_tiler_staged_copied"), "GBLENS_LAYER_STAGED=1 GBLENS_LAYER_STAGED_SHARED=0");
  const json stats = tilerStats("GBLENS_LAYER_STAGED=1", "msaa", 2);
  ASSERT_TRUE(stats.is_object());
  EXPECT_EQ(stats["layer"]["ring_staged"], true) << stats.dump();
  EXPECT_EQ(stats["layer"]["ring_download"], "application queue") << stats.dump();  // lavapipe: one queue
  EXPECT_EQ(stats["layer"]["ring_staged_shared"], true) << stats.dump();
  // GBLENS_LAYER_TILES=1: single-sampled attachments go image to image into the ring's tiles,
  // de-tiled by the download (AttachSequence.TheCopiedOutRing... compares their bits with the
  // application's dumps that way); off by default.
  const json single = tilerStats("GBLENS_LAYER_STAGED=1 GBLENS_LAYER_TILES=1", "subpass", 2);
  ASSERT_TRUE(single.is_object());
  EXPECT_GT(single["layer"]["ring_tile_copies"].get<int>(), 0) << single.dump();
  const json off = tilerStats("GBLENS_LAYER_STAGED=1", "subpass", 2);
  ASSERT_TRUE(off.is_object());
  EXPECT_EQ(off["layer"]["ring_tile_copies"], 0) << off.dump();
}

// The same MSAA G-buffer through RenderDoc: `renderdoccmd capture` of the subject's frame 1 (it
// brackets the frame with RenderDoc's in-application API), imported with a layout naming its
// textures by the resource ids RenderDoc lists (they have no names) and the camera by its uniform
// buffer: every sample of every target equals the application's own dump of that sample.
TEST(RenderDoc, AMultisampledCaptureImportsEverySampleAsTheApplicationsOwnDump) {
  const std::string dir = freshDir("rdc_tiler_msaa");
  const RunResult rec = runShell("timeout -k 5 120 renderdoccmd capture -w -c '" + dir + "/msaa' '" + tiler() +
                                 "' --mode msaa --frames 3 --capture-frame 1 --dump '" + dir + "/dump' --dump-frame 1");
  ASSERT_NE(rec.output.find("RenderDoc captured frame 1, dumped frame 1"), std::string::npos) << rec.output;
  const std::string rdc = dir + "/msaa_capture.rdc";
  ASSERT_TRUE(std::ifstream(rdc).good()) << rec.output;
  const RunResult list = runShell("'" + std::string(GBLENS_BINARY) + "' import '" + rdc + "' --list");
  ASSERT_EQ(list.exitCode, 0) << list.output;
  // RenderDoc's listing: "  2D Color Attachment 142      #142    R8G8B8A8_UNORM  320x180, 4 samples", and
  // the pass's uniform buffer "    uniform Buffer 133   #133   1024 bytes ...".
  std::map<std::string, std::string> idOfFormat;
  std::string uniform;
  std::istringstream lines(list.output);
  for (std::string line; std::getline(lines, line);) {
    std::istringstream words(line);
    std::vector<std::string> w{std::istream_iterator<std::string>(words), std::istream_iterator<std::string>()};
    for (size_t k = 0; k + 1 < w.size(); ++k)
      if (w[k].size() > 1 && w[k][0] == '#') {
        if (w[0] == "2D") idOfFormat[w[k + 1]] = w[k];
        if (w[0] == "uniform" && uniform.empty()) uniform = w[k];
        break;
      }
  }
  const json frame = json::parse(std::ifstream(dir + "/dump/frame.json"));
  const std::map<std::string, std::string> rdcFormat = {{"VK_FORMAT_R8G8B8A8_UNORM", "R8G8B8A8_UNORM"},
                                                        {"VK_FORMAT_A2B10G10R10_UNORM_PACK32", "R10G10B10A2_UNORM"},
                                                        {"VK_FORMAT_R32_UINT", "R32_UINT"},
                                                        {"VK_FORMAT_D32_SFLOAT", "D32"},
                                                        {"VK_FORMAT_R16G16B16A16_SFLOAT", "R16G16B16A16_FLOAT"}};
  // The multisampled G-buffer alone: RenderDoc 1.24's replay on lavapipe crashes now and then (about
  // one capture in three, the same capture not every time) when it replays the lighting pass that
  // reads those samples, so the single-sampled `lit` it writes is left out of this import.
  json layout = json::parse(std::ifstream(tilerDir() + "/layout_msaa.json"));
  auto withoutLit = [](const json& targets) {
    json kept = json::array();
    for (const json& t : targets)
      if (t["name"] != "lit") kept.push_back(t);
    return kept;
  };
  layout["targets"] = withoutLit(layout["targets"]);
  json gbuffer = frame;
  gbuffer["targets"] = withoutLit(frame["targets"]);
  ASSERT_EQ(gbuffer["targets"].size(), 4u);
  for (json& t : layout["targets"])
    for (const json& d : frame["targets"])
      if (d["name"] == t["name"]) {
        const std::string id = idOfFormat[rdcFormat.at(d["vk_format"].get<std::string>())];
        ASSERT_FALSE(id.empty()) << d.dump() << list.output;
        t["source"] = {{"renderdoc", id}};
      }
  ASSERT_FALSE(uniform.empty()) << list.output;
  const uint32_t at = frame["camera"]["uniform_buffer"]["dynamic_offset"];
  json& camera = layout["camera"];
  camera.erase("live");
  camera.erase("view_from_world");
  camera.erase("clip_from_view");
  camera["renderdoc"] = {{"buffer", uniform}, {"view_from_world", {{"offset", at + 16}}}, {"clip_from_view", {{"offset", at + 80}}}};
  std::ofstream(dir + "/layout.json") << layout.dump(2);
  const RunResult imp = runShell("'" + std::string(GBLENS_BINARY) + "' import '" + rdc + "' --layout '" + dir +
                                 "/layout.json' -o '" + dir + "/imported'");
  ASSERT_EQ(imp.exitCode, 0) << imp.output;
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir + "/imported", c, error)) << error;
  EXPECT_EQ(expectEverySampleDumped(c, gbuffer, dir + "/dump"), 16u);
  const TargetImage& depth = c.frame.images[size_t(c.frame.indexOf("depth"))];
  ASSERT_EQ(depth.samples.size(), 4u);
  EXPECT_NE(depth.samples[0].data, depth.samples[3].data);  // not one sample four times

  // --suggest-layout drafts the multisampled G-buffer as the subject's own layout says (from sample
  // 0's texels): its floor-filled frame once made the albedo's first two channels pass for an
  // octahedral normal. The draft also reads the lit target, so RenderDoc's replay crash (above) is
  // retried, named by its message.
  RunResult draft;
  for (int attempt = 0; attempt < 4; ++attempt) {
    draft = runShell("'" + std::string(GBLENS_BINARY) + "' import '" + rdc + "' --suggest-layout -o '" + dir + "/draft.json'");
    if (draft.output.find("RenderDoc's replay crashed") == std::string::npos) break;
  }
  ASSERT_EQ(draft.exitCode, 0) << draft.output;
  const json drafted = json::parse(std::ifstream(dir + "/draft.json"));
  std::map<std::string, std::string> truth;  // texture id -> the subject layout's first quantity
  for (const json& t : layout["targets"]) truth[t["source"]["renderdoc"]] = t["quantities"][0]["quantity"];
  size_t checked = 0;
  for (const json& t : drafted["targets"]) {
    const std::string id = t["source"]["renderdoc"];
    if (!truth.count(id)) continue;
    SCOPED_TRACE(id);
    ASSERT_FALSE(t["quantities"].empty()) << t.dump();
    EXPECT_EQ(t["quantities"][0]["quantity"], truth[id]) << t.dump();
    ++checked;
  }
  EXPECT_EQ(checked, 4u) << drafted.dump();
}

}  // namespace
// make bench's attach section for another application (`--attach-app`, bench_attach_app.cpp): the
// four variants of the Vulkan 1.0 subject, each timed, its frames streamed through shared memory;
// a command line without {frames}, or without its layout, is refused in one line naming the flag.
TEST(TilerAttach, TheBenchTimesAnotherApplicationsFourVariants) {
  const std::string dir = freshDir("attach_tiler_bench");
  const std::string app = "'" + tiler() + " --mode subpass --size 160x90 --frames {frames}'";
  const std::string common = "'" + std::string(GBLENS_BINARY) + "' bench --only attach --attach-rounds 1 --attach-soak 100 "
                             "--attach-frames 3 --attach-size 96x54 --attach-app-frames 4 --out '" + dir + "/out' --attach-app ";
  const RunResult r = runShell(common + app + " --attach-app-layout '" + tilerDir() + "/layout_subpass.json'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  const json bench = json::parse(std::ifstream(dir + "/out/bench.json"), nullptr, false);
  ASSERT_TRUE(bench.is_object() && bench.contains("attach_application")) << r.output;
  // gblens's own study has the viewer variants, each saying what the viewer took and the application copied.
  std::vector<std::string> own;
  for (const json& v : bench["attach"]["variants"]) {
    own.push_back(v["name"]);
    if (!v.contains("viewer")) continue;
    EXPECT_EQ(v["viewer"]["paced"], v["name"] == "viewer 60 Hz") << v.dump();
    ASSERT_EQ(v["viewer"]["taken"].size(), 1u) << v.dump();
    EXPECT_LE(v["viewer"]["copied_frames"][0], v["viewer"]["application_frames"][0]) << v.dump();
  }
  EXPECT_EQ(own, (std::vector<std::string>{"without", "idle", "every frame", "every 4th frame", "viewer 60 Hz",
                                           "viewer 60 Hz, unpaced"}));
  const json& a = bench["attach_application"];
  EXPECT_EQ(a["frames"], json::array({4, 16}));
  std::vector<std::string> names;
  for (const json& v : a["variants"]) {
    names.push_back(v["name"]);
    ASSERT_EQ(v["frame_ms"].size(), 1u) << v.dump();
    // Every run ended well (null: one failed); the value itself, a difference of two short runs'
    // wall times on a shared machine, is the bench's to report, not this test's to bound.
    EXPECT_TRUE(v["frame_ms"][0].is_number()) << v.dump();
  }
  EXPECT_EQ(names, (std::vector<std::string>{"without", "idle", "every frame", "every 4th frame"}));
  EXPECT_GE(a["streaming"]["received"].get<int>(), 4) << a.dump();  // of the longer run's 16 (the first wait for the ring; a loaded machine drops some)
  EXPECT_TRUE(a["streaming"]["layer"]["ring_shared"].get<bool>());    // a Vulkan 1.0 application too
  std::ifstream md(dir + "/out/bench.md");
  EXPECT_NE(std::string(std::istreambuf_iterator<char>(md), {}).find("the layer's cost for another application"), std::string::npos);
  const RunResult noLayout = runShell(common + app);
  EXPECT_EQ(noLayout.exitCode, 2);
  EXPECT_NE(noLayout.output.find("needs --attach-app-layout"), std::string::npos) << noLayout.output;
  const RunResult noFrames = runShell(common + "'" + tiler() + " --frames 4' --attach-app-layout x.json");
  EXPECT_EQ(noFrames.exitCode, 2);
  EXPECT_NE(noFrames.output.find("needs {frames}"), std::string::npos) << noFrames.output;
}

}  // namespace gb
