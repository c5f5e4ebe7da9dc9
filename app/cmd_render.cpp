// gblens render: one headless frame of a scene, written as a PNG of the final image or of one
// examination view (--target).
#include <cstdio>
#include <memory>

#include "app/cli.h"
#include "renderer/frame_memory.h"
#include "views/report.h"
#include "views/visualize.h"

namespace gb {

Command addRenderCommand(CLI::App& root) {
  auto o = std::make_shared<CommonOptions>();
  auto target = std::make_shared<std::string>("final");
  o->output = "frame.png";
  CLI::App* cmd = root.add_subcommand("render", "render one frame headless and write a PNG");
  addCommonOptions(cmd, *o);
  cmd->add_option("-o,--output", o->output, "PNG to write")->capture_default_str();
  cmd->add_option("--target", *target,
                  "final | albedo | normal | depth | specular | shadow | shadowmap | coverage_masked | coverage_full | "
                  "hdr | hardware_depth | stencil")
      ->check(CLI::IsMember({"final", "albedo", "normal", "depth", "specular", "shadow", "shadowmap",
                             "coverage_masked", "coverage_full", "hdr", "hardware_depth", "stencil"}))
      ->capture_default_str();
  return {cmd, [o, target]() -> int {
            std::string error;
            if (!finishCommonOptions(*o, error)) {
              std::fprintf(stderr, "gblens render: %s\n", error.c_str());
              return 2;
            }
            Scene scene;
            if (!loadSceneOrReport(*o, scene)) return 2;
            ViewKind view = ViewKind::Final;
            parseView(*target, view);
            RenderOptions ro = o->render;
            ro.coverage = view == ViewKind::CoverageMasked || view == ViewKind::CoverageFull;
            for (const std::string& name : viewTargets(view)) {
              Target t;
              parseTarget(name, t);
              if (std::string why = targetUnavailable(t, ro, &scene); !why.empty()) {
                std::fprintf(stderr, "gblens render: --target %s needs %s, which is %s\n", target->c_str(), name.c_str(),
                             why.c_str());
                return 2;
              }
            }

            ContextOptions co;
            co.validation = o->validate;
            co.device = o->device;
            GpuContext ctx = createContext(co);
            // An output the device cannot hold is refused here, before any target is allocated.
            if (std::string why = frameTooLarge(ctx, scene, ro); !why.empty()) {
              std::fprintf(stderr, "gblens render: %s\n", why.c_str());
              destroyContext(ctx);
              return 2;
            }
            int status = 0;
            {
              Renderer r;
              initRenderer(r, ctx, scene);
              FrameRequest request;
              for (const std::string& name : viewTargets(view)) {
                Target t;
                parseTarget(name, t);
                request.readback.push_back(t);
              }
              // Single pass: the G-buffer stays in tile memory (transient) unless this view reads it.
              ro.keepGBuffer = false;
              for (Target t : request.readback)
                ro.keepGBuffer |= t == Target::AlbedoSpecular || t == Target::NormalShadow || t == Target::Depth;
              std::vector<FrameStats> frames;
              for (int i = 0; i < o->frames; ++i) frames.push_back(renderFrame(r, ro, request));
              FrameStats counted;  // culling counts from one more frame, not timed
              if (o->stats) counted = renderCountingFrame(r, ro, request);
              FrameImages images;
              images.normalFormat = ro.normalFormat;
              images.final = &r.readback[size_t(Target::Final)];
              images.albedoSpecular = &r.readback[size_t(Target::AlbedoSpecular)];
              images.normalShadow = &r.readback[size_t(Target::NormalShadow)];
              images.depth = &r.readback[size_t(Target::Depth)];
              images.shadowMap = &r.readback[size_t(Target::ShadowMap)];
              images.coverageMasked = &r.readback[size_t(Target::CoverageMasked)];
              images.coverageFull = &r.readback[size_t(Target::CoverageFull)];
              images.hdr = &r.readback[size_t(Target::Hdr)];
              images.depthStencil = &r.readback[size_t(Target::DepthStencil)];
              images.reversedZ = ro.reversedZ;
              if (!writePng(o->output, visualize(view, images), error)) {
                std::fprintf(stderr, "gblens render: %s\n", error.c_str());
                status = 2;
              } else {
                std::fprintf(stderr, "gblens: wrote %s (%s, %ux%u)\n", o->output.c_str(), viewName(view), ro.width,
                             ro.height);
              }
              if (o->stats) std::printf("%s\n", statsJson(frames, ctx, ro, scene, &counted).dump(2).c_str());
              destroyRenderer(r);
            }
            if (reportValidation(ctx) && status == 0) status = 1;
            destroyContext(ctx);
            return status;
          }};
}

}  // namespace gb
