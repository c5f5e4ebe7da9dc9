// gblens probe CAPTURE X Y [--json] [--reference]: the pixel dossier (views/probe.h) from a
// capture's files; --reference adds the ray-traced reference at the pixel (views/analysis/
// probe_reference.h), from the scene the manifest names.
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "renderer/scene/builtin.h"
#include "views/analysis/probe.h"
#include "views/analysis/probe_reference.h"
#include "views/capture/capture.h"

namespace gb {

namespace {
struct ProbeArgs {
  std::string capture;
  uint32_t x = 0, y = 0;
  bool json = false, reference = false;
};

// The scene the capture was rendered from, as its manifest names it (with the same light count),
// checked against the content hash it recorded; false with one line when it cannot be had.
bool captureScene(const Capture& c, Scene& scene, std::string& error) {
  const nlohmann::json& s = c.manifest.value("scene", nlohmann::json::object());
  const std::string source = s.value("source", "");
  if (source.empty() || source.rfind("import:", 0) == 0) {
    error = c.dir + ": --reference needs the scene the frame was rendered from (this capture names none: imported?)";
    return false;
  }
  try {
    scene = loadScene(source, c.frame.options.lights);
  } catch (const std::exception& e) {
    error = c.dir + ": --reference: the capture's scene " + source + ": " + e.what();
    return false;
  }
  const std::string sha = s.value("content_sha256", "");
  if (!sha.empty() && sha != sceneContentSha256(scene)) {
    error = c.dir + ": --reference: " + source + " has changed since the capture (content_sha256 differs)";
    return false;
  }
  return true;
}
}  // namespace

Command addProbeCommand(CLI::App& root) {
  auto o = std::make_shared<ProbeArgs>();
  CLI::App* cmd = root.add_subcommand("probe", "print everything about one pixel of a capture");
  cmd->add_option("CAPTURE", o->capture, "capture directory")->required();
  cmd->add_option("X", o->x, "pixel column (0 = left)")->required();
  cmd->add_option("Y", o->y, "pixel row (0 = top)")->required();
  cmd->add_flag("--json", o->json, "print the dossier as JSON");
  cmd->add_flag("--reference", o->reference,
                "add the double-precision ray-traced reference at the pixel and the G-buffer's error against it (the "
                "capture's own scene)");
  return {cmd, [o]() -> int {
            Capture c;
            std::string error;
            if (!loadCapture(o->capture, c, error)) {
              std::fprintf(stderr, "gblens probe: %s\n", error.c_str());
              return 2;
            }
            PixelDossier d = probePixel(c.frame, o->x, o->y);
            if (!d.error.empty()) {
              std::fprintf(stderr, "gblens probe: %s\n", d.error.c_str());
              return 2;
            }
            nlohmann::json j = o->json ? dossierJson(d) : nlohmann::json();
            std::string text = o->json ? "" : dossierText(d);
            if (o->reference) {
              Scene scene;
              if (!captureScene(c, scene, error)) {
                std::fprintf(stderr, "gblens probe: %s\n", error.c_str());
                return 2;
              }
              const reference::RayScene rays(scene);
              const ReferencePixel r = referencePixel(rays, c.frame, d);
              if (o->json) j["reference"] = referenceJson(r);
              else text += referenceText(r);
            }
            if (o->json)
              std::printf("%s\n", j.dump(2).c_str());
            else
              std::fputs(text.c_str(), stdout);
            return 0;
          }};
}

}  // namespace gb
