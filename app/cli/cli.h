// Options every subcommand shares, parsed the same way everywhere (CLI11), and the helpers
// that turn them into a scene, a device and a renderer.
#pragma once
#include <CLI/CLI.hpp>

#include <functional>
#include <map>
#include <string>
#include <vector>

#include "app/cli/params.h"
#include "renderer/core/options.h"
#include "renderer/frame/renderer.h"
#include "renderer/scene/scene.h"
#include "renderer/vk/renderdoc_capture.h"

namespace gb {

struct CommonOptions {
  std::string scene = "builtin:temple";
  RenderOptions render;                        // defaults before parsing; the parsed options after
  std::map<std::string, std::string> values;   // option table name -> text given (or the default)
  int frames = 1;
  bool stats = false;
  std::string device;
  bool validate = false;
  std::string output;
};

// SCENE, one flag per entry of the option table (renderer/options.h: --size, --lights, --path,
// --normal-format, ...), --frames, --stats, --device, --validate. (-o is added by the commands
// that write something.) Flags a command does not want, or "scene" for the positional, can be
// listed in `except`.
void addCommonOptions(CLI::App* cmd, CommonOptions& o, const std::vector<std::string>& except = {});

// An option naming a view of the view table (render --target, view --view): the accepted names
// come from the table, listed in the help.
void addViewOption(CLI::App* cmd, const std::string& flag, std::string& value, const std::string& help);

// Completes RenderOptions from the parsed strings; on a malformed value returns false with a
// one-line message naming the flag.
bool finishCommonOptions(CommonOptions& o, std::string& error);

// A registered subcommand: its CLI11 node and what to run when it was chosen.
struct Command {
  CLI::App* app = nullptr;
  std::function<int()> run;
  int usageExit = 2;  // exit status for a malformed command line (compare: 4, as idiff's file error)
};

Command addRenderCommand(CLI::App& root);
Command addInfoCommand(CLI::App& root);
Command addViewCommand(CLI::App& root);
Command addCaptureCommand(CLI::App& root);
Command addCompareCommand(CLI::App& root);
Command addProbeCommand(CLI::App& root);

// Removes what an interrupted run writing `path` left beside it (views/capture/debris.h) and says so
// on stderr ("gblens COMMAND: removed ...").
void removeDebrisOf(const char* command, const std::string& path);

// Progress on stderr ("  .. TEXT"), as stress prints its own, for a person at a terminal only, so
// that what a script reads (a pipe, a file) is the command's one-line messages. terminalProgress: the
// same as a callback for the engines' progress, null when stderr is no terminal.
void progressLine(const std::string& text);
std::function<void(const std::string&)> terminalProgress();

// The command line as typed (set by main; recorded in capture manifests).
std::string& commandLine();
Command addErrorCommand(CLI::App& root);
Command addBenchCommand(CLI::App& root);
Command addStressCommand(CLI::App& root);
Command addImportCommand(CLI::App& root);
Command addCheckCommand(CLI::App& root);
Command addStatsCommand(CLI::App& root);
Command addDecomposeCommand(CLI::App& root);
Command addAttachCommand(CLI::App& root);
Command addMotionCommand(CLI::App& root);
Command addFlickerCommand(CLI::App& root);
Command addHistoryCommand(CLI::App& root);


// Loads SCENE; on a user mistake prints one line and returns false (caller exits 2).
bool loadSceneOrReport(const CommonOptions& o, Scene& scene);

// Ends a RenderDoc capture of a command's frame and prints where the .rdc went, or why none was
// written (nothing when the command does not run under RenderDoc).
void reportRenderDocCapture(const char* command, RenderDocCapture& capture);

}  // namespace gb
