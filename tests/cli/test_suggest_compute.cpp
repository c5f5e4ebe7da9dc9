// What `--suggest` leaves out of a draft, and says so: a G-buffer written by compute
// (tests/subjects/tiler_deferred --mode compute: its resolve dispatch writes albedo and normal into
// storage images no render pass holds). Live (attach --suggest, the layer's storage_after) and from a
// RenderDoc capture (import --suggest-layout, RenderDoc's CS_RWResource), each storage image is named
// with the source that picks it and none is drafted; a layout of those sources alone reads each as the
// application's own dump of the frame, bit for bit.
#include <gtest/gtest.h>

#include <fstream>
#include <sstream>
#include <nlohmann/json.hpp>

#include "renderer/core/layout.h"
#include "tests/cli/tiler_subject.h"
#include "tests/support/capture_util.h"
#include "tests/support/test_paths.h"
#include "views/capture/capture.h"

namespace gb {
namespace {

using nlohmann::json;
using tiler_test::expectDumped;
using tiler_test::tiler;

// The layout the "not drafted: <what> NAME (FORMAT) ... \"source\": SOURCE" lines of `output`
// give, a target per storage image of the dump's frame.json (named as the dump names it, found by
// its debug name), its channels a stored vector; null with a failure when a line is missing.
json layoutOfNotes(const std::string& output, const std::string& what, const json& frame) {
  json layout = {{"format", "gblens-layout"}, {"version", 1}, {"name", "the notes' sources"}, {"targets", json::array()}};
  size_t notes = 0;
  for (size_t at = output.find("not drafted: "); at != std::string::npos; at = output.find("not drafted: ", at + 1)) ++notes;
  EXPECT_EQ(notes, 2u) << output;
  for (const json& t : frame["targets"]) {
    if (t["render_pass"] != -1) continue;  // the storage images
    const std::string name = t["debug_name"], note = "not drafted: " + what + " " + name + " (";
    const size_t at = output.find(note);
    EXPECT_NE(at, std::string::npos) << name << "\n" << output;
    if (at == std::string::npos) return json();
    const std::string line = output.substr(at, output.find('\n', at) - at);
    const size_t source = line.find("\"source\": ");
    const std::string format = line.substr(note.size(), line.find(')', note.size()) - note.size());
    StorageFormat f;
    EXPECT_TRUE(source != std::string::npos && parseStorageFormat(format, f)) << line;
    if (source == std::string::npos || !parseStorageFormat(format, f)) return json();
    json channels = json::array();
    for (uint32_t c = 0; c < f.channels; ++c) channels.push_back(c);
    layout["targets"].push_back({{"name", t["name"]}, {"format", format}, {"source", json::parse(line.substr(source + 10))},
                                 {"quantities", {{{"quantity", "vector"}, {"name", t["name"].get<std::string>() + "_v"},
                                                  {"channels", channels}}}}});
  }
  EXPECT_EQ(layout["targets"].size(), 2u);
  return layout["targets"].size() == 2u ? layout : json();
}

// Each target of `layout` in the capture at `dir` equals the dump's file of that name.
void expectNotesDumped(const std::string& dir, const json& layout, const json& frame) {
  Capture c;
  std::string error;
  ASSERT_TRUE(loadCapture(dir, c, error)) << error;
  for (const json& t : layout["targets"])
    for (const json& d : frame["targets"])
      if (d["name"] == t["name"]) expectDumped(c, t["name"], d["files"][0].get<std::string>());
}

// The subject's own dump of frame 1 of 3 in --mode compute: its frame.json, the files' paths made whole.
json dumpFrame1(const std::string& dir) {
  const RunResult dump = runShell("GBLENS_VALIDATE=1 '" + tiler() + "' --mode compute --frames 3 --dump '" + dir +
                                  "/dump' --dump-frame 1");
  EXPECT_EQ(dump.exitCode, 0) << dump.output;
  json frame = dump.exitCode == 0 ? json::parse(std::ifstream(dir + "/dump/frame.json")) : json();
  if (frame.is_object())
    for (json& t : frame["targets"]) t["files"][0] = dir + "/dump/" + t["files"][0].get<std::string>();
  return frame;
}

// attach --suggest on --mode compute drafts from render passes only: what a dispatch writes into a
// storage image is not decided from the frame's structure. It says so, naming each storage image the
// dispatches bind (the README's resolve set: tiler.albedo at binding 2, tiler.normal at 3) with a
// source, and none of them is a draft target; a layout of just those sources, as the notes print
// them, streams each image as the application's own dump of the frame.
TEST(TilerAttach, SuggestNamesTheStorageImagesComputeWritesWithSourcesThatStreamThem) {
  const std::string dir = freshDir("attach_tiler_suggest_compute");
  const RunResult suggested = runShell("cd '" + dir + "' && DISPLAY= WAYLAND_DISPLAY= GBLENS_VALIDATE=1 timeout 120 '" +
                                       GBLENS_BINARY + "' attach --suggest -o draft.json -- '" + tiler() +
                                       "' --mode compute --frames 5000");
  ASSERT_EQ(suggested.exitCode, 0) << suggested.output;
  const json draft = json::parse(std::ifstream(dir + "/draft.json"));
  for (const json& t : draft["targets"]) EXPECT_EQ(t["source"]["live"].value("name", "").rfind("tiler.", 0), std::string::npos) << t;
  const json frame = dumpFrame1(dir);
  ASSERT_TRUE(frame.is_object());
  const json layout = layoutOfNotes(suggested.output, "storage image", frame);
  ASSERT_TRUE(layout.is_object());
  std::ofstream(dir + "/notes.json") << layout.dump(2);
  const RunResult r = runShell("GBLENS_VALIDATE=1 '" + std::string(GBLENS_BINARY) + "' attach --layout '" + dir +
                               "/notes.json' --capture-frame 1 -o '" + dir + "/live' -- '" + tiler() + "' --mode compute --frames 3");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  expectNotesDumped(dir + "/live", layout, frame);
}

// The same from a RenderDoc capture of --mode compute (RenderDoc's usage records: CS_RWResource at
// the resolve dispatch): import --suggest-layout names the two textures the dispatch binds for
// writing with their sources, drafts neither, and a layout of those sources imports each as the
// application's own dump of the captured frame.
TEST(RenderDoc, SuggestNamesTheTexturesComputeWritesWithSourcesThatImportThem) {
  const std::string dir = freshDir("rdc_tiler_compute");
  const RunResult rec = runShell("timeout -k 5 120 renderdoccmd capture -w -c '" + dir + "/compute' '" + tiler() +
                                 "' --mode compute --frames 3 --capture-frame 1 --dump '" + dir + "/dump' --dump-frame 1");
  ASSERT_NE(rec.output.find("RenderDoc captured frame 1, dumped frame 1"), std::string::npos) << rec.output;
  const std::string rdc = dir + "/compute_capture.rdc";
  // The listing marks the two (and only those) as a dispatch's storage images.
  const RunResult list = runShell("'" + std::string(GBLENS_BINARY) + "' import '" + rdc + "' --list");
  ASSERT_EQ(list.exitCode, 0) << list.output;
  std::istringstream lines(list.output);
  size_t marked = 0;
  for (std::string line; std::getline(lines, line);)
    if (line.find("(a storage image of the dispatch at event ") != std::string::npos) {
      ++marked;
      EXPECT_EQ(line.rfind("  tiler.", 0), 0u) << line;
    }
  EXPECT_EQ(marked, 2u) << list.output;
  const RunResult suggested =
      runShell("'" + std::string(GBLENS_BINARY) + "' import '" + rdc + "' --suggest-layout -o '" + dir + "/draft.json'");
  ASSERT_EQ(suggested.exitCode, 0) << suggested.output;
  const json draft = json::parse(std::ifstream(dir + "/draft.json"));
  for (const json& t : draft["targets"]) EXPECT_EQ(t["source"].value("renderdoc", "").rfind("tiler.", 0), std::string::npos) << t;
  json frame = json::parse(std::ifstream(dir + "/dump/frame.json"));
  for (json& t : frame["targets"]) t["files"][0] = dir + "/dump/" + t["files"][0].get<std::string>();
  const json layout = layoutOfNotes(suggested.output, "texture", frame);
  ASSERT_TRUE(layout.is_object());
  std::ofstream(dir + "/notes.json") << layout.dump(2);
  const RunResult r = runShell("'" + std::string(GBLENS_BINARY) + "' import '" + rdc + "' --layout '" + dir + "/notes.json' -o '" +
                               dir + "/imported'");
  ASSERT_EQ(r.exitCode, 0) << r.output;
  expectNotesDumped(dir + "/imported", layout, frame);
}

}  // namespace
}  // namespace gb
