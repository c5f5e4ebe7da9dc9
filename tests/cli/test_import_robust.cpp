// Malformed and hostile input to gblens import and to the capture readers (issue 29): each case is a
// small fixture made here, reproducing a crash, hang or silent acceptance found by mutation (number
// overflow in layouts and sidecars, a directory, FIFO or device as a source, a truncated PNG, a huge
// declared image size, JSON nested 20,000 levels deep, a manifest linked to /dev/zero, a symlink
// leaving a capture, a sidecar without matrices, channel and offset overflows, a path in a
// quantity name, values that overflow to Inf). Each must give one line and exit 2 within seconds,
// write nothing (nothing at -o, nothing left beside it, nothing outside it).
#include "tests/support/test_paths.h"
#include <gtest/gtest.h>
#include <sys/stat.h>

#include <chrono>
#include <filesystem>
#include <fstream>

#include <OpenImageIO/imageio.h>

#include "tests/cli/import_fixtures.h"
#include "tests/support/capture_util.h"

namespace gb {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using namespace fixtures;

// Runs `gblens ARGS` under a hard limit; a hang shows as exit 124 and fails the checks below.
RunResult runBounded(const std::string& args, double& seconds) {
  const auto start = std::chrono::steady_clock::now();
  RunResult r = runShell("timeout -k 5 60 '" + std::string(GBLENS_BINARY) + "' " + args);
  seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

// One line starting "gblens COMMAND: ", holding every word, exit `code`, nothing at `out` or beside it.
void expectOneLine(const std::string& command, const std::string& args, int code, const std::vector<std::string>& words,
                   const std::string& out = "") {
  SCOPED_TRACE(command + " " + args);
  double seconds = 0.0;
  const RunResult r = runBounded(command + " " + args + (out.empty() ? "" : " -o '" + out + "'"), seconds);
  EXPECT_EQ(r.exitCode, code) << r.output;
  // Progress lines ("  .. reading ...") come first; the mistake is one line of its own.
  std::string message = r.output;
  while (message.rfind("  .. ", 0) == 0) message.erase(0, message.find('\n') + 1);
  EXPECT_EQ(std::count(message.begin(), message.end(), '\n'), 1) << "not one line:\n" << r.output;
  EXPECT_EQ(message.rfind("gblens " + command + ": ", 0), 0u) << r.output;
  for (const std::string& w : words) EXPECT_NE(r.output.find(w), std::string::npos) << "'" << w << "' not in: " << r.output;
  // "Within seconds": a hang is what is caught here (the limit above is 60 s), not speed.
  EXPECT_LT(seconds, 30.0) << r.output;
  if (out.empty()) return;
  EXPECT_FALSE(fs::exists(out)) << out << " was written";
  for (const auto& e : fs::directory_iterator(fs::path(out).parent_path()))
    EXPECT_EQ(e.path().filename().string().find(".partial-"), std::string::npos) << "left behind: " << e.path();
}

void writeText(const std::string& path, const std::string& text) { std::ofstream(path, std::ios::binary) << text; }

// The layout's text with the number `marker` (written once, by the caller) replaced by `text`.
std::string replaced(const json& layout, const std::string& marker, const std::string& text) {
  std::string s = layout.dump();
  const size_t at = s.find(marker);
  if (at == std::string::npos) throw std::runtime_error("marker not found");
  return s.replace(at, marker.size(), text);
}

// Fixture C (16x8: gbuf.exr, normal.exr, depth.exr) with a camera, a light and a sun: every part of a
// layout that the cases below spoil.
json fullLayout(const std::string& dir) {
  json l = writeFixtureC(dir, false);
  l["size"] = {16, 8};
  std::vector<double> view = {1, 0, 0, 0, 0, 1, 0, 0, 0, 0, 1, 0, 0, 0, -3, 1};
  std::vector<double> proj = {1.2, 0, 0, 0, 0, 2.4, 0, 0, 0, 0, -1.004, -1, 0, 0, -0.2004, 0};
  l["camera"] = {{"view_from_world", view}, {"clip_from_view", proj}, {"convention", "gl"}};
  l["lights"] = {{"model", "gblens"},
                 {"points", {{{"position", {0, 1, -2}}, {"radius", 3}, {"color", {1, 1, 1}}, {"intensity", 2}}}},
                 {"sun", {{"direction", {0.3, 1, 0.2}}, {"color", {1, 1, 1}}}},
                 {"ambient", {0.1, 0.1, 0.1}}};
  writeJson(dir + "/full.json", l);
  writeJson(dir + "/cam.json", {{"view_from_world", view}, {"clip_from_view", proj}});
  return l;
}

TEST(ImportRobust, NumbersBeyondWhatTheFieldHoldsAreOneLine) {
  const std::string dir = freshDir("robust-numbers");
  const json good = fullLayout(dir);
  const std::string layout = "--layout '" + dir + "/case.json'", out = dir + "/out";
  ASSERT_EQ(runGblens("import --layout '" + dir + "/full.json' -o '" + dir + "/control'").exitCode, 0);
  // Each position holds the marker 7777777, replaced by a number nlohmann cannot hold as a double,
  // then by one it holds but the field does not.
  struct Position {
    const char* name;
    std::function<void(json&)> mark;
    const char* refusal;  // the field's words for a 30-digit integer (nullptr: the field holds one: imported)
  };
  const std::vector<Position> positions = {
      {"version", [](json& l) { l["version"] = 7777777; }, "version"},
      {"size", [](json& l) { l["size"][0] = 7777777; }, "size"},
      {"channel", [](json& l) { l["targets"][0]["quantities"][1]["channels"][0] = 7777777; }, "channels"},
      {"matrix", [](json& l) { l["camera"]["clip_from_view"][5] = 7777777; }, nullptr},
      {"light", [](json& l) { l["lights"]["points"][0]["radius"] = 7777777; }, nullptr},
      {"sun", [](json& l) { l["lights"]["sun"]["direction"][1] = 7777777; }, nullptr},
  };
  // Every overflowing form once, then 1e999 at every position.
  const std::vector<std::string> overflows = {"-1e999", "1e400", "1" + std::string(400, '0'), "1e999"};
  for (size_t i = 0; i < positions.size(); ++i) {
    const Position& p = positions[i];
    json l = good;
    p.mark(l);
    writeText(dir + "/case.json", replaced(l, "7777777", overflows[std::min(i, overflows.size() - 1)]));
    expectOneLine("import", layout, 2, {"case.json", "not valid JSON", "number overflow"}, out);
    writeText(dir + "/case.json", replaced(l, "7777777", "123456789012345678901234567890"));
    if (p.refusal) {
      expectOneLine("import", layout, 2, {"case.json", p.refusal}, out);
    } else {  // a value the field may hold: imported (the property test reads such captures back)
      EXPECT_EQ(runGblens("import " + layout + " -o '" + out + "'").exitCode, 0) << p.name;
      fs::remove_all(out);
    }
  }
  // The same in a camera sidecar.
  json l = good;
  l["camera"] = {{"sidecar", "side.json"}, {"convention", "gl"}};
  writeJson(dir + "/case.json", l);
  json side = json::parse(readText(dir + "/cam.json"));
  side["clip_from_view"][0] = 7777777;
  writeText(dir + "/side.json", replaced(side, "7777777", "-1e999"));
  expectOneLine("import", layout, 2, {"side.json", "not valid JSON"}, out);
  // A channel index of 2^32 is not channel 0; an offset of 2^64-1 is not offset 0.
  l = good;
  l["targets"][0]["quantities"][1]["channels"][0] = 4294967296ull;
  writeJson(dir + "/case.json", l);
  expectOneLine("import", layout, 2, {"case.json", "\"gbuf\"", "channels", "4294967296"}, out);
  l = good;
  l["targets"][2]["source"] = {{"file", "depth.exr"}, {"raw", true}, {"offset", 18446744073709551615ull}};
  writeJson(dir + "/case.json", l);
  expectOneLine("import", layout, 2, {"case.json", "\"depth\"", "offset", "18446744073709551615"}, out);
  l = good;
  l["camera"] = {{"renderdoc", {{"buffer", "ubo"}, {"view_from_world", {{"offset", 18446744073709551615ull}}},
                                {"clip_from_view", {{"offset", 64}}}}}};
  writeJson(dir + "/case.json", l);
  expectOneLine("import", layout, 2, {"case.json", "camera", "renderdoc", "offset"}, out);
  // Values that are numbers but overflow what import computes from them (written as null before).
  l = good;
  l["lights"]["points"][0]["position"] = {1e300, 0, 0};
  writeJson(dir + "/case.json", l);
  expectOneLine("import", layout, 2, {"case.json", "points[0]", "position"}, out);
  l = good;
  l["lights"]["sun"]["direction"] = {1e200, 1e200, 1e200};
  writeJson(dir + "/case.json", l);
  expectOneLine("import", layout, 2, {"case.json", "sun", "direction"}, out);
  l = good;
  l["camera"]["view_from_world"] = {1e200, 0, 0, 0, 0, 1e200, 0, 0, 0, 0, 1e200, 0, 0, 0, 0, 1};
  writeJson(dir + "/case.json", l);
  expectOneLine("import", layout, 2, {"case.json", "camera", "view_from_world"}, out);
  EXPECT_FALSE(fs::exists(out));
}

TEST(ImportRobust, SourcesThatAreNotFilesAndImagesThatLieAreOneLine) {
  const std::string dir = freshDir("robust-sources");
  const json good = fullLayout(dir);
  const std::string layout = "--layout '" + dir + "/case.json'", out = dir + "/out";
  ASSERT_EQ(mkfifo((dir + "/fifo").c_str(), 0600), 0);
  const std::vector<std::pair<std::string, std::string>> sources = {
      {"/", "is a directory"}, {".", "is a directory"}, {dir + "/fifo", "is a FIFO"}, {"/dev/zero", "is a device"}};
  for (size_t i = 0; i < sources.size(); ++i) {
    json l = good;  // as an image file and as a raw dump, in turn
    l["targets"][2]["source"] = {{"file", sources[i].first}, {"raw", i % 2 == 1}};
    writeJson(dir + "/case.json", l);
    // "/" and "/dev/zero" lie outside the layout's folder: refused as such, and as what they are
    // when the layout may read them.
    const bool outside = sources[i].first[0] == '/' && sources[i].first.rfind(dir, 0) != 0;
    expectOneLine("import", layout + (outside ? " --allow-outside-sources" : ""), 2, {"case.json", "\"depth\"", sources[i].second}, out);
    if (outside) expectOneLine("import", layout, 2, {"case.json", "\"depth\"", "outside the layout's folder"}, out);
  }
  expectOneLine("import", layout.substr(0, 9) + "'" + dir + "/full.json' --camera '" + dir + "'", 2, {"sidecar", "is a directory"}, out);
  expectOneLine("import", "--layout '" + dir + "' ", 2, {"is a directory"}, out);

  // A PNG target: truncated (libpng's own message folded into the one line), and a 157-byte PNG
  // whose header claims 60000x60000 (refused before its pixels are allocated).
  {
    std::vector<uint8_t> pixels(16 * 8 * 3, 100);
    OIIO::ImageSpec spec(16, 8, 3, OIIO::TypeDesc::UINT8);
    auto o = OIIO::ImageOutput::create(dir + "/albedo.png");
    ASSERT_TRUE(o && o->open(dir + "/albedo.png", spec) && o->write_image(OIIO::TypeDesc::UINT8, pixels.data()) && o->close());
  }
  json png = {{"format", "gblens-layout"}, {"version", 1}, {"size", {16, 8}},
              {"targets", {{{"name", "albedo"}, {"format", "rgb8_unorm"}, {"source", {{"file", "albedo.png"}}},
                            {"quantities", {{{"quantity", "albedo"}, {"channels", {0, 1, 2}}}}}}}}};
  writeJson(dir + "/case.json", png);
  ASSERT_EQ(runGblens("import " + layout + " -o '" + dir + "/png-ok'").exitCode, 0);  // control: the PNG imports
  std::string bytes = readText(dir + "/albedo.png");
  writeText(dir + "/albedo.png", bytes.substr(0, bytes.size() - 20));
  expectOneLine("import", layout, 2, {"case.json", "\"albedo\"", "albedo.png"}, out);
  // The header: signature, IHDR (60000 x 60000, 8-bit RGB; its CRC from zlib's table by hand), a tiny IDAT.
  auto crc = [](const std::string& s) {
    uint32_t c = 0xFFFFFFFFu;
    for (unsigned char b : s) {
      c ^= b;
      for (int k = 0; k < 8; ++k) c = (c >> 1) ^ (0xEDB88320u & (0u - (c & 1u)));
    }
    return c ^ 0xFFFFFFFFu;
  };
  auto be = [](uint32_t v) { return std::string{char(v >> 24), char(v >> 16), char(v >> 8), char(v)}; };
  auto chunk = [&](const std::string& type, const std::string& data) { return be(uint32_t(data.size())) + type + data + be(crc(type + data)); };
  const std::string ihdr = be(60000) + be(60000) + std::string("\x08\x02\x00\x00\x00", 5);
  const std::string huge = std::string("\x89PNG\r\n\x1a\n", 8) + chunk("IHDR", ihdr) + chunk("IDAT", std::string(100, '\0')) + chunk("IEND", "");
  writeText(dir + "/albedo.png", huge);
  expectOneLine("import", layout, 2, {"case.json", "\"albedo\"", "60000x60000", "16x8"}, out);
  png.erase("size");
  writeJson(dir + "/case.json", png);
  expectOneLine("import", layout, 2, {"case.json", "\"albedo\"", "60000x60000", "more than"}, out);
}

TEST(ImportRobust, DeepNestingSidecarsWithoutMatricesAndUnsafeNamesAreOneLine) {
  const std::string dir = freshDir("robust-names");
  const json good = fullLayout(dir);
  const std::string layout = "--layout '" + dir + "/case.json'", out = dir + "/out";
  const std::string deep = std::string(20000, '[') + std::string(20000, ']');
  writeText(dir + "/case.json", replaced(good, "\"fixture C: for gblens check\"", deep));
  expectOneLine("import", layout, 2, {"case.json", "nested deeper than"}, out);
  writeJson(dir + "/case.json", good);
  writeText(dir + "/side.json", "{\"extra\": " + deep + "}");
  expectOneLine("import", layout + " --camera '" + dir + "/side.json'", 2, {"side.json", "nested deeper than"}, out);
  // A sidecar naming another file (or a buffer) holds no matrices: refused, not identity.
  writeJson(dir + "/side.json", {{"sidecar", "cam.json"}});
  expectOneLine("import", layout + " --camera '" + dir + "/side.json'", 2, {"side.json", "sidecar", "matrices"}, out);
  writeJson(dir + "/side.json", json::object());
  expectOneLine("import", layout + " --camera '" + dir + "/side.json'", 2, {"side.json", "view_from_world", "missing"}, out);
  // Names that become file or EXR channel names.
  for (const std::string& name : {std::string("x/../../escaped"), std::string(300, 'q'), std::string("..")}) {
    json l = good;
    l["targets"][0]["quantities"][0]["name"] = name;
    writeJson(dir + "/case.json", l);
    expectOneLine("import", layout, 2, {"case.json", "\"gbuf\"", "name"}, out);
  }
  EXPECT_FALSE(fs::exists(fs::path(dir).parent_path() / "escaped.png"));
}

// A capture made by import, then spoiled as an attacker would: every reader refuses it in one line.
TEST(ImportRobust, SpoiledCapturesAreRefusedByEveryReader) {
  const std::string dir = freshDir("robust-capture");
  fullLayout(dir);
  const std::string cap = dir + "/cap";
  ASSERT_EQ(runGblens("import --layout '" + dir + "/full.json' -o '" + cap + "'").exitCode, 0);
  auto readers = [&](const std::string& c, const std::vector<std::string>& words, const std::string& what) {
    SCOPED_TRACE(what);
    expectOneLine("probe", "'" + c + "' 3 3", 2, words);
    expectOneLine("check", "'" + c + "'", 2, words);
    expectOneLine("stats", "'" + c + "' --rect 0,0,4,4", 2, words);
    expectOneLine("compare", "'" + c + "' '" + cap + "' -o '" + dir + "/diff'", 4, words);
  };
  const std::string manifest = readText(cap + "/manifest.json");
  auto spoiled = [&](const std::string& name) {
    const std::string c = dir + "/" + name;
    fs::remove_all(c);
    fs::copy(cap, c);
    return c;
  };
  // The manifest nested 20,000 deep (in the embedded layout's name), and linked to /dev/zero.
  std::string c = spoiled("deep");
  std::string text = manifest;
  text.replace(text.find("\"fixture C: for gblens check\""), 29, std::string(20000, '[') + std::string(20000, ']'));
  writeText(c + "/manifest.json", text);
  readers(c, {"manifest.json", "nested deeper than"}, "deep");
  c = spoiled("devzero");
  fs::remove(c + "/manifest.json");
  fs::create_symlink("/dev/zero", c + "/manifest.json");
  readers(c, {"manifest.json"}, "devzero");
  // A listed file replaced by a link to a copy outside the folder (the checksum matches).
  c = spoiled("link");
  fs::copy_file(c + "/gbuf.exr", dir + "/outside.exr");
  fs::remove(c + "/gbuf.exr");
  fs::create_symlink(dir + "/outside.exr", c + "/gbuf.exr");
  // The rest through probe and compare only (the four share loadCapture; two cases above show it).
  auto twoReaders = [&](const std::string& c, const std::vector<std::string>& words, const std::string& what) {
    SCOPED_TRACE(what);
    expectOneLine("probe", "'" + c + "' 3 3", 2, words);
    expectOneLine("compare", "'" + c + "' '" + cap + "' -o '" + dir + "/diff'", 4, words);
  };
  twoReaders(c, {"gbuf.exr", "symbolic link leaving the capture folder"}, "link");
  // A quantity name with a path, a number that JSON cannot hold, an integer beyond its field.
  for (auto [from, to, words] : std::vector<std::tuple<std::string, std::string, std::string>>{
           {"\"name\": \"Albedo\"", "\"name\": \"x/../../escaped\"", "contains '/'"},
           {"\"reversed_z\": false", "\"reversed_z\": null", "reversed_z"},
           {"\"width\": 16", "\"width\": 4294967312", "width"}}) {
    c = spoiled("edit");
    text = manifest;
    ASSERT_NE(text.find(from), std::string::npos) << from;
    text.replace(text.find(from), from.size(), to);
    writeText(c + "/manifest.json", text);
    twoReaders(c, {"manifest.json", words}, from);
  }
  EXPECT_FALSE(fs::exists(dir + "/escaped.png"));
  EXPECT_FALSE(fs::exists(fs::path(dir).parent_path() / "escaped.png"));
}

}  // namespace
}  // namespace gb
