// gblens attach's command-line fuzz entry (see attach_entry.h).
#include "tests/fuzz/attach_entry.h"

#include <filesystem>
#include <fstream>
#include <string_view>
#include <vector>

#include "app/cli/attach_args.h"
#include "app/cli/messages.h"

namespace gb::fuzz {

namespace {

namespace fs = std::filesystem;

// The layouts "@NAME" arguments name: one with live sources and a camera read live, one with a file
// source (attach refuses it), one that is not JSON.
void writeLayouts(const std::string& dir) {
  if (fs::exists(dir + "/live.json")) return;
  fs::create_directories(dir);
  std::ofstream(dir + "/live.json")
      << R"({"format": "gblens-layout", "version": 1, "targets": [{"name": "albedo", "format": "rgba8_unorm",)"
         R"( "source": {"live": {"pass": 0, "color": 0}}, "quantities": [{"quantity": "albedo", "name": "A", "channels": [0, 1, 2]}]},)"
         R"( {"name": "depth", "format": "d32f", "source": {"live": {"pass": 0, "depth": true}},)"
         R"( "quantities": [{"quantity": "depth", "name": "D", "channels": [0], "encoding": "hardware"}]}],)"
         R"( "camera": {"live": {"pass": 0, "set": 0, "binding": 2}, "view_from_world": {"offset": 64},)"
         R"( "clip_from_view": {"offset": 0}}})";
  std::ofstream(dir + "/file.json")
      << R"({"format": "gblens-layout", "version": 1, "size": [4, 2], "targets": [{"name": "t", "format": "r32f",)"
         R"( "source": {"file": "a.bin", "raw": true}, "quantities": [{"quantity": "depth", "name": "D", "channels": [0]}]}]})";
  std::ofstream(dir + "/draft.json") << "{\"format\": \"gblens-layout\", \"version\": 1, \"targets\": [";
}

}  // namespace

std::string attachOne(const uint8_t* data, size_t size, const std::string& dir) {
  writeLayouts(dir);
  std::vector<std::string> args = {"gblens", "attach"};
  const std::string_view all(reinterpret_cast<const char*>(data), size);
  for (size_t at = 0; at <= all.size() && args.size() < 66;) {
    const size_t end = std::min(all.find('\0', at), all.size());
    std::string arg(all.substr(at, end - at));
    if (arg.rfind('@', 0) == 0) arg = dir + "/" + arg.substr(1);
    args.push_back(arg);
    at = end + 1;
  }
  std::vector<char*> argv;
  for (std::string& a : args) argv.push_back(a.data());
  CLI::App root{"gblens"};
  CLI::App* cmd = root.add_subcommand("attach", "");
  AttachOptions o;
  addAttachOptions(cmd, o);
  try {
    root.parse(int(argv.size()), argv.data());
  } catch (const CLI::ParseError& e) {
    const std::string what = oneLine(e.what());  // as main prints it
    return what.empty() ? "usage" : what;
  }
  LiveOptions lo;
  LivePlan plan;
  std::string error;
  if (!checkAttachOptions(o, lo, error) || !planLive(lo, plan, error)) return error.empty() ? "refused" : oneLine(error);
  return "";
}

}  // namespace gb::fuzz
