// Importing a G-buffer another program wrote: every target of a layout read from its source (an
// image file through OpenImageIO, a raw dump, or texels a RenderDoc replay returned), checked against
// the layout, and assembled into a FrameSnapshot that captures, views, the probe and compare treat
// exactly as gblens's own frames. The camera is turned into gblens's convention here.
#pragma once
#include <array>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "renderer/core/layout.h"
#include "renderer/core/layout_json.h"
#include "renderer/core/snapshot.h"

namespace gb {

// Byte buffers of frames already shown, for the next frame's texels (ImportInput::pool): a stream's
// frames are of one size, and a buffer already written once is filled again without the page
// faults and zero-filling of a fresh allocation (at 4K most of a streamed frame's decoding).
struct TexelPool {
  std::vector<std::vector<uint8_t>> spare;
  // The smallest spare buffer of at least `bytes` capacity (moved out), else an empty one.
  std::vector<uint8_t> take(size_t bytes);
  // A frame's image buffers (every target's, every sample plane's), `keep` buffers at most.
  void give(FrameSnapshot&& frame, size_t keep);
};

struct ImportInput {
  Layout layout;                    // resolved (layout_json.h)
  std::string layoutDir;            // relative source paths: the layout file's folder ...
  std::vector<std::string> files;   // ... unless a file given on the command line has that name; a
                                    // source without "file" takes the only one given
  // A file the layout names (a source, the camera's sidecar) must lie in the layout's folder or the
  // folder of a file given (after symlinks): a layout someone else wrote cannot read your files.
  // True (--allow-outside-sources): anywhere.
  bool allowOutsideSources = false;
  std::string cameraFile;           // --camera: a sidecar JSON overriding the layout's camera
  // Texels read from a RenderDoc capture for its targets ({"renderdoc": ...} sources), packed as
  // renderer/core/texels.h says, by target name; and the bytes of the camera's uniform buffer.
  std::map<std::string, std::vector<uint8_t>> renderdocTexels;
  std::map<std::string, std::array<uint32_t, 2>> renderdocSizes;  // their textures' width and height
  std::map<std::string, uint32_t> renderdocSamples;  // a multisampled texture's samples: that many planes
  std::vector<uint8_t> renderdocCameraBuffer;
  std::string renderdocCameraBufferAt;  // where it was read, for people: " (#123) at event 140"
  std::string capture;                  // the RenderDoc capture imported ("": files): a sidecar may be beside it
  // Texels the gblens layer streamed for {"live": ...} targets (`gblens attach`, views/live/live.h),
  // by target name: packed as texels.h says, in the stream's shared memory, with the attachment's size.
  struct LiveTexels {
    const uint8_t* data = nullptr;
    size_t bytes = 0;
    uint32_t width = 0, height = 0;
    uint32_t samples = 1;     // a multisampled attachment: this many planes, each `sampleStride` bytes
    size_t sampleStride = 0;
  };
  std::map<std::string, LiveTexels> liveTexels;
  TexelPool* pool = nullptr;  // where the live texels' buffers come from (null: allocated)
  // Targets the source does not hold (e.g. a target without a source whose name no texture of the
  // RenderDoc capture has): absent from the frame ("not captured"), not an error.
  std::set<std::string> leftOut;
};

// A layout for import: a file, or "builtin:NAME" (assets/layouts/NAME.json carried in the binary,
// e.g. builtin:gblens), resolved with `params`. `dir` receives the folder relative source paths
// start from ("" for a built-in layout: the files given on the command line).
bool loadImportLayout(const std::string& spec, const LayoutParameters& params, Layout& out, std::string& dir,
                      std::string& error);
// A quantity a layout without a camera cannot hold: a hardware depth (positions come from it) and a
// normal or position in any space but the view's.
bool needsCamera(const Quantity& q);
// "builtin:blender-cycles, builtin:gblens, ...": every layout the binary carries.
std::string builtinLayoutNames();

// The 16 floats at `offset` of a buffer as a matrix (m[column][row]), stored column- or row-major.
glm::dmat4 matrixFromFloats(const std::vector<uint8_t>& bytes, uint64_t offset, bool rowMajor);

// Reads every target and the camera. False with one line naming the file, the target and the
// field (a missing channel, a size or format the layout does not match, a singular camera, ...).
bool importFrame(const ImportInput& in, FrameSnapshot& out, std::string& error);

// "FILE: targets[T]: \"NAME\"": where a target is, for messages.
std::string layoutTargetWhere(const Layout& l, uint32_t t);

// The options an imported frame records: `options` (what a parameterised layout was resolved with)
// with the frame's own size and depth direction. Only those and `stated` (the --param names) are
// facts: the rest is recorded as unknown (FrameSnapshot::unknown), never as a default.
void setImportedOptions(FrameSnapshot& frame, const RenderOptions& options, const std::vector<std::string>& stated = {});

// The camera a layout describes (matrices, sidecar or uniform-buffer bytes) in gblens's convention:
// Vulkan clip space (y down, depth 0..1; w = -z for a perspective, 1 for an orthographic
// projection), right-handed view space, Y-up right-handed world. Any other projection, or a
// perspective looking the way the view's handedness says it does not, is refused with one line.
bool importCamera(const LayoutCamera& c, uint32_t width, uint32_t height, Camera& out, std::string& error);

}  // namespace gb
