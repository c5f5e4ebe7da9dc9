// RenderDoc captures (.rdc) as a source of G-buffers: list a capture's passes and textures, read the
// stored bits of textures and the bytes of buffers at an event. The replay runs in a child process,
// the system /usr/bin/python3 with Debian's python3-renderdoc, on a script carried inside the binary
// (renderdoc_replay.py), watched for progress: a replay that stops making progress is ended with one
// line naming the limit and the variable that raises it, never a hang.
#pragma once
#include <array>
#include <cstdint>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "renderer/core/targets.h"

namespace gb {

struct RdcTexture {
  std::string name;    // RenderDoc's name: the debug name the application gave, else RenderDoc's own
  uint64_t id = 0;     // RenderDoc's resource id ("#id" names it where names repeat)
  bool autoName = false;  // the name is RenderDoc's own ("2D Image 127"): the application gave none
  std::string format;  // RenderDoc's format name, e.g. "R16G16B16A16_FLOAT", "D32S8"
  std::optional<TexelFormat> texelFormat;  // when gblens can hold the format
  uint32_t width = 0, height = 0;
  uint32_t depth = 1, mips = 1, layers = 1, samples = 1;
  std::vector<uint32_t> reads;  // events that read it (sampled, input attachment, copy/blit/resolve source)
  std::vector<uint32_t> computeWrites;  // dispatches that bind it as a storage image (may write it)
  bool presented = false;       // a swapchain image
};

// computeWrites for people: "27", "27 and 3 more" ("" : none).
inline std::string computeWriteEvents(const RdcTexture& t) {
  if (t.computeWrites.empty()) return "";
  return std::to_string(t.computeWrites.front()) +
         (t.computeWrites.size() > 1 ? " and " + std::to_string(t.computeWrites.size() - 1) + " more" : "");
}

// A uniform or storage buffer used at a draw or dispatch: its kind and the stages that read it (from
// RenderDoc's usage records, in a listing), and where it is bound (set, binding, array index), the
// bound byte range and the members the shaders' reflection declares (from the pipeline state,
// readDrawState; `bound` says whether those are known).
struct RdcBinding {
  std::string name;  // RenderDoc's name, "#id" when unnamed
  uint64_t id = 0;
  bool autoName = false;  // RenderDoc made the name up
  std::string kind;  // "uniform" or "storage"
  uint64_t bytes = 0;                 // the whole buffer
  uint32_t set = 0, binding = 0, index = 0;
  std::vector<std::string> stages;    // vertex, fragment, compute, ...
  uint64_t offset = 0, range = 0;     // the bound range, bytes from the buffer's start
  struct Member {
    std::string name, type;
    uint64_t offset = 0;              // from the start of the bound range
  };
  std::vector<Member> members;
  bool bound = false;                 // set, binding, index, offset, range and members are known
  std::vector<uint8_t> data;          // the bound range's bytes (readDrawState with bytes)
};

// A label region (every one, nested ones too), or a render pass no region names by itself.
struct RdcPass {
  std::string name;
  uint32_t firstEvent = 0, lastEvent = 0;
  uint32_t depth = 0;                // nesting: 0 for a top-level region
  std::vector<std::string> writes;   // textures bound for writing inside it (targets, storage, copy/clear
                                     // destinations), by name ("#id" when unnamed)
  uint32_t boundAt = 0;              // its last draw or dispatch (0: none) ...
  std::vector<RdcBinding> buffers;   // ... the buffers used there,
  std::vector<std::string> outputs;  // its colour targets, depth target (names; a draw only)
  std::string depthTarget;
  std::array<double, 4> viewport{};  // x, y, width, height (readDrawState; Vulkan: a negative height flips y)
  // The application's own store ops of the render passes begun inside it, per attachment texture
  // ("store", "dont_care", "none"; "" where the capture does not say): an aspect not stored is no
  // quantity of the frame.
  struct Store {
    std::string texture, store, stencilStore;
  };
  std::vector<Store> stores;
};

struct RdcBuffer {
  std::string name;
  uint64_t id = 0, bytes = 0;
};

struct RdcListing {
  std::string api;         // the capture's API, e.g. "Vulkan"
  std::string driverNote;  // where it was recorded and what replays it here
  // The same as data (a manifest's "source"): "recorded" {api, machine, device, driver, driver_info}
  // as far as the capture says, "replay" {renderdoc, device, degraded} of this machine.
  nlohmann::json provenance;
  std::vector<RdcPass> passes;
  std::vector<RdcTexture> textures;
  std::vector<RdcBuffer> buffers;  // every buffer of the capture
  uint32_t lastEvent = 0;
};

// How long a replay may run: while it reports progress (a line per step); silent, kReplayStallSeconds
// without CPU time (hung) or kReplayBusySeconds plus one second per 10 MiB of capture of working without
// a word (spinning); in any case kReplayLimitSeconds plus one second per 10 MiB. GBLENS_RENDERDOC_STALL,
// GBLENS_RENDERDOC_BUSY and GBLENS_RENDERDOC_TIMEOUT (seconds) override them.
constexpr int kReplayStallSeconds = 30;
constexpr int kReplayBusySeconds = 120;
constexpr int kReplayLimitSeconds = 600;

// Where the replay runs. The defaults suit the command line; tests shorten the limits.
struct RdcReplayOptions {
  std::string python = "/usr/bin/python3";
  int stallSeconds = 0;  // 0: kReplayStallSeconds (GBLENS_RENDERDOC_STALL overrides both)
  int busySeconds = 0;   // 0: the busy limit above (GBLENS_RENDERDOC_BUSY overrides both)
  int limitSeconds = 0;  // 0: the limit above (GBLENS_RENDERDOC_TIMEOUT overrides both)
};

bool listRenderDocCapture(const std::string& rdc, RdcListing& out, std::string& error,
                          const RdcReplayOptions& options = {});

// Raw texels of named (or "#id") textures after `event` (0: the end of the pass that last writes
// each one), packed as renderer/core/texels.h says: colour tightly, depth/stencil as the depth
// plane then one stencil byte a texel. Exactly the stored bits, not a tone-mapped export.
struct RdcTexels {
  RdcTexture texture;
  uint32_t event = 0;  // the event it was read after
  std::vector<uint8_t> bytes;  // a multisampled texture: texture.samples planes of sampleBytes, sample 0 first
  size_t sampleBytes = 0;
};
bool readRenderDocTexels(const std::string& rdc, uint32_t event, const std::vector<std::string>& textures,
                         std::vector<RdcTexels>& out, std::string& error, const RdcReplayOptions& options = {});

// The bytes of a buffer (by name or "#id") at `event` (0: its first use), e.g. a uniform buffer
// holding the camera matrices. `at` (optional) receives the buffer's id and the event it was read at.
struct RdcBufferRead {
  uint64_t id = 0;
  uint32_t event = 0;
};
bool readRenderDocBuffer(const std::string& rdc, uint32_t event, const std::string& buffer, std::vector<uint8_t>& out,
                         std::string& error, const RdcReplayOptions& options = {}, RdcBufferRead* at = nullptr);

// The buffers bound at the last draw or dispatch up to each event (0: the frame's last) with where
// they are bound, and the viewport (out[event].boundAt: that draw's event); with `bytes`, each bound
// range's bytes. RenderDoc 1.24 can crash moving from some events to others (seen on llvmpipe: a
// heap corruption replaying from gblens's point_lights draws to light_coverage's): the replay
// starts again at the event it stopped at, and an event that crashes a fresh replay too is left out,
// named in `skipped`. False only when the replay cannot run at all.
bool readDrawState(const std::string& rdc, const std::vector<uint32_t>& events, bool bytes,
                   std::map<uint32_t, RdcPass>& out, std::string& skipped, std::string& error,
                   const RdcReplayOptions& options = {});

// RenderDoc's format description -> the TexelFormat gblens holds it in (rgba8 sRGB/unorm/snorm,
// rgba16 snorm, rgb10a2, rgba16f, rgba32f, r32f, r32 uint, d32s8, d24s8, d32f, d16); none otherwise.
struct RdcFormat {
  std::string name, type, compType;  // RenderDoc's names: "R8G8B8A8_SRGB", "Regular", "UNormSRGB"
  uint32_t compCount = 0, compByteWidth = 0;
  bool bgra = false;
};
std::optional<TexelFormat> texelFormatOf(const RdcFormat& format);

}  // namespace gb
