// What this device's sampler makes of 8-bit sRGB values (srgb_probe.cpp).
#pragma once
#include <vector>

#include "renderer/gpu/renderer_state.h"

namespace gb {

// What this device's sampler returns for each 8-bit sRGB value (index = byte), measured once.
const std::vector<float>& probeSrgbDecode(Renderer& r);

}  // namespace gb
