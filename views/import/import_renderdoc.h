// A RenderDoc capture as the source of an import: the event to read at (--event, --pass, or after the
// pass that last writes each target), the raw texels of the layout's targets (checked against the
// layout's formats), and the camera's uniform buffer, gathered into an ImportInput (import.h).
#pragma once
#include <string>
#include <vector>

#include "views/import/import.h"
#include "views/import/renderdoc_replay.h"

namespace gb {

struct RenderDocImport {
  std::string rdc;
  uint32_t event = 0;        // --event EID (0: not given)
  std::string pass;          // --pass NAME: the last event of that label region
  bool cameraGiven = false;  // --camera: the layout's uniform buffer is not read
  RdcReplayOptions replay;
};

// What was read, for the command's summary.
struct RenderDocImported {
  RdcListing listing;
  struct Read {
    std::string target, texture, format;
    uint32_t event = 0;
  };
  std::vector<Read> reads;
  struct LeftOut {
    std::string target, why;
  };
  // Targets without a source whose name no written texture has, or whose texture is a 1x1 stand-in
  // (gblens keeps one for a target a turned-off feature would write) in a larger frame.
  std::vector<LeftOut> leftOut;
  std::string camera;  // where the camera's buffer was read: " (#id) at event N" ("" : not read)
};

// Fills `in` (whose layout is set) from the capture. A target with {"renderdoc": NAME} reads that
// texture; a target without a source reads the texture of its own name, and is left out (absent)
// when the capture has none, no pass up to the event writes it, or it is a 1x1 stand-in while the
// frame is larger. False with one line naming the capture or the layout's target and field.
bool readRenderDocImport(const RenderDocImport& r, ImportInput& in, RenderDocImported& info, std::string& error);

// Target `target` of `in` reads `texels` (its size, bytes, and a multisampled texture's sample count).
void takeRenderDocTexels(ImportInput& in, const std::string& target, RdcTexels&& texels);

}  // namespace gb
