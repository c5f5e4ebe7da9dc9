// Which pass writes the G-buffer, decided by the frame's structure (a RenderDoc capture's usage
// records, or the gblens layer's report of a running application's frame): the G-buffer pass is the
// one whose colour attachments later passes read together (sampled, input attachments, copies),
// with its depth; a pass whose output is presented or that only reads others is lighting or
// composite; a later pass's own depth is not the G-buffer's; an aspect the application does not
// store (storeOp DONT_CARE) holds no quantity. Without reads to go by, the pass writing the most
// colour targets with a depth target.
#pragma once
#include <cstdint>
#include <set>
#include <string>
#include <vector>

namespace gb {

struct PassFacts {
  std::string name;   // for people ("render pass 1", a label)
  uint32_t first = 0, last = 0;  // its span in the frame's order (events, or the pass ordinal twice)
  struct Output {
    std::string image;       // an id of the image, the same across passes
    bool depth = false;      // the depth/stencil attachment
    bool stored = true;      // the application stores it (colour, or the depth aspect)
    bool stencilStored = true;  // ... and the stencil aspect (formats with one)
    bool usable = true;      // a format and shape a layout can hold
    uint32_t width = 0, height = 0;
  };
  std::vector<Output> outputs;
};

struct FrameFacts {
  std::vector<PassFacts> passes;  // in frame order
  // Per image: when it is read (in the passes' span units). Empty for every image: not known.
  std::vector<std::pair<std::string, std::vector<uint32_t>>> reads;
  bool readsKnown = false;
  std::set<std::string> presented;  // images shown on screen
};

enum class Writer : uint8_t { GBuffer, Later, Forward };

struct PassTarget {
  size_t pass = 0, output = 0;  // FrameFacts::passes[pass].outputs[output]
  Writer writer = Writer::GBuffer;
  bool readLater = false;       // a later pass reads it
  bool presented = false;
  bool stencilStored = true;
};

struct PassRoles {
  int gbuffer = -1;             // the G-buffer pass (-1: none: forward rendering, or nothing drawn)
  bool forward = false;         // no pass writes a G-buffer: `gbuffer` is the pass that draws the frame
  std::vector<PassTarget> targets;  // what a draft holds, G-buffer pass first
  std::vector<std::string> notes;   // why, and what was left out, for people
};

// `forced`: a pass the user named (--pass / --event), or -1.
PassRoles decideRoles(const FrameFacts& facts, int forced = -1);

}  // namespace gb
