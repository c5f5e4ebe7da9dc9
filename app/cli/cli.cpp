// Shared option parsing for every subcommand.
#include "app/cli/cli.h"

#include <algorithm>
#include <cstdio>
#include <cstdlib>

#include <unistd.h>

#include "renderer/core/layout_json.h"
#include "renderer/scene/builtin.h"
#include "views/analysis/view_table.h"
#include "views/capture/debris.h"

namespace gb {

void addCommonOptions(CLI::App* cmd, CommonOptions& o, const std::vector<std::string>& except) {
  // A later flag overrides an earlier one, so scripts can append overrides to a base command.
  cmd->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  if (std::find(except.begin(), except.end(), "scene") == except.end())
    cmd->add_option("SCENE", o.scene, "builtin:temple, builtin:depth-range, builtin:normal-sphere, or a .gltf/.glb file")->capture_default_str();
  // One flag per option-table entry: the flag, the JSON key and the bench name are one name.
  for (const OptionInfo& info : optionTable()) {
    if (std::find(except.begin(), except.end(), info.name) != except.end()) continue;
    std::string& value = o.values[info.name];
    value = getOption(o.render, info.name);
    CLI::Option* opt = cmd->add_option(flagName(info.name), value, info.help)->capture_default_str();
    if (info.kind == OptionKind::Choice) opt->check(CLI::IsMember(info.choices));
  }
  cmd->add_option("--frames", o.frames,
                  "render N frames, report the median (render: from 3 frames on, those before the last in flight, "
                  "frame_ms their throughput)")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_flag("--stats", o.stats, "print frame statistics as JSON on stdout");
  cmd->add_option("--device", o.device, "Vulkan device by name or index (default: first GPU, else CPU)");
  cmd->add_flag("--validate", o.validate, "enable Vulkan validation layers; non-zero exit on any message");
}

bool finishCommonOptions(CommonOptions& o, std::string& error) {
  for (const auto& [name, value] : o.values)
    if (!setOption(o.render, name, value, error)) return false;
  return true;
}

bool loadSceneOrReport(const CommonOptions& o, Scene& scene) {
  try {
    scene = loadScene(o.scene, o.render.lights);
  } catch (const SceneError& e) {
    std::fprintf(stderr, "gblens: %s\n", e.message.c_str());
    return false;
  }
  for (const std::string& w : scene.warnings) std::fprintf(stderr, "gblens: warning: %s\n", w.c_str());
  if (size_t(o.render.camera) >= scene.cameras.size()) {
    std::fprintf(stderr, "gblens: --camera %d: %s has %zu camera(s)\n", o.render.camera, o.scene.c_str(),
                 scene.cameras.size());
    return false;
  }
  return true;
}

void reportRenderDocCapture(const char* command, RenderDocCapture& capture) {
  if (!capture.active()) return;
  std::string error;
  std::string path = capture.end(&error);
  if (path.empty())
    std::fprintf(stderr, "%s: %s\n", command, error.c_str());
  else
    std::fprintf(stderr, "gblens: RenderDoc capture %s\n", path.c_str());
}

void removeDebrisOf(const char* command, const std::string& path) {
  for (const std::string& line : removeDebris(path)) std::fprintf(stderr, "gblens %s: %s\n", command, line.c_str());
}

void progressLine(const std::string& text) {
  static const bool terminal = isatty(STDERR_FILENO) == 1;
  if (terminal) std::fprintf(stderr, "  .. %s\n", text.c_str());
}

std::function<void(const std::string&)> terminalProgress() {
  if (isatty(STDERR_FILENO) != 1) return {};
  return [](const std::string& s) { progressLine(s); };
}

std::string& commandLine() {
  static std::string line;
  return line;
}

void addViewOption(CLI::App* cmd, const std::string& flag, std::string& value, const std::string& help) {
  // A frame's views are its layout's quantities: gblens's own here; a capture's layout may have others.
  const std::string list = viewNameList(layoutViews(nativeLayout(RenderOptions{})));
  cmd->add_option(flag, value, help + " (a quantity of the frame's layout; gblens's: " + list + "; case and _ ignored)")
      ->capture_default_str();
}

}  // namespace gb
