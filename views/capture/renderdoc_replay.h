// RenderDoc captures (.rdc) as a source of G-buffers: list a capture's passes and textures, read the
// stored bits of textures and the bytes of buffers at an event. The replay runs in a child process,
// the system /usr/bin/python3 with Debian's python3-renderdoc, on a script carried inside the binary
// (renderdoc_replay.py), under a time limit: a capture that does not replay on this machine's driver
// gives one line naming the API and the driver, never a hang.
#pragma once
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "renderer/core/targets.h"

namespace gb {

struct RdcTexture {
  std::string name;    // RenderDoc's name: the debug name the application gave, else RenderDoc's own
  uint64_t id = 0;     // RenderDoc's resource id ("#id" names it where names repeat)
  std::string format;  // RenderDoc's format name, e.g. "R16G16B16A16_FLOAT", "D32S8"
  std::optional<TexelFormat> texelFormat;  // when gblens can hold the format
  uint32_t width = 0, height = 0;
  uint32_t depth = 1, mips = 1, layers = 1, samples = 1;
};

// A label region (every one, nested ones too), or a render pass no region names by itself.
struct RdcPass {
  std::string name;
  uint32_t firstEvent = 0, lastEvent = 0;
  uint32_t depth = 0;                // nesting: 0 for a top-level region
  std::vector<std::string> writes;   // textures bound for writing inside it (targets, storage, copy/clear
                                     // destinations), by name ("#id" when unnamed)
};

struct RdcListing {
  std::string api;         // the capture's API, e.g. "Vulkan"
  std::string driverNote;  // where it was recorded and what replays it here
  std::vector<RdcPass> passes;
  std::vector<RdcTexture> textures;
  uint32_t lastEvent = 0;
};

// The replay's time limit: kReplayBaseSeconds plus one second per 10 MiB of capture (a small
// capture: 20 s; listing one takes a few seconds), unless set.
constexpr int kReplayBaseSeconds = 20;

// Where the replay runs. The defaults suit the command line; tests shorten the limit.
struct RdcReplayOptions {
  std::string python = "/usr/bin/python3";
  int timeoutSeconds = 0;  // 0: the limit above; GBLENS_RENDERDOC_TIMEOUT overrides both (seconds)
};

bool listRenderDocCapture(const std::string& rdc, RdcListing& out, std::string& error,
                          const RdcReplayOptions& options = {});

// Raw texels of named (or "#id") textures after `event` (0: the end of the pass that last writes
// each one), packed as renderer/core/texels.h says: colour tightly, depth/stencil as the depth
// plane then one stencil byte a texel. Exactly the stored bits, not a tone-mapped export.
struct RdcTexels {
  RdcTexture texture;
  uint32_t event = 0;  // the event it was read after
  std::vector<uint8_t> bytes;
};
bool readRenderDocTexels(const std::string& rdc, uint32_t event, const std::vector<std::string>& textures,
                         std::vector<RdcTexels>& out, std::string& error, const RdcReplayOptions& options = {});

// The bytes of a buffer (by name or "#id") at `event` (0: its first use), e.g. a uniform buffer
// holding the camera matrices.
bool readRenderDocBuffer(const std::string& rdc, uint32_t event, const std::string& buffer, std::vector<uint8_t>& out,
                         std::string& error, const RdcReplayOptions& options = {});

// RenderDoc's format description -> the TexelFormat gblens holds it in (rgba8 sRGB/unorm/snorm,
// rgba16 snorm, rgb10a2, rgba16f, rgba32f, r32f, r32 uint, d32s8, d24s8, d32f, d16); none otherwise.
struct RdcFormat {
  std::string name, type, compType;  // RenderDoc's names: "R8G8B8A8_SRGB", "Regular", "UNormSRGB"
  uint32_t compCount = 0, compByteWidth = 0;
  bool bgra = false;
};
std::optional<TexelFormat> texelFormatOf(const RdcFormat& format);

}  // namespace gb
