// The probe's reference column (issue 17, part 3): the double-precision ray-traced reference
// (renderer/reference) at one pixel of a gblens frame, beside what its G-buffer stores there,
// with the differences `gblens error` measures over whole frames. Needs the frame's own scene.
#pragma once
#include <string>

#include <nlohmann/json.hpp>

#include "renderer/reference/reference.h"
#include "views/analysis/probe.h"

namespace gb {

struct ReferencePixel {
  reference::Surface surface;       // what the pixel-centre ray meets (hit, normal, depth, sun, ...)
  glm::dvec3 hdr{0.0};              // the reference's shading (no fairy sprites)
  // Against the G-buffer's dossier, where both have a surface and see the same triangle:
  bool compared = false;
  std::string note;                 // why not compared, or what to keep in mind
  double normalDeg = 0.0;           // angle between decoded and reference normals
  double eyeDepthRelative = 0.0;    // |depth.Z - reference| / reference
  double positionRelative = 0.0;    // |P(lighting passes' source) - P_ref| / reference eye depth
  bool shadowDiffers = false;       // stored shadow term (rounded) against sun visibility
  double hdrRelative = 0.0;         // max over R, G, B of |stored - reference| / max(|reference|, 1e-6)
};

// The reference at (x, y) of frame `f` (its camera, time and lights; `rays` built from the scene
// the frame was rendered from), compared with the dossier `d` of the same pixel.
ReferencePixel referencePixel(const reference::RayScene& rays, const FrameSnapshot& f, const PixelDossier& d);
nlohmann::json referenceJson(const ReferencePixel& r);
std::string referenceText(const ReferencePixel& r);

}  // namespace gb
