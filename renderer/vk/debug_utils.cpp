// VK_EXT_debug_utils names and labels (see debug_utils.h).
#include "renderer/vk/debug_utils.h"

#include <cstring>
#include <vector>

#include "renderer/vk/context.h"

namespace gb {

bool debugUtilsAvailable() {
  uint32_t n = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &n, nullptr);
  std::vector<VkExtensionProperties> exts(n);
  vkEnumerateInstanceExtensionProperties(nullptr, &n, exts.data());
  for (const VkExtensionProperties& e : exts)
    if (std::strcmp(e.extensionName, VK_EXT_DEBUG_UTILS_EXTENSION_NAME) == 0) return true;
  return false;
}

void loadDebugUtils(GpuContext& ctx) {
  // Instance-level entry points: the loader's trampolines reach the layers (RenderDoc, validation)
  // and the driver alike; null when the instance was created without the extension.
  ctx.debugUtils.setObjectName = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
      vkGetInstanceProcAddr(ctx.instance, "vkSetDebugUtilsObjectNameEXT"));
  ctx.debugUtils.cmdBeginLabel = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(ctx.instance, "vkCmdBeginDebugUtilsLabelEXT"));
  ctx.debugUtils.cmdEndLabel = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(ctx.instance, "vkCmdEndDebugUtilsLabelEXT"));
  if (!ctx.debugUtils.cmdBeginLabel || !ctx.debugUtils.cmdEndLabel)
    ctx.debugUtils.cmdBeginLabel = nullptr, ctx.debugUtils.cmdEndLabel = nullptr;  // both or neither
}

void setName(const GpuContext& ctx, uint64_t handle, VkObjectType type, const char* name) {
  if (!name || !handle || !ctx.debugUtils.setObjectName) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name;
  ctx.debugUtils.setObjectName(ctx.device, &info);
}

void beginLabel(const GpuContext& ctx, VkCommandBuffer cmd, const char* name) {
  if (!ctx.debugUtils.cmdBeginLabel) return;
  VkDebugUtilsLabelEXT label{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  label.pLabelName = name;
  ctx.debugUtils.cmdBeginLabel(cmd, &label);
}

void endLabel(const GpuContext& ctx, VkCommandBuffer cmd) {
  if (ctx.debugUtils.cmdEndLabel) ctx.debugUtils.cmdEndLabel(cmd);
}

}  // namespace gb
