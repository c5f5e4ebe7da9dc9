// The camera of an unfamiliar capture, found by search (import --suggest-layout): every 4x4 float
// matrix in the buffers bound at the G-buffer pass, in both orders, tried as a projection
// (perspective or orthographic, either clip convention, standard or reversed depth), as a view
// matrix (view_from_world or its inverse), or as a combined clip_from_world split into both; a pair is
// kept when the G-buffer's stored positions, projected through it, land on their own pixels (and
// its depth, when the G-buffer has one).
#pragma once
#include <cstdint>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/camera.h"
#include "renderer/core/layout.h"
#include "views/import/renderdoc_replay.h"

namespace gb {

struct CameraEvidence {
  uint32_t width = 0, height = 0;
  bool clipYUp = false;           // clip y points up the image (D3D/GL; Vulkan with a negative viewport height)
  bool clipDepthGl = false;       // clip depth -1..1 (OpenGL)
  struct Sample {
    uint32_t x = 0, y = 0;
    bool hasPosition = false;
    glm::dvec3 position{0.0};     // a stored position, as stored (its space unknown)
    double depth = NAN;           // a stored hardware depth (NaN: none)
  };
  std::vector<Sample> samples;    // surface pixels
  double pixelBound = 0.5;        // how far (pixels, median) positions may land and confirm a camera
};

struct FoundCamera {
  bool found = false;
  nlohmann::json camera;          // the draft's "camera" block (with its "guess" note)
  LayoutCamera layout;            // the same, matrices filled in
  Camera converted;               // in gblens's convention (import.h)
  bool positionsChecked = false;  // stored positions confirmed the choice ...
  Space positionSpace = Space::View;  // ... in this space
  double pixelError = 0.0;        // median distance of the projected positions from their pixels
  std::vector<std::string> summary;  // lines for the terminal
};

// Every candidate in `buffers` (their bound ranges' bytes; offsets reported from the buffer's start).
// `source`: the camera block names a capture's buffer ("renderdoc") or a running application's binding
// in render pass `livePass` ("live": offsets from the bound range's start).
FoundCamera searchCamera(const std::vector<RdcBinding>& buffers, const CameraEvidence& evidence,
                         const std::string& source = "renderdoc", int livePass = 0);
// The `wanted` best distinct cameras (the first is searchCamera's), for a caller that judges them by
// other evidence (normals against a linear depth). Never empty: a first entry not found says why.
std::vector<FoundCamera> searchCameras(const std::vector<RdcBinding>& buffers, const CameraEvidence& evidence,
                                       const std::string& source, int livePass, size_t wanted);

// A camera given otherwise (a sidecar): the median distance in pixels of the stored positions,
// projected through it, from their pixels, in the space (view or world) they fit best; INFINITY
// when the evidence holds no positions or the camera does not import.
double fitPositions(const LayoutCamera& camera, const CameraEvidence& evidence, Space& space);

// The signed world axis closest to the image's up direction (a camera looking straight up or down:
// the one opposite the view direction), and how close, for the "up" guess.
Axis guessUpAxis(const LayoutCamera& camera, const Camera& converted, double& alignment);

}  // namespace gb
