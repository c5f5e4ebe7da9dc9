// Which lighting method `--method auto` runs: per kind of device and light count, from the
// crossovers `gblens bench --only methods` measured (docs/performance.md, "What auto picks"); and
// which G-buffer `--gbuffer auto` fills, per kind of device, from the same bench's runs.
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "renderer/core/options.h"

namespace gb {

// The device kinds the crossovers were measured on: a CPU device (lavapipe) and a GPU (an
// NVIDIA H100 for the methods, an H200 for the G-buffer; integrated and virtual GPUs use their
// figures, unmeasured).
enum class DeviceKind { Cpu, Gpu };
const char* name(DeviceKind d);

struct MethodChoice {
  Method method = Method::Deferred;  // never Auto
  std::string reason;                // "auto: clustered on a GPU (...)", or "--method tiled"
};

// One measured crossover: on `device`, from `fromLights` scene lights on, auto runs `method`
// (the entry with the largest fromLights not above the light count).
struct MethodCrossover {
  DeviceKind device;
  size_t fromLights;
  Method method;
  const char* measured;  // where the figure comes from (docs/performance.md)
};
const std::vector<MethodCrossover>& methodCrossovers();

// The method a frame with these options runs on `device` with `lights` scene lights.
MethodChoice chooseMethod(const RenderOptions& o, DeviceKind device, size_t lights);

struct GBufferChoice {
  GBufferKind gbuffer = GBufferKind::Raster;  // never Auto
  std::string reason;                         // "auto: visibility on a GPU (...)", or "--gbuffer raster"
};

// One measurement behind --gbuffer auto: on `device`, auto fills the G-buffer as `gbuffer`.
struct GBufferMeasurement {
  DeviceKind device;
  GBufferKind gbuffer;
  const char* measured;  // where the figure comes from (docs/perf-gpu.md, "The visibility buffer")
};
const std::vector<GBufferMeasurement>& gbufferMeasurements();

// The G-buffer kind a frame with these options fills on `device`, before the scene and the device's
// features are asked (frameGBuffer, renderer/gpu/render_targets.h): a named kind as named; auto
// raster where the options leave visibility no G-buffer to resolve (method forward, the
// single-pass path), else the measured kind for the device.
GBufferChoice chooseGBuffer(const RenderOptions& o, DeviceKind device);

// Whether a frame of method `ran` (clustered) assigns its lights on the CPU, to the cluster grid
// (--cluster-assign; auto: on a CPU device), and why ("cluster grid on the CPU: a CPU device ...").
bool clusterGridOn(const RenderOptions& o, DeviceKind device, Method ran, std::string& reason);

}  // namespace gb
