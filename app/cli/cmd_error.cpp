// gblens error: one frame against the double-precision reference, error per quantity (normal,
// albedo, eye depth, positions from every source, shadow, final HDR colour, lighting passes),
// silhouettes counted apart. --json for machines; -o DIR writes where the errors are as PNGs.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "app/cli/cli.h"
#include "renderer/frame/session.h"
#include "views/analysis/accuracy.h"
#include "views/capture/report.h"

namespace gb {

static void printStats(const char* what, const char* unit, const ErrorStats& s) {
  if (!s.count) {
    std::printf("  %-34s (no pixels)\n", what);
    return;
  }
  std::printf("  %-34s mean %-10.3g rms %-10.3g p99 %-10.3g max %-10.3g %s  (%llu px)\n", what, s.mean, s.rms, s.p99, s.max,
              unit, (unsigned long long)s.count);
}

static void printReport(const FrameError& e, const RenderOptions& o, double bandTexels) {
  uint64_t total = uint64_t(e.width) * e.height;
  uint64_t sil = e.silhouette + e.coverageOnlyGpu + e.coverageOnlyReference;
  std::printf("pixels %llu: surface %llu, sky %llu, silhouettes %llu (%.3f%%: other triangle %llu, only GPU %llu, only "
              "reference %llu; from %s)\n",
              (unsigned long long)total, (unsigned long long)e.surface, (unsigned long long)e.sky, (unsigned long long)sil,
              100.0 * sil / std::max<uint64_t>(total, 1), (unsigned long long)e.silhouette,
              (unsigned long long)e.coverageOnlyGpu, (unsigned long long)e.coverageOnlyReference,
              e.primitiveIds ? "primitive_id" : "depth differences");
  std::printf("G-buffer (surface pixels):\n");
  printStats("normal", "deg", e.normalDeg);
  printStats("albedo, untextured", "/255", e.albedoUntextured);
  printStats("albedo, textured (filtering differs)", "/255", e.albedoTextured);
  printStats("specular", "/255", e.specular);
  printStats("eye depth", "relative", e.eyeDepthRelative);
  printStats("eye depth", "ulp", e.eyeDepthUlps);
  std::printf("positions, |P - P_ref| / eye depth (and scene units):\n");
  auto pos = [](const char* what, const PositionError& p) {
    printStats(what, "", p.relative);
    printStats("", "units", p.absolute);
  };
  pos("from eye depth (R32F)", e.fromEyeDepth);
  printStats("  beyond the float placement", "", e.fromEyeDepthBeyondPlacement);
  std::string hw = std::string("from hardware depth (") + name(o.depthFormat) + (o.reversedZ ? ", reversed Z)" : ")");
  pos(hw.c_str(), e.fromHardwareDepth);
  if (e.storedPosition) {
    std::string st = std::string("stored position (") + name(o.position) + ", " + name(o.positionSpace) + ")";
    pos(st.c_str(), e.fromPosition);
  }
  pos("used by the lighting passes", e.used);
  std::printf("shadow (faces toward the sun; penumbra band %.3g texels excluded):\n", bandTexels);
  std::printf("  %-34s %.4f%% of %llu px (false shadow %llu, false light %llu); band %llu px (%llu differ); not compared %llu\n",
              "lit/shadowed differs", 100.0 * e.shadow.fraction, (unsigned long long)e.shadow.compared,
              (unsigned long long)e.shadow.falseShadow, (unsigned long long)e.shadow.falseLight,
              (unsigned long long)e.shadow.band, (unsigned long long)e.shadow.bandMismatched,
              (unsigned long long)e.shadow.notCompared);
  std::printf("final HDR colour vs the reference (surface pixels; per pixel max over R,G,B):\n");
  printStats("absolute", "", e.hdr.absolute);
  printStats("relative", "", e.hdr.relative);
  printStats("relative, untextured, outside band", "", e.hdrUntexturedOutsideBand.relative);
  std::printf("lighting passes alone (reference shading of the GPU's own G-buffer, %s accumulation):\n", name(o.accumFormat));
  printStats("relative", "", e.lighting.relative);
  printStats("per light contribution", "", e.lighting.perContribution);
  if (e.srgbDecodeMaxRelative >= 0.0)
    std::printf("  (albedo as this device decodes sRGB: up to %.3g relative off the exact curve)\n", e.srgbDecodeMaxRelative);
}

static bool writeErrorImages(const std::string& dir, const FrameError& e) {
  bool ok = true;
  for (const ErrorMapDef& map : errorMaps()) {
    std::string error, path = (std::filesystem::path(dir) / (std::string(map.name) + ".png")).string();
    if (!writePng(path, map.make(e), error)) {
      std::fprintf(stderr, "gblens error: %s\n", error.c_str());
      ok = false;
    }
  }
  if (ok) std::fprintf(stderr, "gblens: wrote error images to %s\n", dir.c_str());
  return ok;
}

static int measure(const CommonOptions& o, bool json, double band) {
  Scene scene;
  if (!loadSceneOrReport(o, scene)) return 2;
  if (!o.output.empty()) {
    std::error_code ec;
    std::filesystem::create_directories(o.output, ec);
    if (ec) {
      std::fprintf(stderr, "gblens error: -o %s: cannot create the folder (%s)\n", o.output.c_str(),
                   ec.message().c_str());
      return 2;
    }
  }
  HeadlessSession session(scene, {o.device, o.validate, json});
  // An output the device cannot hold is refused here, before any target is allocated.
  if (std::string why = session.tooLarge(o.render); !why.empty()) {
    std::fprintf(stderr, "gblens error: %s\n", why.c_str());
    return 2;
  }
  if (std::string why = session.refused(o.render); !why.empty()) {  // --gbuffer visibility out of reach
    std::fprintf(stderr, "gblens error: %s\n", why.c_str());
    return 2;
  }
  if (!session.primitiveIdAvailable())
    std::fprintf(stderr, "gblens error: %s has no gl_PrimitiveID: silhouettes from depth differences\n",
                 session.deviceName().c_str());
  ReferenceCache cache(scene);
  auto render = [&](const RenderOptions& ro, const std::vector<Target>& t) { return session.renderSnapshot(ro, t); };
  FrameError e = measureFrame(render, o.render, cache, band).error;
  if (json) {
    nlohmann::json j = {{"scene", scene.source},
                        {"device", session.deviceName()},
                        {"options", optionsJson(o.render)},
                        {"shadow_band_texels", band},
                        {"error", errorJson(e)}};
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    printReport(e, o.render, band);
  }
  int status = 0;
  if (!o.output.empty() && !writeErrorImages(o.output, e)) status = 2;
  if (session.reportValidation() && status == 0) status = 1;
  return status;
}

Command addErrorCommand(CLI::App& root) {
  auto o = std::make_shared<CommonOptions>();
  auto json = std::make_shared<bool>(false);
  auto band = std::make_shared<double>(kShadowBandTexels);
  CLI::App* cmd = root.add_subcommand("error", "one frame's error per quantity against the double-precision CPU reference");
  addCommonOptions(cmd, *o);
  cmd->add_flag("--json", *json, "print the figures as JSON on stdout");
  cmd->add_option("-o,--output", o->output, "folder for error images (shadow, silhouettes, normal, hdr, position, lighting)");
  cmd->add_option("--band", *band, "penumbra band half-width in shadow-map texels, left out of the shadow comparison")
      ->check(CLI::Range(0.0, 1000.0))
      ->capture_default_str();
  return {cmd, [o, json, band]() -> int {
            std::string error;
            if (!finishCommonOptions(*o, error)) {
              std::fprintf(stderr, "gblens error: %s\n", error.c_str());
              return 2;
            }
            return measure(*o, *json, *band);
          }};
}

}  // namespace gb
