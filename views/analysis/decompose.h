// Lighting decomposition (issue 17, section 2): the frame's lighting recomputed from its G-buffer
// with the shading formulas the GPU uses (shaders/shading.h, in double), split by term and by
// light: lighting only (white albedo), diffuse, specular, sun (direct + ambient), point lights,
// and the count of point lights whose sphere reaches each surface point. `gblens decompose`
// writes them; gblens's own frames and imported ones whose layout gives lights in gblens's model.
#pragma once
#include <array>
#include <string>

#include "renderer/core/image.h"
#include "renderer/core/snapshot.h"

namespace gb {

enum class LightingTerm : uint8_t { Lighting, Diffuse, Specular, Sun, PointLights, LightCount, Count };
constexpr size_t kLightingTermCount = size_t(LightingTerm::Count);
// "lighting", "diffuse", "specular", "sun", "point_lights", "light_count": the one name of each
// (file names, JSON).
const char* name(LightingTerm t);

struct Decomposition {
  std::array<CpuImage, kLightingTermCount> images;  // RGBA32F (light_count: R32F), frame size
};

// False with `error` when the frame's lights cannot be evaluated (the layout gives none in gblens's
// model) or it has no albedo and normal. Pixels without a surface are 0 in every term. Rows are
// counted into the calling thread's WorkProgress (core/progress.h), one per row of the frame;
// cancelled, it stops and returns false ("cancelled").
bool decomposeLighting(const FrameSnapshot& f, Decomposition& out, std::string& error, unsigned threads = 0);

}  // namespace gb
