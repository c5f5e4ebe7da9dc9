// Object names and command-buffer label regions (VK_EXT_debug_utils), so that RenderDoc, Nsight and
// validation messages show "gbuffer > albedo_specular" instead of anonymous handles. Every call is a
// no-op when the instance lacks the extension (the function pointers stay null).
#pragma once
#include <vulkan/vulkan.h>

#include <cstdint>

namespace gb {

struct GpuContext;

// True when the instance can enable VK_EXT_debug_utils (the loader or a layer offers it).
bool debugUtilsAvailable();
// Loads the extension's functions into ctx.debugUtils (createContext calls it once the device exists).
void loadDebugUtils(GpuContext& ctx);

// Sets a debug name (RenderDoc's resource names, validation messages).
void setName(const GpuContext& ctx, uint64_t handle, VkObjectType type, const char* name);

// A label region in a command buffer: RenderDoc's event browser shows it as a folder of its commands.
void beginLabel(const GpuContext& ctx, VkCommandBuffer cmd, const char* name);
void endLabel(const GpuContext& ctx, VkCommandBuffer cmd);

// beginLabel for the life of the scope.
class LabelScope {
 public:
  LabelScope(const GpuContext& ctx, VkCommandBuffer cmd, const char* name) : ctx_(ctx), cmd_(cmd) {
    beginLabel(ctx, cmd, name);
  }
  ~LabelScope() { endLabel(ctx_, cmd_); }
  LabelScope(const LabelScope&) = delete;
  LabelScope& operator=(const LabelScope&) = delete;

 private:
  const GpuContext& ctx_;
  VkCommandBuffer cmd_;
};

}  // namespace gb
