// Shared option parsing for every subcommand.
#include "app/cli.h"

#include <algorithm>
#include <cstdio>

#include "renderer/builtin.h"

namespace gb {

void addCommonOptions(CLI::App* cmd, CommonOptions& o) {
  // A later flag overrides an earlier one, so scripts can append overrides to a base command.
  cmd->option_defaults()->multi_option_policy(CLI::MultiOptionPolicy::TakeLast);
  cmd->add_option("SCENE", o.scene, "builtin:temple, or a .gltf/.glb file")->capture_default_str();
  cmd->add_option("--size", o.size, "output size WxH")->capture_default_str();
  cmd->add_option("--time", o.render.time, "animation time in seconds (fixed)")->capture_default_str();
  cmd->add_option("--lights", o.render.lights, "generated point lights (0..65536)")
      ->check(CLI::Range(0, 65536))
      ->capture_default_str();
  cmd->add_option("--camera", o.render.camera, "camera index (gblens info lists them)")
      ->check(CLI::NonNegativeNumber)
      ->capture_default_str();
  cmd->add_option("--path", o.path, "two-pass | single-pass")
      ->check(CLI::IsMember({"two-pass", "single-pass"}))
      ->capture_default_str();
  cmd->add_option("--eye-depth", o.eyeDepth, "USE_EYE_DEPTH: on | off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--stencil-culling", o.stencilCulling, "LIGHT_STENCIL_CULLING: on | off")
      ->check(CLI::IsMember({"on", "off"}))
      ->capture_default_str();
  cmd->add_option("--stencil-mask", o.stencilMask, "per-light (exact, 7 lights per stencil batch) | shared (the sample's one mask)")
      ->check(CLI::IsMember({"per-light", "shared"}))
      ->capture_default_str();
  cmd->add_option("--method", o.method, "deferred | forward | tiled")
      ->check(CLI::IsMember({"deferred", "forward", "tiled"}))
      ->capture_default_str();
  cmd->add_option("--shadow-map-size", o.render.shadowMapSize, "shadow map size in texels (square)")
      ->check(CLI::Range(1, 16384))
      ->capture_default_str();
  cmd->add_option("--frames", o.frames, "render N frames, report the median")
      ->check(CLI::Range(1, 100000))
      ->capture_default_str();
  cmd->add_flag("--stats", o.stats, "print frame statistics as JSON on stdout");
  cmd->add_option("--device", o.device, "Vulkan device by name or index (default: first GPU, else CPU)");
  cmd->add_flag("--validate", o.validate, "enable Vulkan validation layers; non-zero exit on any message");
}

bool finishCommonOptions(CommonOptions& o, std::string& error) {
  unsigned w = 0, h = 0;
  char x = 0, extra = 0;
  if (std::sscanf(o.size.c_str(), "%u%c%u%c", &w, &x, &h, &extra) != 3 || (x != 'x' && x != 'X') || w == 0 || h == 0 ||
      w > 16384 || h > 16384) {
    error = "--size " + o.size + ": expected WxH with 1..16384 each, e.g. 1280x720";
    return false;
  }
  o.render.width = w;
  o.render.height = h;
  parse(o.path, o.render.path);
  parse(o.method, o.render.method);
  o.render.eyeDepth = o.eyeDepth == "on";
  o.render.stencilCulling = o.stencilCulling == "on";
  parse(o.stencilMask, o.render.stencilMask);
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

int reportValidation(const GpuContext& ctx) {
  if (!ctx.validation) return 0;
  ValidationLog& log = validationLog();
  int n = log.errors + log.warnings;
  if (n) std::fprintf(stderr, "gblens: %d validation message(s) (%d errors)\n", n, int(log.errors));
  return n;
}

std::string& commandLine() {
  static std::string line;
  return line;
}

double median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  size_t n = v.size();
  return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace gb
