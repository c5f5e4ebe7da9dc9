// Importing a G-buffer another program wrote: every target of a layout read from its source (an
// image file through OpenImageIO, a raw dump, or texels a RenderDoc replay returned), checked against
// the layout, and assembled into a FrameSnapshot that captures, views, the probe and compare treat
// exactly as gblens's own frames. The camera is turned into gblens's convention here.
#pragma once
#include <map>
#include <string>
#include <vector>

#include "renderer/core/layout.h"
#include "renderer/core/snapshot.h"

namespace gb {

struct ImportInput {
  Layout layout;                    // resolved (layout_json.h)
  std::string layoutDir;            // relative source paths: the layout file's folder ...
  std::vector<std::string> files;   // ... unless a file given on the command line has that name; a
                                    // source without "file" takes the only one given
  std::string cameraFile;           // --camera: a sidecar JSON overriding the layout's camera
  // Texels read from a RenderDoc capture for its targets ({"renderdoc": ...} sources), packed as
  // renderer/core/texels.h says, by target name; and the bytes of the camera's uniform buffer.
  std::map<std::string, std::vector<uint8_t>> renderdocTexels;
  std::vector<uint8_t> renderdocCameraBuffer;
};

// Reads every target and the camera. False with one line naming the file, the target and the
// field (a missing channel, a size or format the layout does not match, a singular camera, ...).
bool importFrame(const ImportInput& in, FrameSnapshot& out, std::string& error);

// The camera a layout describes (matrices, sidecar or uniform-buffer bytes) in gblens's convention:
// Vulkan clip space (y down, depth 0..1), right-handed view space, Y-up world.
bool importCamera(const LayoutCamera& c, uint32_t width, uint32_t height, Camera& out, std::string& error);

}  // namespace gb
