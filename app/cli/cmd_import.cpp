// gblens import: another renderer's G-buffer becomes an ordinary gblens capture.
//   gblens import FILES... --layout L.json -o DIR [--camera CAM.json] [--param NAME=VALUE]... [--size WxH]
//   gblens import APP.rdc --layout L.json [--event EID | --pass NAME] -o DIR [...]
//   gblens import --layout L.json --frames A..B -o SEQ   (a #### pattern in the layout: a sequence)
//   gblens import APP.rdc --list
//   gblens import APP.rdc|FILES... --suggest-layout [--event EID | --pass NAME] [-o DRAFT.json]
// The layout says what the files hold (docs/layout-format.md); the capture is written atomically, and
// nothing at all when anything does not match (one line naming the file, the target and the field; exit 2).
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "app/cli/cli.h"
#include "app/cli/messages.h"
#include "renderer/core/library_output.h"
#include "views/capture/capture.h"
#include "views/capture/image_io.h"
#include "views/capture/sequence.h"
#include "views/import/import_renderdoc.h"
#include "views/infer/suggest.h"

namespace gb {

namespace {

struct ImportOptions {
  std::vector<std::string> inputs;
  std::string layout, output, camera, size, pass, frames;
  std::vector<std::string> params;
  uint32_t event = 0;
  bool list = false, suggest = false;
  bool verbose = false;  // library messages (libpng, OpenEXR) as printed, not folded into the one line
  bool allowOutside = false;  // --allow-outside-sources
};

// What import is doing now (cli.h progressLine: a terminal only, so that a refusal read by a script is
// its one line, "gblens import: ...").
void progress(const std::string& text) { progressLine(text); }

bool isRenderDocCapture(const std::string& path) {
  std::string ext = std::filesystem::path(path).extension().string();
  std::transform(ext.begin(), ext.end(), ext.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return ext == ".rdc";
}

// The buffers bound at a pass's last draw, under the innermost pass that ends with that draw.
void printBindings(const RdcListing& l, const RdcPass& p) {
  for (const RdcPass& q : l.passes)
    if (&q != &p && q.boundAt == p.boundAt && q.firstEvent >= p.firstEvent && q.lastEvent <= p.lastEvent &&
        q.lastEvent - q.firstEvent < p.lastEvent - p.firstEvent)
      return;
  for (const RdcBinding& b : p.buffers) {
    std::string stages, members, where = "binding not read";
    for (const std::string& s : b.stages) stages += (stages.empty() ? "" : ",") + s;
    for (size_t i = 0; i < b.members.size() && i < 8; ++i)
      members += (members.empty() ? "" : ", ") + b.members[i].name + "@" + std::to_string(b.members[i].offset);
    if (b.members.size() > 8) members += ", ...";
    if (b.bound)
      where = "set " + std::to_string(b.set) + " binding " + std::to_string(b.binding) +
              (b.index ? "[" + std::to_string(b.index) + "]" : "") + ", bytes " + std::to_string(b.offset) + ".." +
              std::to_string(b.offset + b.range);
    std::printf("  %*s  %-7s %-22s #%-6llu %8llu bytes  %s  (%s)%s%s%s\n", int(2 * p.depth), "", b.kind.c_str(),
                b.name.c_str(), (unsigned long long)b.id, (unsigned long long)b.bytes, where.c_str(), stages.c_str(),
                members.empty() ? "" : " {", members.c_str(), members.empty() ? "" : "}");
  }
}

// Where each pass's buffers are bound (set, binding, range), from the pipeline state at its last draw.
void addBindings(const std::string& rdc, RdcListing& l, std::string& note) {
  std::vector<uint32_t> events;
  for (const RdcPass& p : l.passes)
    if (p.boundAt) events.push_back(p.boundAt);
  std::map<uint32_t, RdcPass> states;
  std::string skipped, error;
  progress("reading where " + std::to_string(events.size()) + " draws bind their buffers");
  if (!readDrawState(rdc, events, false, states, skipped, error)) {
    note = "set and binding not read: " + error;
    return;
  }
  if (!skipped.empty()) note = "set and binding not read at event " + skipped + ": RenderDoc's replay crashed there";
  for (RdcPass& p : l.passes)
    for (RdcBinding& b : p.buffers)
      for (const RdcBinding& s : states[p.boundAt].buffers)
        if (s.id == b.id && !b.bound) {
          const std::vector<std::string> stages = b.stages;
          b = s;  // the usage records' stages are the ones that read it; the descriptor's may say more
          if (!stages.empty()) b.stages = stages;
        }
}

void printListing(const std::string& rdc, const RdcListing& l, const std::string& note) {
  std::printf("capture   %s\n", rdc.c_str());
  std::printf("api       %s\n", l.api.c_str());
  std::printf("replay    %s\n", l.driverNote.c_str());
  std::printf("events    1..%u\n", l.lastEvent);
  std::printf("passes    %zu (events first..last; the textures bound for writing; below: the buffers bound at\n"
              "          its last draw or dispatch: name, id, size, bound range, set/binding, stages {members@offset})\n",
              l.passes.size());
  for (const RdcPass& p : l.passes) {
    std::string writes;
    for (const std::string& w : p.writes) writes += (writes.empty() ? "" : ", ") + w;
    std::printf("  %*s%-*s %5u..%-5u %s\n", int(2 * p.depth), "", int(28 - 2 * std::min(p.depth, 8u)), p.name.c_str(),
                p.firstEvent, p.lastEvent, writes.c_str());
    printBindings(l, p);
  }
  std::printf("textures  %zu (name, id, format, size; * : a format gblens cannot hold)\n", l.textures.size());
  for (const RdcTexture& t : l.textures) {
    std::string size = std::to_string(t.width) + "x" + std::to_string(t.height);
    if (t.depth > 1) size += "x" + std::to_string(t.depth);
    if (t.layers > 1) size += ", " + std::to_string(t.layers) + " layers";
    if (t.mips > 1) size += ", " + std::to_string(t.mips) + " mips";
    if (t.samples > 1) size += ", " + std::to_string(t.samples) + " samples";
    // Bound for writing by a dispatch: a G-buffer written by compute is one of these (no pass lists it).
    const std::string compute =
        t.computeWrites.empty() ? "" : "  (a storage image of the dispatch at event " + computeWriteEvents(t) + ")";
    std::printf("  %-28s #%-6llu %-22s %s%s%s\n", t.name.c_str(), (unsigned long long)t.id, t.format.c_str(), size.c_str(),
                t.texelFormat ? "" : " *", compute.c_str());
  }
  if (!note.empty()) std::printf("note      %s\n", note.c_str());
  std::printf("buffers   %zu (name, id, size)\n", l.buffers.size());
  for (const RdcBuffer& b : l.buffers)
    std::printf("  %-28s #%-6llu %llu bytes\n", b.name.c_str(), (unsigned long long)b.id, (unsigned long long)b.bytes);
}


int importFail(const std::string& message) {
  // One line, whatever a library's message held.
  std::fprintf(stderr, "gblens import: %s\n", oneLine(message).c_str());
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

// --suggest-layout: the draft to -o (atomically) or stdout, what was found on stderr.
int runSuggest(const ImportOptions& o) {
  if (!o.layout.empty()) return importFail("--suggest-layout: drafts a layout; give no --layout");
  SuggestRequest r;
  r.inputs = o.inputs;
  r.event = o.event;
  r.pass = o.pass;
  r.progress = progress;
  Suggestion draft;
  std::string error;
  if (!suggestLayout(r, draft, error)) return importFail(error);
  const std::string text = draft.layout.dump(2) + "\n";
  if (o.output.empty()) {
    std::fputs(text.c_str(), stdout);
  } else {
    if (!writeTextAtomically(o.output, text, error)) return importFail(o.output + ": cannot write the draft");
  }
  for (const std::string& line : draft.summary) std::fprintf(stderr, "  %s\n", line.c_str());
  std::string args = isRenderDocCapture(o.inputs[0]) ? o.inputs[0] : "";
  if (args.empty())
    for (const std::string& i : o.inputs) args += (args.empty() ? "" : " ") + i;
  std::fprintf(stderr, "gblens import: draft%s%s; check every \"guess\", then: gblens import %s --layout %s%s -o DIR\n",
               o.output.empty() ? " on stdout" : " written to ", o.output.c_str(), args.c_str(),
               o.output.empty() ? "DRAFT.json" : o.output.c_str(),
               o.event ? (" --event " + std::to_string(o.event)).c_str() : o.pass.empty() ? "" : (" --pass " + o.pass).c_str());
  return 0;
}

// One frame read with the layout, its options and absences settled as every import's are.
bool importedFrame(const ImportInput& in, const RenderOptions& options, const std::vector<std::string>& stated,
                   FrameSnapshot& frame, std::string& error) {
  if (!importFrame(in, frame, error)) return false;
  // The options the layout was resolved with are the frame's (gblens's own frames: how it was rendered).
  setImportedOptions(frame, options, stated);
  // gblens's own layout: a target the capture does not hold says why, as gblens's captures do (a
  // 1x1 stand-in of coverage left out: "not computed: coverage off", by the options given).
  if (frame.layout.name == nativeLayout(options).name)
    for (uint32_t t = 0; t < frame.layout.targets.size(); ++t)
      for (const TargetInfo& info : targetTable())
        if (!frame.images[t].present() && info.name == frame.layout.targets[t].name &&
            targetAbsence(info.target, frame.options) != Absent::No)
          frame.absences[t] = targetAbsence(info.target, frame.options);
  return true;
}

// --frames A..B: every frame the layout's pattern names, as one sequence (views/capture/sequence.h);
// each frame's time and jitter from its camera (a sidecar per frame), when it gives them.
int runImportSequence(const ImportOptions& o, const ImportInput& base, const RenderOptions& options,
                      const std::vector<std::string>& stated, bool rdc) {
  int64_t first = 0, last = 0;
  std::string error;
  if (!parseFrameRange(o.frames, "--frames", first, last, error)) return importFail(error);
  // RenderDoc writes a capture per frame (APP_frameN.rdc): the pattern is in the .rdc's name.
  const bool inputPattern = std::any_of(o.inputs.begin(), o.inputs.end(), [](const std::string& f) { return f.find('#') != std::string::npos; });
  if (!hasFramePattern(base.layout) && !inputPattern)
    return importFail("--frames: neither " + o.layout + " nor the files name a frame pattern (# in a source's file, the camera's "
                      "sidecar or a file given)");
  const nlohmann::json extra = {{"command_line", commandLine()}, {"source", {{"layout", o.layout}, {"inputs", o.inputs}}}};
  const bool ok = writeSequence(o.output, size_t(last - first + 1), [&](size_t i, SequenceEntry& e, std::string& why) {
    ImportInput in = base;
    e.number = first + int64_t(i);
    in.layout = layoutForFrame(base.layout, e.number);
    if (rdc) {
      const std::string capture = framePath(o.inputs[0], e.number);
      RenderDocImport r{capture, o.event, o.pass, !o.camera.empty(), {}};
      RenderDocImported read;
      progress("frame " + std::to_string(e.number) + ": reading " + capture + " (RenderDoc replays it)");
      if (!readRenderDocImport(r, in, read, why)) {
        why = "frame " + std::to_string(e.number) + ": " + why;
        return false;
      }
      e.meta.driver = read.listing.driverNote;
    } else {
      in.files = o.inputs;
      for (std::string& f : in.files) f = framePath(f, e.number);  // FILES may name the frames by the pattern too
    }
    progress("frame " + std::to_string(e.number) + ": decoding " + std::to_string(in.layout.targets.size()) + " targets");
    if (!importedFrame(in, options, stated, e.frame, why)) {
      why = "frame " + std::to_string(e.number) + ": " + why;
      return false;
    }
    e.time = e.frame.layout.camera.time;
    e.jitter = e.frame.layout.camera.jitter;
    e.meta.scene = "import: " + o.layout + " frame " + std::to_string(e.number);
    e.meta.source = {{"inputs", o.inputs}, {"frame", e.number}};
    if (rdc) e.meta.source["tool"] = "RenderDoc";
    e.meta.commandLine = commandLine();
    return true;
  }, extra, error);
  if (!ok) return importFail(error);
  std::printf("imported frames %lld..%lld with layout %s into the sequence %s\n", (long long)first, (long long)last,
              o.layout.c_str(), o.output.c_str());
  return 0;
}

int runImport(const ImportOptions& o) {
  showLibraryOutput(o.verbose);
  const bool rdc = o.inputs.size() == 1 && isRenderDocCapture(o.inputs[0]);
  if (o.inputs.empty() && o.layout.empty()) return importFail("INPUT: give image files and --layout, or a RenderDoc capture");
  for (const std::string& input : o.inputs)
    if (isRenderDocCapture(input) && !rdc) return importFail(input + ": a RenderDoc capture is imported on its own");
  if (o.list) {
    if (!rdc) return importFail("--list: lists a RenderDoc capture (one .rdc)");
    RdcListing listing;
    std::string error;
    progress("listing " + o.inputs[0] + " (RenderDoc replays it)");
    if (!listRenderDocCapture(o.inputs[0], listing, error)) return importFail(error);
    std::string note;
    addBindings(o.inputs[0], listing, note);
    printListing(o.inputs[0], listing, note);
    return 0;
  }
  if (o.suggest) return runSuggest(o);
  if (o.layout.empty()) return importFail("--layout: required (a layout file, docs/layout-format.md, or builtin:gblens)");
  if (o.output.empty()) return importFail("-o: required (the capture folder to write)");
  if (!rdc && (o.event || !o.pass.empty())) return importFail(std::string(o.event ? "--event" : "--pass") + ": applies to a RenderDoc capture (.rdc)");

  RenderOptions options;
  std::string error;
  std::vector<std::string> stated;  // the options the user gave: facts the capture records
  if (!parseLayoutParameters(o.params, options, error, &stated) ||
      (!o.size.empty() && !setOption(options, "size", o.size, error)))
    return importFail(error);
  removeDebrisOf("import", o.output);
  ImportInput in;
  if (!loadImportLayout(o.layout, layoutParameters(options), in.layout, in.layoutDir, error)) return importFail(error);
  if (const std::string why = importCameraRefusal(in.layout); !why.empty()) return importFail(why);
  if (!o.size.empty()) in.layout.width = options.width, in.layout.height = options.height;
  in.cameraFile = o.camera;
  in.allowOutsideSources = o.allowOutside;
  if (!o.frames.empty()) return runImportSequence(o, in, options, stated, rdc);
  RenderDocImported read;
  if (rdc) {
    RenderDocImport r{o.inputs[0], o.event, o.pass, !o.camera.empty(), {}};
    progress("reading " + o.inputs[0] + " (RenderDoc replays it: the listing, the texels, the camera's buffer)");
    if (!readRenderDocImport(r, in, read, error)) return importFail(error);
  } else {
    in.files = o.inputs;
  }

  if (hasFramePattern(in.layout))
    return importFail(o.layout + ": its sources name frames (####): give --frames A..B (the sequence to write)");
  FrameSnapshot frame;
  progress("decoding " + std::to_string(in.layout.targets.size()) + " targets with layout " + o.layout);
  if (!importedFrame(in, options, stated, frame, error)) return importFail(error);
  CaptureMeta meta;
  meta.scene = "import:";
  for (const std::string& input : o.inputs) meta.scene += " " + input;
  meta.driver = read.listing.driverNote;
  // Where the frame came from, as data: compare warns when two imports were replayed differently.
  meta.source = {{"inputs", o.inputs}};
  if (rdc) {
    meta.source["tool"] = "RenderDoc";
    for (const char* key : {"recorded", "replay"})
      if (read.listing.provenance.contains(key)) meta.source[key] = read.listing.provenance[key];
  }
  meta.commandLine = commandLine();
  progress("writing " + o.output);
  if (!writeCapture(o.output, frame, meta, error)) return importFail(error);

  std::printf("imported %s (%ux%u) with layout %s into %s\n", rdc ? o.inputs[0].c_str() : "files", frame.camera.width,
              frame.camera.height, o.layout.c_str(), o.output.c_str());
  for (uint32_t t = 0; t < frame.layout.targets.size(); ++t) {
    const LayoutTarget& lt = frame.layout.targets[t];
    if (frame.images[t].present())
      std::printf("  %-20s %-14s %ux%u  %s\n", lt.name.c_str(), lt.format.name.c_str(), frame.images[t].image.width,
                  frame.images[t].image.height, sourceText(lt, read).c_str());
  }
  for (const RenderDocImported::LeftOut& l : read.leftOut) std::printf("  %-20s absent: %s\n", l.target.c_str(), l.why.c_str());
  const LayoutCamera& c = frame.layout.camera;
  if (c.present)
    std::printf("camera    %s: %s, %s view, world up %s (%s-handed), near %.6g far %.6g%s\n", c.from.c_str(),
                orthographic(frame.camera) ? "orthographic" : "perspective", c.leftHanded ? "left-handed" : "right-handed",
                name(c.up), c.worldLeftHanded ? "left" : "right", frame.camera.znear, frame.camera.zfar,
                frame.camera.reversedZ ? ", reversed Z" : "");
  else
    std::printf("camera    none (the layout gives none: positions only as stored, vectors only in view space)\n");
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
  cmd->add_option("--layout", o->layout,
                  "what the G-buffer holds: a layout file (docs/layout-format.md) or a layout gblens carries: " +
                      builtinLayoutNames());
  cmd->add_option("-o,--output", o->output, "the capture folder to write (atomically); --suggest-layout: the draft's file");
  cmd->add_option("--frames", o->frames, "A..B: the frames a layout's #### pattern names, written as one sequence (docs/temporal.md)");
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
  CLI::Option* list = cmd->add_flag("--list", o->list,
                                     "RenderDoc: print the capture's passes, events, textures (name, id, format, size) and "
                                     "the buffers each pass binds (name, id, size, set/binding, stages)");
  cmd->add_flag("--suggest-layout", o->suggest,
                "draft a layout (to -o, else stdout): RenderDoc: the G-buffer pass's targets, a guessed quantity per "
                "channel and the camera searched for in its buffers; image files: targets from channel names")
      ->excludes(list);
  cmd->add_flag("--allow-outside-sources", o->allowOutside,
                "let the layout read files outside its folder and the given files' folders (a layout you trust)");
  cmd->add_flag("--verbose", o->verbose, "print what image libraries say about broken files as they say it");
  return {cmd, [o]() -> int { return runImport(*o); }};
}

}  // namespace gb
