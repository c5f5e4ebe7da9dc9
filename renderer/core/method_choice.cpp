// The crossovers behind `--method auto` and the measurements behind `--gbuffer auto` (see
// method_choice.h). Each entry names the bench run it comes from; docs/performance.md and
// docs/perf-gpu.md have the tables and how to re-measure them.
#include "renderer/core/method_choice.h"

#include "renderer/core/visibility.h"

namespace gb {

const char* name(DeviceKind d) { return d == DeviceKind::Cpu ? "a CPU device" : "a GPU"; }

const std::vector<MethodCrossover>& methodCrossovers() {
  static const std::vector<MethodCrossover> table = {
      {DeviceKind::Cpu, 0, Method::Deferred,
       "lavapipe, builtin:temple 1280x720: fastest at 16 lights (the cluster grid 1.02-1.07x slower)"},
      {DeviceKind::Cpu, 64, Method::Clustered,
       "lavapipe, builtin:temple 1280x720: the cluster grid 1.1x faster than deferred at 64 lights, 1.6x at 256, "
       "2.6x at 1024, 4.7x at 4096"},
      {DeviceKind::Gpu, 0, Method::Tiled,
       "H100, builtin:temple 720p-4K, frames in flight: tiled 6-12% faster than clustered at 16 and 256 lights, "
       "5% at 1024"},
      {DeviceKind::Gpu, 4096, Method::Clustered,
       "H100, builtin:temple 720p-4K, frames in flight: within 2.5% of tiled at 4096 lights, faster from 16384 "
       "(1.2x), 1.4-1.5x at 65536"},
  };
  return table;
}

MethodChoice chooseMethod(const RenderOptions& o, DeviceKind device, size_t lights) {
  if (o.method != Method::Auto) return {o.method, std::string("--method ") + name(o.method)};
  if (o.path == Path::SinglePass)
    return {Method::Deferred, "auto: deferred, the only method with the single-pass path (--path single-pass)"};
  const MethodCrossover* pick = nullptr;
  for (const MethodCrossover& c : methodCrossovers())
    if (c.device == device && c.fromLights <= lights && (!pick || c.fromLights >= pick->fromLights)) pick = &c;
  if (!pick) return {Method::Deferred, "auto: deferred (no crossover measured for this device)"};
  return {pick->method, std::string("auto: ") + name(pick->method) + " on " + name(device) + " (" + pick->measured + ")"};
}

const std::vector<GBufferMeasurement>& gbufferMeasurements() {
  static const std::vector<GBufferMeasurement> table = {
      {DeviceKind::Cpu, GBufferKind::Raster,
       "lavapipe, builtin:temple 1280x720: the visibility resolve about 180 ms against 16 ms for the G-buffer pass"},
      {DeviceKind::Gpu, GBufferKind::Visibility,
       "H200, builtin:temple, frames in flight, faster in every cell measured: 1080p 256 lights 1.41 -> 1.09 ms, "
       "65536 lights 4.46 -> 4.13, 4K 256 lights 5.17 -> 4.00, 65536 lights 13.27 -> 12.09"},
  };
  return table;
}

GBufferChoice chooseGBuffer(const RenderOptions& o, DeviceKind device) {
  if (o.gbuffer != GBufferKind::Auto) return {o.gbuffer, std::string("--gbuffer ") + name(o.gbuffer)};
  // The options that leave visibility nothing to resolve: the refusal --gbuffer visibility would get.
  RenderOptions visibility = o;
  visibility.gbuffer = GBufferKind::Visibility;
  if (const std::string refused = visibilityOptionsRefusal(visibility); !refused.empty())
    return {GBufferKind::Raster, "auto: raster (" + refused + ")"};
  for (const GBufferMeasurement& m : gbufferMeasurements())
    if (m.device == device)
      return {m.gbuffer, std::string("auto: ") + name(m.gbuffer) + " on " + name(device) + " (" + m.measured + ")"};
  return {GBufferKind::Raster, "auto: raster (nothing measured for this device)"};
}

bool clusterGridOn(const RenderOptions& o, DeviceKind device, Method ran, std::string& reason) {
  if (ran != Method::Clustered) return reason = std::string("method ") + name(ran) + ": no clusters", false;
  if (o.clusterAssign == ClusterAssign::Gpu) return reason = "occupied clusters in compute (--cluster-assign gpu)", false;
  if (o.clusterAssign == ClusterAssign::Cpu) return reason = "cluster grid on the CPU (--cluster-assign cpu)", true;
  if (o.lightSetup == LightSetup::Gpu)
    return reason = "auto: occupied clusters in compute (--light-setup gpu: the grid needs the lights on the CPU)", false;
  if (device == DeviceKind::Cpu)
    return reason = "auto: cluster grid on the CPU, shaded in a fragment pass (a CPU device: its compute passes are "
                    "slow, docs/performance.md)",
           true;
  return reason = "auto: occupied clusters in compute (a GPU)", false;
}

}  // namespace gb
