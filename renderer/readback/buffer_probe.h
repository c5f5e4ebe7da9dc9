// The device probes' dispatch (codec_probe, shading_probe): a compute shader run once over a
// host-visible buffer of cases, in place, waited for.
#pragma once
#include <vector>

#include "renderer/gpu/renderer_state.h"

namespace gb {

// `shader` with these specialization constants over `values` (the pass set's kBindingTileLights
// storage buffer, MemoryUse::Readback), `groups` workgroups; returns when the results are readable.
void runBufferProbe(Renderer& r, Shader shader, const std::vector<SpecConstant>& spec, const Buffer& values, uint32_t groups);

}  // namespace gb
