// Which lighting method `--method auto` runs: per kind of device and light count, from the
// crossovers `gblens bench --only methods` measured (docs/performance.md, "What auto picks").
#pragma once
#include <cstddef>
#include <string>
#include <vector>

#include "renderer/core/options.h"

namespace gb {

// The device kinds the crossovers were measured on: a CPU device (lavapipe) and a GPU (an
// NVIDIA H100; integrated and virtual GPUs use its crossovers, unmeasured).
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

// Whether a frame of method `ran` (clustered) assigns its lights on the CPU, to the cluster grid
// (--cluster-assign; auto: on a CPU device), and why ("cluster grid on the CPU: a CPU device ...").
bool clusterGridOn(const RenderOptions& o, DeviceKind device, Method ran, std::string& reason);

}  // namespace gb
