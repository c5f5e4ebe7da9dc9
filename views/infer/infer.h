// What an unknown G-buffer holds, decided by evidence (docs/import.md "How gblens decides"): each
// target's channel groups are tested against the geometry that ties depth, positions and normals
// together — a position is what a pinhole maps onto its own pixel, a normal is perpendicular to the
// surface that depth or positions describe (in the space where it is), a linear depth is the
// distance that surface lies at, albedo is what the light multiplies — and the hypothesis that
// explains the data is kept, with its evidence, a confidence and what it beat. What no evidence
// decides is drafted as stored values ("unknown"). Shared by `import --suggest-layout` (RenderDoc
// captures, image files) and `attach --suggest` (a running application).
#pragma once
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/camera.h"
#include "renderer/core/image.h"
#include "renderer/core/layout.h"
#include "views/import/renderdoc_replay.h"
#include "views/infer/evidence.h"
#include "views/infer/roles.h"

namespace gb {

struct InferTarget {
  std::string label;                 // the name the application or file gave it ("" : none)
  StorageFormat format;
  const CpuImage* texels = nullptr;  // null: none to look at
  Writer writer = Writer::GBuffer;
  bool readLater = false;            // a later pass reads it
  bool presented = false;            // shown on screen
  bool stencilStored = true;         // depth/stencil formats: the application stores the stencil
};

struct InferInput {
  std::vector<InferTarget> targets;
  std::vector<RdcBinding> buffers;   // bound where the G-buffer pass draws, with their bytes (camera search)
  bool clipYUp = false, clipDepthGl = false;  // the API's clip space (and a negative viewport)
  bool clipYKnown = true;                     // false: the viewport's sign is not known (live): both are tried
  std::string bufferSource = "renderdoc";     // the camera block's source key for a found buffer
  int livePass = 0;                           // "live": the render pass the buffers were bound in
  // A camera given otherwise (a sidecar beside image files): used, not searched for.
  std::optional<LayoutCamera> given;
  Camera givenConverted;
  std::string givenNote;
};

struct InferOutput {
  std::vector<nlohmann::json> quantities;  // per target: its "quantities" list
  nlohmann::json camera;                   // the draft's camera block (null: none)
  std::vector<std::string> summary;        // for the terminal
  SurfaceMask surface;
};

InferOutput inferLayout(const InferInput& input);

}  // namespace gb
