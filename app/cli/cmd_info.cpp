// gblens info: what a scene holds (meshes, triangles, materials, textures, cameras with their
// --camera index, lights, bounds, what gblens ignores) and, with --timing, how long it takes to
// load (parse / decode / build) and to be ready on the GPU (initRenderer).
#include <chrono>
#include <cmath>
#include <cstdio>
#include <memory>

#include "app/cli/cli.h"
#include "renderer/frame/session.h"
#include "renderer/scene/builtin.h"

namespace gb {

namespace {

struct InfoOptions {
  std::string scene = "builtin:temple";
  int lights = 256;
  bool timing = false;
  std::string device;
  bool validate = false;
};

using Clock = std::chrono::steady_clock;
double msSince(Clock::time_point t) { return std::chrono::duration<double, std::milli>(Clock::now() - t).count(); }

void printScene(const Scene& s, const SceneLoadStats& st, bool file) {
  std::printf("scene       %s\n", s.source.c_str());
  uint64_t vertices = s.vertices.size(), indices = s.indices.size();
  if (file)
    std::printf("meshes      %u glTF meshes, %u primitives -> %zu drawn meshes, %u nodes\n", st.fileMeshes,
                st.filePrimitives, s.meshes.size(), st.fileNodes);
  else
    std::printf("meshes      %zu\n", s.meshes.size());
  std::printf("instances   %zu\n", s.instances.size());
  std::printf("triangles   %llu drawn (%llu unique), %llu vertices\n", (unsigned long long)drawnTriangles(s),
              (unsigned long long)(indices / 3), (unsigned long long)vertices);
  std::printf("materials   %zu\n", s.materials.size());
  for (size_t i = 0; i < s.materials.size(); ++i) {
    const MaterialDesc& m = s.materials[i];
    const char* alpha = m.alphaMode == AlphaMode::Opaque ? "OPAQUE" : m.alphaMode == AlphaMode::Mask ? "MASK" : "BLEND";
    std::printf("  [%zu] %-28s %s%s specular %.3f%s%s\n", i, m.name.c_str(), alpha, m.doubleSided ? " double-sided" : "",
                m.specular, m.baseColorTexture >= 0 ? " base-texture" : "", m.normalTexture >= 0 ? " normal-texture" : "");
  }
  uint64_t texels = 0;
  for (const Texture& t : s.textures) texels += uint64_t(t.width) * t.height;
  std::printf("textures    %zu (%.1f MiB as RGBA8, before mips)%s\n", s.textures.size(), double(texels) * 4.0 / 1048576.0,
              file ? (", " + std::to_string(st.fileImages) + " images in the file").c_str() : "");
  for (size_t i = 0; i < s.textures.size(); ++i)
    std::printf("  [%zu] %-28s %ux%u %s\n", i, s.textures[i].name.c_str(), s.textures[i].width, s.textures[i].height,
                s.textures[i].srgb ? "sRGB" : "linear");
  std::printf("cameras     %zu (select with --camera N; 0 is the default)\n", s.cameras.size());
  for (size_t i = 0; i < s.cameras.size(); ++i) {
    const CameraDesc& c = s.cameras[i];
    glm::dvec3 p(c.worldFromEye[3]), fwd = -glm::dvec3(c.worldFromEye[2]);
    std::printf("  [%zu] %-20s yfov %.1f deg  near %.4g far %.4g  at (%.4g, %.4g, %.4g) looking (%.3f, %.3f, %.3f)\n", i,
                c.name.c_str(), c.yfov * 180.0 / 3.141592653589793, c.znear, c.zfar, p.x, p.y, p.z, fwd.x, fwd.y, fwd.z);
  }
  if (s.generatedLights)
    std::printf("lights      %zu generated point lights (--lights N)%s\n", s.lights.size(), s.sun.enabled ? " + sun" : "");
  else
    std::printf("lights      from the file: %u point, %u spot (drawn as point), %u directional%s -> %zu point lights%s\n",
                st.pointLights, st.spotLights, st.directionalLights, st.directionalLights ? " (sun)" : "", s.lights.size(),
                s.sun.enabled ? " + sun" : ", no sun");
  for (size_t i = 0; i < s.lights.size() && !s.generatedLights; ++i) {
    const PointLightDesc& l = s.lights[i];
    std::printf("  [%zu] at (%.4g, %.4g, %.4g) radius %.4g colour (%.3f, %.3f, %.3f) intensity %.4g\n", i, l.center.x,
                l.center.y, l.center.z, l.radius, l.color.r, l.color.g, l.color.b, l.intensity);
  }
  if (s.bounds.empty()) {
    std::printf("bounds      empty (nothing to draw)\n");
  } else {
    glm::dvec3 size = s.bounds.max - s.bounds.min;
    std::printf("bounds      min (%.4g, %.4g, %.4g) max (%.4g, %.4g, %.4g) size (%.4g, %.4g, %.4g)\n", s.bounds.min.x,
                s.bounds.min.y, s.bounds.min.z, s.bounds.max.x, s.bounds.max.y, s.bounds.max.z, size.x, size.y, size.z);
  }
  for (const std::string& i : st.ignored) std::printf("ignored     %s\n", i.c_str());
}

}  // namespace

Command addInfoCommand(CLI::App& root) {
  auto o = std::make_shared<InfoOptions>();
  CLI::App* cmd = root.add_subcommand("info", "list what a scene holds; --timing: load and upload time");
  cmd->add_option("SCENE", o->scene, "builtin:temple, or a .gltf/.glb file")->capture_default_str();
  cmd->add_option("--lights", o->lights, "generated point lights for scenes without lights (0..65536)")
      ->check(CLI::Range(0, 65536))
      ->capture_default_str();
  cmd->add_flag("--timing", o->timing, "also time loading (parse/decode/build) and the GPU upload (initRenderer)");
  cmd->add_option("--device", o->device, "Vulkan device for --timing, by name or index");
  cmd->add_flag("--validate", o->validate, "enable Vulkan validation layers for --timing");
  return {cmd, [o]() -> int {
            SceneLoadStats stats;
            Scene scene;
            auto t0 = Clock::now();
            try {
              scene = loadScene(o->scene, o->lights, &stats);
            } catch (const SceneError& e) {
              std::fprintf(stderr, "gblens: %s\n", e.message.c_str());
              return 2;
            }
            double loadMs = msSince(t0);
            for (const std::string& w : scene.warnings) std::fprintf(stderr, "gblens: warning: %s\n", w.c_str());
            const bool file = o->scene.rfind("builtin:", 0) != 0;
            printScene(scene, stats, file);
            if (!o->timing) return 0;

            // The device, the upload and the first frame timed apart (only the upload is the scene's).
            auto t1 = Clock::now();
            HeadlessSession session({o->device, o->validate, true});
            double contextMs = msSince(t1);
            auto t2 = Clock::now();
            session.useScene(scene);
            double uploadMs = msSince(t2);
            RenderOptions ro;
            ro.lights = o->lights;
            auto t3 = Clock::now();
            session.render(ro);
            double firstFrameMs = msSince(t3);
            session.releaseScene();  // validation messages of the teardown count too
            int status = session.reportValidation() ? 1 : 0;
            std::printf("timing      load %.1f ms (parse %.1f, decode %.1f, build %.1f)\n", loadMs, stats.parseMs,
                        stats.decodeMs, stats.buildMs);
            std::printf("            upload %.1f ms (initRenderer: buffers, textures with mips)\n", uploadMs);
            std::printf("            ready in %.1f ms (load + upload) on %s\n", loadMs + uploadMs,
                        session.deviceName().c_str());
            std::printf("            not counted: Vulkan context %.1f ms, first %ux%u frame %.1f ms (pipelines created)\n",
                        contextMs, ro.width, ro.height, firstFrameMs);
            return status;
          }};
}

}  // namespace gb
