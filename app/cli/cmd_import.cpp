// gblens import APP.rdc --list: what a RenderDoc capture holds, so that a user can write the layout
// that says what its G-buffer means: the passes (label regions and unnamed render passes) with their
// event ranges and the textures they write, and every texture's name, id, format and size.
#include <algorithm>
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "views/capture/renderdoc_replay.h"

namespace gb {

namespace {

struct ImportOptions {
  std::string input;
  bool list = false;
};

void printListing(const std::string& rdc, const RdcListing& l) {
  std::printf("capture   %s\n", rdc.c_str());
  std::printf("api       %s\n", l.api.c_str());
  std::printf("replay    %s\n", l.driverNote.c_str());
  std::printf("events    1..%u\n", l.lastEvent);
  std::printf("passes    %zu (events first..last; the textures bound for writing)\n", l.passes.size());
  for (const RdcPass& p : l.passes) {
    std::string writes;
    for (const std::string& w : p.writes) writes += (writes.empty() ? "" : ", ") + w;
    std::printf("  %*s%-*s %5u..%-5u %s\n", int(2 * p.depth), "", int(28 - 2 * std::min(p.depth, 8u)), p.name.c_str(),
                p.firstEvent, p.lastEvent, writes.c_str());
  }
  std::printf("textures  %zu (name, id, format, size; * : a format gblens cannot hold)\n", l.textures.size());
  for (const RdcTexture& t : l.textures) {
    std::string size = std::to_string(t.width) + "x" + std::to_string(t.height);
    if (t.depth > 1) size += "x" + std::to_string(t.depth);
    if (t.layers > 1) size += ", " + std::to_string(t.layers) + " layers";
    if (t.mips > 1) size += ", " + std::to_string(t.mips) + " mips";
    if (t.samples > 1) size += ", " + std::to_string(t.samples) + " samples";
    std::printf("  %-28s #%-6llu %-22s %s%s\n", t.name.c_str(), (unsigned long long)t.id, t.format.c_str(), size.c_str(),
                t.texelFormat ? "" : " *");
  }
}

int runImport(const ImportOptions& o) {
  if (!o.list) {
    std::fprintf(stderr, "gblens import: %s: only --list is implemented so far\n", o.input.c_str());
    return 2;
  }
  RdcListing listing;
  std::string error;
  if (!listRenderDocCapture(o.input, listing, error)) {
    std::fprintf(stderr, "gblens import: %s\n", error.c_str());
    return 2;
  }
  printListing(o.input, listing);
  return 0;
}

}  // namespace

Command addImportCommand(CLI::App& root) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* cmd = root.add_subcommand("import", "turn another renderer's G-buffer into a gblens capture");
  cmd->add_option("INPUT", o->input, "a RenderDoc capture (.rdc)")->required();
  cmd->add_flag("--list", o->list, "print the capture's passes, events and textures (name, id, format, size)");
  return {cmd, [o]() -> int { return runImport(*o); }};
}

}  // namespace gb
