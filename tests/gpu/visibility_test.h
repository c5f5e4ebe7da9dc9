// What the visibility-buffer tests share (tests/gpu/test_visibility*.cpp): the frame they render.
#pragma once
#include "renderer/core/options.h"

namespace gb {

// 160x90, 16 lights, a fixed time and a small shadow map; primitive_id on (which triangle each
// pixel shows: the neighbours on the same one, the reference's silhouettes).
inline RenderOptions visibilityOptions() {
  RenderOptions o;
  o.width = 160;
  o.height = 90;
  o.lights = 16;
  o.time = 2.5;
  o.shadowMapSize = 256;
  o.primitiveId = true;
  return o;
}

}  // namespace gb
