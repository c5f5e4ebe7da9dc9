// gblens import: another renderer's G-buffer becomes an ordinary gblens capture.
//   gblens import FILES... --layout L.json -o DIR [--camera CAM.json] [--param NAME=VALUE]... [--size WxH]
//   gblens import APP.rdc --layout L.json [--event EID | --pass NAME] -o DIR [...]
//   gblens import APP.rdc --list
// The layout says what the files hold (docs/layout-format.md); the capture is written atomically, and
// nothing at all when anything does not match (one line naming the file, the target and the field; exit 2).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/cli/cli.h"
#include "views/capture/capture.h"
#include "views/capture/import_renderdoc.h"

namespace gb {

namespace {

struct ImportOptions {
  std::vector<std::string> inputs;
  std::string layout, output, camera, size, pass;
  std::vector<std::string> params;
  uint32_t event = 0;
  bool list = false;
};

bool isRenderDocCapture(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".rdc";
}

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

int fail(std::string message) {
  // One line, whatever a library's message held.
  for (size_t at; (at = message.find('\n')) != std::string::npos;) message.replace(at, 1, "; ");
  std::fprintf(stderr, "gblens import: %s\n", message.c_str());
  return 2;
}

// The texts the summary shows for where a target came from.
std::string sourceText(const LayoutTarget& t, const RenderDocImported& rdc) {
  for (const RenderDocImported::Read& r : rdc.reads)
    if (r.target == t.name) return r.texture + " (" + r.format + ") after event " + std::to_string(r.event);
  const TargetSource& s = t.source;
  std::string text = s.path.empty() ? "the file given" : s.path;
  if (s.kind == TargetSource::Kind::Raw) text += " (raw, offset " + std::to_string(s.offset) + ")";
  if (!s.part.empty()) text += " part " + s.part;
  return text;
}

int runImport(const ImportOptions& o) {
  const bool rdc = o.inputs.size() == 1 && isRenderDocCapture(o.inputs[0]);
  if (o.inputs.empty() && o.layout.empty()) return fail("INPUT: give image files and --layout, or a RenderDoc capture");
  for (const std::string& input : o.inputs)
    if (isRenderDocCapture(input) && !rdc) return fail(input + ": a RenderDoc capture is imported on its own");
  if (o.list) {
    if (!rdc) return fail("--list: lists a RenderDoc capture (one .rdc)");
    RdcListing listing;
    std::string error;
    if (!listRenderDocCapture(o.inputs[0], listing, error)) return fail(error);
    printListing(o.inputs[0], listing);
    return 0;
  }
  if (o.layout.empty()) return fail("--layout: required (a layout file, docs/layout-format.md, or builtin:gblens)");
  if (o.output.empty()) return fail("-o: required (the capture folder to write)");
  if (!rdc && (o.event || !o.pass.empty())) return fail(std::string(o.event ? "--event" : "--pass") + ": applies to a RenderDoc capture (.rdc)");

  RenderOptions options;
  std::string error;
  if (!parseLayoutParameters(o.params, options, error) || (!o.size.empty() && !setOption(options, "size", o.size, error)))
    return fail(error);
  ImportInput in;
  if (!loadImportLayout(o.layout, layoutParameters(options), in.layout, in.layoutDir, error)) return fail(error);
  if (!o.size.empty()) in.layout.width = options.width, in.layout.height = options.height;
  in.cameraFile = o.camera;
  RenderDocImported read;
  if (rdc) {
    RenderDocImport r{o.inputs[0], o.event, o.pass, !o.camera.empty(), {}};
    if (!readRenderDocImport(r, in, read, error)) return fail(error);
  } else {
    in.files = o.inputs;
  }

  FrameSnapshot frame;
  if (!importFrame(in, frame, error)) return fail(error);
  // The options the layout was resolved with are the frame's (gblens's own frames: how it was rendered).
  setImportedOptions(frame, options);
  CaptureMeta meta;
  meta.scene = "import:";
  for (const std::string& input : o.inputs) meta.scene += " " + input;
  meta.driver = read.listing.driverNote;
  meta.commandLine = commandLine();
  if (!writeCapture(o.output, frame, meta, error)) return fail(error);

  std::printf("imported %s (%ux%u) with layout %s into %s\n", rdc ? o.inputs[0].c_str() : "files", frame.camera.width,
              frame.camera.height, o.layout.c_str(), o.output.c_str());
  for (uint32_t t = 0; t < frame.layout.targets.size(); ++t) {
    const LayoutTarget& lt = frame.layout.targets[t];
    if (frame.images[t].present())
      std::printf("  %-20s %-14s %ux%u  %s\n", lt.name.c_str(), lt.format.name.c_str(), frame.images[t].image.width,
                  frame.images[t].image.height, sourceText(lt, read).c_str());
  }
  for (const std::string& name : read.leftOut) std::printf("  %-20s absent: no pass of the capture writes a texture of that name\n", name.c_str());
  return 0;
}

}  // namespace

Command addImportCommand(CLI::App& root) {
  auto o = std::make_shared<ImportOptions>();
  CLI::App* cmd = root.add_subcommand("import", "turn another renderer's G-buffer (image files, raw dumps, a RenderDoc "
                                                "capture) into a gblens capture");
  cmd->add_option("INPUT", o->inputs,
                  "image files (EXR, PNG, TIFF, HDR, ...) and raw dumps (default: the files the layout names), or one "
                  "RenderDoc capture (.rdc)");
  cmd->add_option("--layout", o->layout, "what the G-buffer holds: a layout file (docs/layout-format.md) or builtin:gblens");
  cmd->add_option("-o,--output", o->output, "the capture folder to write (atomically)");
  cmd->add_option("--camera", o->camera, "a camera sidecar JSON (the layout's camera fields) overriding the layout's camera");
  cmd->add_option("--param", o->params, "NAME=VALUE: an option value for a parameterised layout (e.g. normal_format=oct-rg16)")
      ->allow_extra_args(false)
      ->multi_option_policy(CLI::MultiOptionPolicy::TakeAll);
  cmd->add_option("--size", o->size, "WxH of every target the layout gives no size (e.g. raw dumps)");
  CLI::Option* event = cmd->add_option("--event", o->event, "RenderDoc: read every target after this event (1..last)")
                           ->check(CLI::Validator([](std::string& v) { return v == "0" ? "events start at 1 (see --list)" : ""; },
                                                  "EID", "event"));
  cmd->add_option("--pass", o->pass, "RenderDoc: read every target at the end of this pass (label region, see --list)")
      ->excludes(event);
  cmd->add_flag("--list", o->list, "RenderDoc: print the capture's passes, events and textures (name, id, format, size)");
  return {cmd, [o]() -> int { return runImport(*o); }};
}

}  // namespace gb
