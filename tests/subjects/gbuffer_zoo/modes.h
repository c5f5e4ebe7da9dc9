// The seven G-buffer designs: for each mode its render passes in recording order, their attachments
// (format, clear, store ops), what each pass samples, and its draws with their shaders and state.
// README.md and truth/MODE.json describe the same tables in words.
#pragma once
#include <vulkan/vulkan.h>

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

namespace zoo {

enum class Mode { world_tbn = 1, forward, lighting_depth, stencil_dontcare, linear_depth, view_oct, y_down };

bool parse_mode(const std::string& text, Mode& out);
const char* mode_name(Mode m);

struct Attachment {
  const char* name;  // dump file stem
  VkFormat format;
  VkClearValue clear;
  bool store;          // storeOp STORE (else DONT_CARE); the depth aspect for depth formats
  bool stencil_store;  // stencilStoreOp STORE, formats with stencil only
};

enum class DrawKind { scene, decal, markers, fullscreen };
enum class StencilUse { none, write_bits, write_id, test_floor };

struct Spirv {
  const uint32_t* words;
  size_t bytes;
};

struct Draw {
  DrawKind kind;
  Spirv vs, fs;
  bool depth_test = false, depth_write = false;
  VkCompareOp depth_op = VK_COMPARE_OP_LESS;
  StencilUse stencil = StencilUse::none;
  uint32_t color_mask = ~0u;  // bit i: colour attachment i is written
};

struct Pass {
  const char* role;  // gbuffer | lighting | composite | post | forward
  std::vector<Attachment> attachments;  // colour attachments first (location order), depth last
  std::vector<std::pair<int, int>> samples;  // [pass, attachment] bound at bindings 3, 4, ...
  std::vector<Draw> draws;
  bool flip_viewport = false;  // negative-height viewport (D3D-style clip space)
};

struct ModeDesc {
  Mode mode;
  std::vector<Pass> passes;
};

const ModeDesc& describe(Mode m);

}  // namespace zoo
