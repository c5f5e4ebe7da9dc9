// gblens render: one headless frame of a scene, written as a PNG of the final image or of one
// examination view (--target, a name of the view table); with --frames N, the frames before the
// last in flight (frame_ms in --stats: their throughput).
#include <cstdio>
#include <memory>
#include <optional>

#include "app/cli/cli.h"
#include "renderer/core/assert.h"
#include "renderer/core/layout_json.h"
#include "renderer/frame/session.h"
#include "views/analysis/visualize.h"
#include "views/capture/report.h"

namespace gb {

// The view's target must be computed under these options: a one-line refusal otherwise.
static bool viewAvailable(const ViewDef& view, Target t, const RenderOptions& ro, const Scene& scene) {
  Absent why = targetAbsence(t, ro, scene.sun.enabled);
  if (why == Absent::No) return true;
  std::fprintf(stderr, "gblens render: --target %s needs %s, which is %s\n", view.name.c_str(), targetName(t),
               absentText(why));
  return false;
}

static int render(const CommonOptions& o, const std::string& viewName) {
  Scene scene;
  if (!loadSceneOrReport(o, scene)) return 2;
  RenderOptions ro = o.render;
  const Layout layout = nativeLayout(ro);
  const std::vector<ViewDef> views = layoutViews(layout);
  const int k = findView(views, viewName);
  if (k < 0) {
    std::fprintf(stderr, "gblens render: --target %s: not a view of gblens's frame (%s)\n", viewName.c_str(),
                 viewNameList(views).c_str());
    return 2;
  }
  const ViewDef& view = views[size_t(k)];
  Target target = Target::Final;
  const bool known = parseTarget(layout.targets[view.target].name, target);  // gblens's layout names its targets
  GB_ASSERT(known);
  ro.coverage = target == Target::CoverageMasked || target == Target::CoverageFull;
  // Single pass: the G-buffer stays in tile memory (transient) unless this view reads it.
  ro.keepGBuffer = targetInfo(target).role == TargetRole::GBuffer || view.surfaceOnly;
  HeadlessSession session(scene, {o.device, o.validate});
  // Which targets the frame computes depends on the G-buffer kind this device runs (--gbuffer auto).
  const RenderOptions ran = session.frameOptions(ro);
  if (!viewAvailable(view, target, ran, scene)) return 2;
  // An output the device cannot hold is refused here, before any target is allocated.
  if (std::string why = session.tooLarge(ro); !why.empty()) {
    std::fprintf(stderr, "gblens render: %s\n", why.c_str());
    return 2;
  }
  if (std::string why = session.refused(ro); !why.empty()) {  // --gbuffer visibility out of reach
    std::fprintf(stderr, "gblens render: %s\n", why.c_str());
    return 2;
  }
  FrameRequest request;
  request.readback = {target};
  // Normals and positions are drawn where a surface is: the eye depth says where.
  if (view.surfaceOnly && target != Target::Depth && targetAbsence(Target::Depth, ran, scene.sun.enabled) == Absent::No)
    request.readback.push_back(Target::Depth);
  std::vector<FrameStats> frames;
  // Frames before the last in flight (the CPU records one while the GPU runs the one before),
  // when there are enough for a burst and none counts coverage; the last one is read back.
  std::optional<FrameBurst> burst;
  if (o.frames >= 3 && !ro.coverage) {
    burst = session.renderBurst(ro, o.frames - 1);
    frames.push_back(burst->first);
    frames.insert(frames.end(), burst->frames.begin(), burst->frames.end());
  }
  for (int i = int(frames.size()); i < o.frames; ++i) {
    RenderDocCapture rdc(session.context(), i + 1 == o.frames);  // under RenderDoc: the frame written
    frames.push_back(session.render(ro, request));
    reportRenderDocCapture("gblens render", rdc);
  }
  FrameSnapshot frame = session.snapshot(request.readback);
  FrameStats counted;  // culling counts from one more frame, not timed
  if (o.stats) counted = session.renderCounting(ro, request);
  int status = 0;
  std::string error;
  const std::vector<ViewDef> frameViews = layoutViews(frame.layout);
  if (!writePng(o.output, visualize(frame, frameViews[size_t(findView(frameViews, view.name))], defaultSettings(view)), error)) {
    std::fprintf(stderr, "gblens render: %s\n", error.c_str());
    status = 2;
  } else {
    std::fprintf(stderr, "gblens: wrote %s (%s, %ux%u)\n", o.output.c_str(), view.name.c_str(), ro.width, ro.height);
  }
  if (o.stats)
    std::printf("%s\n",
                statsJson(frames, {session.deviceName(), session.driverName(), scene.source}, ro, &counted,
                          burst ? &*burst : nullptr)
                    .dump(2)
                    .c_str());
  if (session.reportValidation() && status == 0) status = 1;
  return status;
}

Command addRenderCommand(CLI::App& root) {
  auto o = std::make_shared<CommonOptions>();
  auto target = std::make_shared<std::string>("final");
  o->output = "frame.png";
  CLI::App* cmd = root.add_subcommand("render", "render one frame headless and write a PNG");
  addCommonOptions(cmd, *o);
  cmd->add_option("-o,--output", o->output, "PNG to write")->capture_default_str();
  addViewOption(cmd, "--target", *target, "the view to write");
  return {cmd, [o, target]() -> int {
            std::string error;
            if (!finishCommonOptions(*o, error)) {
              std::fprintf(stderr, "gblens render: %s\n", error.c_str());
              return 2;
            }
            return render(*o, *target);
          }};
}

}  // namespace gb
