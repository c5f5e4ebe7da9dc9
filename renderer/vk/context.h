// The Vulkan instance, the chosen physical device, one graphics+compute queue, and the
// validation messenger whose counts every test checks.
#pragma once
#include <vulkan/vulkan.h>

#include <atomic>
#include <mutex>
#include <string>
#include <vector>

namespace gb {

// Counts validation messages; tests fail when errors or warnings is non-zero.
struct ValidationLog {
  std::atomic<int> errors{0};
  std::atomic<int> warnings{0};
  std::mutex mutex;
  std::vector<std::string> messages;  // the text of every counted message
  bool echo = true;                   // also print each one to stderr
};
ValidationLog& validationLog();

struct ContextOptions {
  bool validation = false;     // --validate, or GBLENS_VALIDATE=1 in the environment (tests)
  std::string device;          // --device NAME|INDEX; empty: first discrete/integrated GPU, else CPU
  std::vector<std::string> instanceExtensions;  // e.g. the window system's (viewer)
  bool swapchain = false;      // enable VK_KHR_swapchain on the device
  bool quiet = false;          // do not print the chosen device
};

struct DeviceFeatures {
  bool rasterOrderAttachmentAccess = false;  // VK_EXT_rasterization_order_attachment_access
  bool lazilyAllocatedMemory = false;        // a memory type with LAZILY_ALLOCATED
  bool pipelineStatistics = false;
  bool depthClamp = false;
  bool fragmentStoresAndAtomics = false;
  bool timestamps = false;
  bool primitiveId = false;  // gl_PrimitiveID in fragment shaders (the geometryShader feature)
  bool float64 = false;      // shaderFloat64: light setup on the GPU computes in double
  // gbuffer_resolve (--gbuffer visibility): G-buffer stores through unsigned views without a format
  // qualifier (shaderStorageImageWriteWithoutFormat), gl_PrimitiveID (geometryShader).
  bool visibilityResolve = false;
  bool timelineSemaphore = false;  // Vulkan 1.2's (frames that overlap order their compute parts with one)
};

// VK_EXT_debug_utils entry points (renderer/vk/debug_utils.h); null when the instance lacks it.
struct DebugUtilsFunctions {
  PFN_vkSetDebugUtilsObjectNameEXT setObjectName = nullptr;
  PFN_vkCmdBeginDebugUtilsLabelEXT cmdBeginLabel = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT cmdEndLabel = nullptr;
};

struct GpuContext {
  VkInstance instance = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger = VK_NULL_HANDLE;
  VkPhysicalDevice physical = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;
  uint32_t queueFamily = 0;
  // A queue of a compute-only family, where the device has one with timestamps and GBLENS_OVERLAP
  // is not off (else `queue` again, its family and pool): frames whose visibility pass overlaps the
  // previous frame run their compute there (renderer/frame/side_queue.h). With two families every
  // buffer and image is shared by both (VK_SHARING_MODE_CONCURRENT: no ownership transfers).
  VkQueue computeQueue = VK_NULL_HANDLE;
  uint32_t computeFamily = 0;
  VkCommandPool computePool = VK_NULL_HANDLE;
  std::vector<uint32_t> sharedFamilies;  // both families when computeFamily != queueFamily, else empty
  VkCommandPool commandPool = VK_NULL_HANDLE;
  VkPhysicalDeviceProperties properties{};
  VkPhysicalDeviceMemoryProperties memory{};
  DeviceFeatures features;
  std::string deviceName;
  std::string driverName;  // driver name + info, e.g. "llvmpipe: Mesa 22.3.6 (LLVM 15.0.6)"
  bool isCpu = false;
  bool validation = false;
  PFN_vkCmdPushDescriptorSetKHR cmdPushDescriptorSet = nullptr;  // VK_KHR_push_descriptor
  DebugUtilsFunctions debugUtils;                                  // object names, label regions
};

// One line per physical device: "INDEX: NAME (type)". For --device help and errors.
std::vector<std::string> listDevices(VkInstance instance);

// Creates everything; on a user mistake (no such --device) prints one line and exits 2.
GpuContext createContext(const ContextOptions& options);
void destroyContext(GpuContext& ctx);

// Prints the validation summary line when messages were counted; returns their number.
int reportValidation(const GpuContext& ctx);

// True when GBLENS_VALIDATE is set to a non-zero value.
bool validationRequestedByEnvironment();

}  // namespace gb
